#pragma once
/// One frame's record of a sequence manifest (docs/sequences.md#manifest): a small JSON file
/// beside the frame's EXR (out/s.0007.exr -> out/s.0007.manifest.json), written atomically
/// after the EXR by the process that rendered it. One file per frame, so array tasks on
/// different nodes writing into one directory never lose each other's updates; the manifest
/// is the set of records, merged by its reader (sequence/sequence_verify.h).
#include "core/exr_io.h"
#include "scene/scene.h"
#include "scene/scene_loader.h"

#include <cstdint>
#include <string>

namespace kasumi {

struct FrameRecord {
    int64_t frame = 0;
    std::string file;        ///< the EXR's file name, in the record's directory
    std::string scene;       ///< the scene file as given
    std::string scene_hash;  ///< content hash of the frame's document (animation, --set applied)
    std::string settings;    ///< JSON text: resolution, spp, quality, seed, AOVs, compression
    uint64_t seed = 0;
    double render_seconds = 0.0;
    std::string host;      ///< the machine that rendered it
    std::string exr_hash;  ///< core/content_hash.h file_content_hash of the EXR as written
    std::string version;   ///< the kasumi that wrote it
};

/// The record of the frame written to `exr_path`: its ".exr" (if any) replaced by
/// ".manifest.json" (out/s.0007.exr -> out/s.0007.manifest.json, out/s.0007 ->
/// out/s.0007.manifest.json).
std::string frame_record_path(const std::string& exr_path);

/// Writes `record` to `path` as one JSON object, atomically; throws ErrorKind::Output.
void write_frame_record(const FrameRecord& record, const std::string& path);

/// Reads a record; throws ErrorKind::Input naming `path` and what is wrong.
FrameRecord read_frame_record(const std::string& path);

/// The settings a record keeps, as JSON text: the film's resolution, spp and pixel type, the
/// seed, render.quality and the volume estimator of the frame's document (or "none"), and the
/// EXR's AOV bits and compression, which are not in the document.
std::string frame_settings(const SceneDesc& desc, const Json& doc, uint32_t aovs,
                           ExrCompression compression);

/// This machine's host name ("unknown" if it has none).
std::string host_name();

}  // namespace kasumi
