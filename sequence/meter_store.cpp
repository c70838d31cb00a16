#include "sequence/meter_store.h"

#include "core/atomic_file.h"
#include "core/content_hash.h"
#include "core/error.h"
#include "core/json_text.h"
#include "core/module_loader.h"
#include "core/text_file.h"
#include "render/frame_output.h"
#include "sequence/auto_exposure.h"

#include <cstdio>
#include <filesystem>

namespace kasumi {

namespace fs = std::filesystem;

namespace {

/// Everything a metering depends on besides the document: the meter render's size and the
/// build that renders it (the content hash of the binary holding this code, so a rebuilt
/// renderer never reads an older one's meterings).
const std::string& meter_identity() {
    static const std::string identity = [] {
        std::string build = code_object_path();
        try {
            build = build.empty() ? std::string("unknown") : file_content_hash(build);
        } catch (const Error&) {
            build = "unknown";
        }
        return std::string(kKasumiVersion) + " " + build + "; meter " +
               std::to_string(kMeterWidth) + " px, " + std::to_string(kMeterSpp) + " spp";
    }();
    return identity;
}

}  // namespace

MeterStore::MeterStore(std::string dir) : m_dir(std::move(dir)) {}

std::string MeterStore::file_of(const std::string& document) const {
    std::string hash = text_content_hash(meter_identity() + "\n" + document);
    hash = hash.substr(hash.find(':') + 1);
    return (fs::path(m_dir) / (hash + ".json")).string();
}

std::optional<double> MeterStore::find(const std::string& document) const {
    if (m_dir.empty())
        return std::nullopt;
    const std::string path = file_of(document);
    std::error_code ec;
    if (!fs::is_regular_file(path, ec))
        return std::nullopt;
    try {
        const Json record = Json::parse(read_text_file(path, "metering"));
        if (record.value("meter", std::string()) != meter_identity() ||
            record.value("document_bytes", uint64_t{0}) != document.size() ||
            !record.contains("log2_luminance") || !record["log2_luminance"].is_number())
            return std::nullopt;
        return record["log2_luminance"].get<double>();
    } catch (const std::exception&) {
        return std::nullopt;  // unreadable or not JSON: a miss, replaced by put()
    }
}

std::string MeterStore::put(const std::string& document, double log2_luminance) const {
    if (m_dir.empty())
        return {};
    try {
        std::error_code ec;
        fs::create_directories(m_dir, ec);
        if (ec)
            return "cannot create " + m_dir + ": " + ec.message();
        char value[40];
        std::snprintf(value, sizeof value, "%.17g", log2_luminance);  // round-trips the double
        const std::string text = "{\"meter\": " + Json(meter_identity()).dump() +
                                 ", \"document_bytes\": " + std::to_string(document.size()) +
                                 ", \"log2_luminance\": " + value + "}\n";
        write_file_atomic(file_of(document), text.data(), text.size());
        return {};
    } catch (const Error& e) {
        return e.what();
    }
}

std::string meter_store_dir(const std::string& output_pattern) {
    const fs::path parent = fs::path(output_pattern).parent_path();
    return ((parent.empty() ? fs::path(".") : parent) / ".kasumi-meter").string();
}

}  // namespace kasumi
