#include "sequence/sequence_cache.h"

#include "lights/light_json.h"
#include "volume/medium_json.h"

#include <cstdio>
#include <sstream>
#include <vector>

namespace kasumi {

namespace {

/// Everything a parse reads besides its node's text: the node's location (errors and default
/// names quote it) and the extra arguments.
std::string element_key(const JsonNode& node, const std::string& extra) {
    return node.file() + '\n' + node.pointer() + '\n' + extra + '\n' + node.value().dump();
}

template <typename Map, typename Parse>
auto lookup(Map& map, const std::string& key, uint64_t frame, bool enabled, uint64_t& parsed,
            uint64_t& reused, bool& was_reused, Parse parse) {
    if (enabled) {
        const auto it = map.find(key);
        if (it != map.end()) {
            it->second.last_used = frame;
            ++reused;
            was_reused = true;
            return it->second.value;
        }
    }
    auto value = parse();
    ++parsed;
    was_reused = false;
    if (enabled)
        map[key] = {value, frame};
    return value;
}

template <typename Map>
void sweep(Map& map, uint64_t frame) {
    for (auto it = map.begin(); it != map.end();) {
        if (it->second.last_used < frame) {
            it = map.erase(it);
        } else {
            ++it;
        }
    }
}

void append(std::vector<std::string>& out, uint64_t n, const char* one, const char* many) {
    if (n == 1)
        out.push_back(std::string("1 ") + one);
    else if (n > 1)
        out.push_back(std::to_string(n) + " " + many);
}

std::string join(const std::vector<std::string>& items) {
    if (items.empty())
        return "-";
    std::string text;
    for (size_t i = 0; i < items.size(); ++i)
        text += (i ? ", " : "") + items[i];
    return text;
}

}  // namespace

ReuseCounts& ReuseCounts::operator+=(const ReuseCounts& o) {
    shapes_parsed += o.shapes_parsed;
    shapes_reused += o.shapes_reused;
    meshes_loaded += o.meshes_loaded;
    meshes_reused += o.meshes_reused;
    lights_parsed += o.lights_parsed;
    lights_reused += o.lights_reused;
    ies_loaded += o.ies_loaded;
    ies_reused += o.ies_reused;
    media_parsed += o.media_parsed;
    media_reused += o.media_reused;
    grids_loaded += o.grids_loaded;
    grids_reused += o.grids_reused;
    bvh_built += o.bvh_built;
    bvh_reused += o.bvh_reused;
    sky_tables_built += o.sky_tables_built;
    sky_tables_reused += o.sky_tables_reused;
    return *this;
}

std::string reuse_text(const ReuseCounts& c) {
    // One side of the log line: the whole structures, then the parts that carry a file (meshes,
    // IES profiles, grids) and the rest of each kind.
    auto side = [](uint64_t bvh, uint64_t sky_tables, uint64_t meshes, uint64_t ies, uint64_t grids,
                   uint64_t shapes, uint64_t lights, uint64_t media) {
        std::vector<std::string> items;
        if (bvh > 0)
            items.push_back("bvh");
        if (sky_tables > 0)
            items.push_back("sky tables");
        append(items, meshes, "mesh", "meshes");
        append(items, ies, "IES profile", "IES profiles");
        append(items, grids, "grid", "grids");
        append(items, shapes - meshes, "other shape", "other shapes");
        append(items, lights - ies, "other light", "other lights");
        append(items, media - grids, "other medium", "other media");
        return join(items);
    };
    return "reused " +
           side(c.bvh_reused, c.sky_tables_reused, c.meshes_reused, c.ies_reused, c.grids_reused,
                c.shapes_reused, c.lights_reused, c.media_reused) +
           "; built " +
           side(c.bvh_built, c.sky_tables_built, c.meshes_loaded, c.ies_loaded, c.grids_loaded,
                c.shapes_parsed, c.lights_parsed, c.media_parsed);
}

Shape SequenceCache::shape(const JsonNode& node, const std::map<std::string, uint32_t>& materials,
                           const std::string& base_dir) {
    std::ostringstream extra;
    extra << base_dir;
    for (const auto& [name, index] : materials)
        extra << '\n' << index << '=' << name;
    bool was_reused = false;
    Shape s = lookup(m_shapes, element_key(node, extra.str()), m_frame, m_enabled,
                     m_counts.shapes_parsed, m_counts.shapes_reused, was_reused,
                     [&] { return parse_shape(node, materials, base_dir); });
    if (std::holds_alternative<MeshShape>(s.geometry))
        ++(was_reused ? m_counts.meshes_reused : m_counts.meshes_loaded);
    return s;
}

Light SequenceCache::light(const JsonNode& node, size_t index) {
    bool was_reused = false;
    Light l = lookup(m_lights, element_key(node, std::to_string(index)), m_frame, m_enabled,
                     m_counts.lights_parsed, m_counts.lights_reused, was_reused,
                     [&] { return parse_light(node, index); });
    if (std::holds_alternative<GoniometricLight>(l.emitter))
        ++(was_reused ? m_counts.ies_reused : m_counts.ies_loaded);
    return l;
}

Medium SequenceCache::medium(const JsonNode& node, size_t index, const std::string& base_dir) {
    bool was_reused = false;
    Medium m = lookup(m_media, element_key(node, std::to_string(index) + '\n' + base_dir), m_frame,
                      m_enabled, m_counts.media_parsed, m_counts.media_reused, was_reused,
                      [&] { return parse_medium(node, index, base_dir); });
    if (std::holds_alternative<VdbMedium>(m.model))
        ++(was_reused ? m_counts.grids_reused : m_counts.grids_loaded);
    return m;
}

std::shared_ptr<const SurfaceScene> SequenceCache::surfaces(const std::string& key) {
    if (!m_enabled || !m_bvh || key != m_bvh_key)
        return nullptr;
    ++m_counts.bvh_reused;
    return m_bvh;
}

void SequenceCache::remember_surfaces(const std::string& key,
                                      std::shared_ptr<const SurfaceScene> bvh) {
    if (!m_enabled)
        return;
    m_bvh_key = key;
    m_bvh = std::move(bvh);
}

std::shared_ptr<const SkyLuts> SequenceCache::sky_tables(const std::string& key) {
    if (!m_enabled || !m_sky_tables || key.empty() || key != m_sky_key)
        return nullptr;
    ++m_counts.sky_tables_reused;
    return m_sky_tables;
}

void SequenceCache::remember_sky_tables(const std::string& key,
                                        std::shared_ptr<const SkyLuts> tables) {
    if (!m_enabled || key.empty())
        return;
    m_sky_key = key;
    m_sky_tables = std::move(tables);
}

ReuseCounts SequenceCache::end_frame() {
    sweep(m_shapes, m_frame);
    sweep(m_lights, m_frame);
    sweep(m_media, m_frame);
    ++m_frame;
    const ReuseCounts frame = m_counts;
    m_total += frame;
    m_counts = ReuseCounts{};
    return frame;
}

std::string bvh_key(const Json& frame_doc) {
    std::string key;
    if (frame_doc.contains("shapes"))
        key = frame_doc["shapes"].dump();
    if (frame_doc.contains("materials") && frame_doc["materials"].is_object()) {
        for (const auto& item : frame_doc["materials"].items())
            key += '\n' + item.key();
    }
    return key;
}

std::string sky_tables_key(const Json& frame_doc, const std::string& scene_path,
                           const SkyScene* sky) {
    if (sky == nullptr || sky->settings.mode != SkyMode::Fast || !frame_doc.contains("atmosphere"))
        return std::string();
    std::string key = scene_path + '\n' + frame_doc["atmosphere"].dump() + "\nnm";
    // Exact values (hexadecimal floats): a key that differs in the last bit builds new tables.
    char buffer[64];
    for (const double nm : sky->atmosphere.wavelengths_nm) {
        std::snprintf(buffer, sizeof buffer, " %a", nm);
        key += buffer;
    }
    key += "\nrgb nm";  // RGB-given coefficients are placed at these in spectral mode
    for (const double nm : sky->settings.rgb_wavelengths_nm) {
        std::snprintf(buffer, sizeof buffer, " %a", nm);
        key += buffer;
    }
    std::snprintf(buffer, sizeof buffer, "\nsun radius %a rad", sky->sun_radius_rad);
    key += buffer;
    return key;
}

}  // namespace kasumi
