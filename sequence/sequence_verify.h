#pragma once
/// `kasumi sequence --verify` (docs/sequences.md#manifest): checks every frame of a sequence
/// against its record (sequence/frame_record.h) and the scene as it is now, across all the
/// records the nodes of a farm wrote. Renders nothing.
#include "sequence/sequence.h"

#include <cstdint>
#include <string>
#include <vector>

namespace kasumi {

enum class FrameStatus {
    Ok,          ///< the EXR is the one recorded, for the scene and settings of now
    Missing,     ///< no EXR
    Stale,       ///< the scene document (after animation and --set) or the settings changed
    Corrupt,     ///< the EXR's bytes differ from the recorded hash, or the record is unreadable
    Unrecorded,  ///< an EXR without a record (written before manifests, or cut off after it)
};

/// "ok", "missing", "stale", "corrupt", "unrecorded".
const char* frame_status_name(FrameStatus status);

struct FrameCheck {
    int64_t frame = 0;
    FrameStatus status = FrameStatus::Ok;
    std::string detail;  ///< what differs, for a status other than ok
};

/// One check per frame of options.frames, in order. Uses scene_path, overrides, frames,
/// output_pattern, aovs and compression of `options`. Throws the input errors of the scene.
std::vector<FrameCheck> verify_sequence(const SequenceOptions& options);

}  // namespace kasumi
