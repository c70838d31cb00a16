#include "sequence/sequence_verify.h"

#include "core/content_hash.h"
#include "core/error.h"
#include "sequence/frame_record.h"
#include "sequence/sequence_cache.h"

#include <filesystem>

namespace kasumi {

const char* frame_status_name(FrameStatus status) {
    switch (status) {
        case FrameStatus::Ok:
            return "ok";
        case FrameStatus::Missing:
            return "missing";
        case FrameStatus::Stale:
            return "stale";
        case FrameStatus::Corrupt:
            return "corrupt";
        case FrameStatus::Unrecorded:
            return "unrecorded";
    }
    return "?";
}

std::vector<FrameCheck> verify_sequence(const SequenceOptions& options) {
    const SceneSource source(options.scene_path, options.overrides);
    SequenceCache cache;
    std::vector<FrameCheck> checks;
    for (const int64_t frame : options.frames) {
        FrameCheck check;
        check.frame = frame;
        const std::string path = frame_path(options.output_pattern, frame);
        const std::string record_path = frame_record_path(path);
        const auto verdict = [&](FrameStatus status, std::string detail) {
            check.status = status;
            check.detail = std::move(detail);
            checks.push_back(check);
        };
        if (!std::filesystem::exists(path)) {
            verdict(FrameStatus::Missing, path + ": no such file");
            continue;
        }
        if (!std::filesystem::exists(record_path)) {
            verdict(FrameStatus::Unrecorded, record_path + ": no record of " + path);
            continue;
        }
        FrameRecord record;
        std::string exr_hash;
        try {
            record = read_frame_record(record_path);
            exr_hash = file_content_hash(path);
        } catch (const Error& e) {
            verdict(FrameStatus::Corrupt, e.what());
            continue;
        }
        if (exr_hash != record.exr_hash) {
            verdict(FrameStatus::Corrupt, path + ": content " + exr_hash + ", recorded " +
                                              record.exr_hash + " (" + record.host + ")");
            continue;
        }
        const Json doc = std::move(source.frame_document(frame).json());
        const std::string scene_hash = text_content_hash(doc.dump());
        if (scene_hash != record.scene_hash) {
            verdict(FrameStatus::Stale, path +
                                            ": the scene changed since it was rendered "
                                            "(document " +
                                            scene_hash + ", recorded " + record.scene_hash + ")");
            continue;
        }
        const SceneDesc desc = source.parse(doc, frame, &cache);
        cache.end_frame();
        const std::string settings = frame_settings(desc, doc, options.aovs, options.compression);
        if (settings != record.settings) {
            verdict(FrameStatus::Stale,
                    path + ": settings " + settings + ", recorded " + record.settings);
            continue;
        }
        verdict(FrameStatus::Ok, "");
    }
    return checks;
}

}  // namespace kasumi
