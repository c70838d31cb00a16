#include "sequence/frame_record.h"

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/text_file.h"

#include <unistd.h>
#include <nlohmann/json.hpp>

namespace kasumi {

std::string frame_record_path(const std::string& exr_path) {
    // Not replace_extension: in a pattern without one ("out/s.####") the frame number would be
    // the extension, and every frame would share one record.
    const std::string suffix = ".exr";
    const bool has_suffix =
        exr_path.size() > suffix.size() &&
        exr_path.compare(exr_path.size() - suffix.size(), suffix.size(), suffix) == 0;
    return (has_suffix ? exr_path.substr(0, exr_path.size() - suffix.size()) : exr_path) +
           ".manifest.json";
}

void write_frame_record(const FrameRecord& r, const std::string& path) {
    const nlohmann::json json = {
        {"frame", r.frame},
        {"file", r.file},
        {"scene", r.scene},
        {"scene_hash", r.scene_hash},
        {"settings", nlohmann::json::parse(r.settings)},
        {"seed", r.seed},
        {"render_seconds", r.render_seconds},
        {"host", r.host},
        {"exr_hash", r.exr_hash},
        {"version", r.version},
    };
    const std::string text = json.dump(1) + "\n";
    write_file_atomic(path, text.data(), text.size());
}

FrameRecord read_frame_record(const std::string& path) {
    nlohmann::json json;
    try {
        json = nlohmann::json::parse(read_text_file(path, "frame record"));
        FrameRecord r;
        r.frame = json.at("frame").get<int64_t>();
        r.file = json.at("file").get<std::string>();
        r.scene = json.at("scene").get<std::string>();
        r.scene_hash = json.at("scene_hash").get<std::string>();
        r.settings = json.at("settings").dump();
        r.seed = json.at("seed").get<uint64_t>();
        r.render_seconds = json.at("render_seconds").get<double>();
        r.host = json.at("host").get<std::string>();
        r.exr_hash = json.at("exr_hash").get<std::string>();
        r.version = json.at("version").get<std::string>();
        return r;
    } catch (const nlohmann::json::exception& e) {
        throw_input_error(path + ": not a frame record: " + e.what());
    }
}

std::string frame_settings(const SceneDesc& desc, const Json& doc, uint32_t aovs,
                           ExrCompression compression) {
    const auto text_at = [&](const char* pointer) {
        const Json::json_pointer at(pointer);
        return doc.contains(at) && doc.at(at).is_string() ? doc.at(at).get<std::string>()
                                                          : std::string("none");
    };
    const nlohmann::json settings = {
        {"width", desc.film.width},
        {"height", desc.film.height},
        {"spp", desc.film.spp},
        {"pixel_type", static_cast<int>(desc.film.pixel_type)},
        {"seed", desc.render.seed},
        {"quality", text_at("/render/quality")},
        {"estimator", text_at("/render/volume/estimator")},
        {"aovs", aovs},
        {"compression", static_cast<int>(compression)},
    };
    return settings.dump();
}

std::string host_name() {
    char name[256] = {};
    if (::gethostname(name, sizeof name - 1) != 0 || name[0] == '\0')
        return "unknown";
    return name;
}

}  // namespace kasumi
