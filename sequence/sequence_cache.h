#pragma once
/// Work kept across the frames of a sequence: parsed shapes (meshes read from OBJ files), lights
/// (IES profiles) and media (VDB grids turned into brick grids), each keyed by the JSON text it
/// was parsed from plus everything else its parse depends on, and the BVH keyed by the JSON text
/// of all shapes and the material names, and the sky's sun-independent tables keyed by the JSON
/// text of the atmosphere plus the wavelengths and the sun's angular radius. A frame re-reads
/// only what its document changed.
#include "scene/scene_loader.h"
#include "sky/sky_luts.h"
#include "surface/surface_scene.h"

#include <cstdint>
#include <map>
#include <memory>
#include <string>

namespace kasumi {

/// How often each kind of work was done or taken from the cache.
struct ReuseCounts {
    uint64_t shapes_parsed = 0, shapes_reused = 0;
    uint64_t meshes_loaded = 0, meshes_reused = 0;  ///< the subset of shapes that are OBJ meshes
    uint64_t lights_parsed = 0, lights_reused = 0;
    uint64_t ies_loaded = 0, ies_reused = 0;  ///< the subset of lights with an IES profile
    uint64_t media_parsed = 0, media_reused = 0;
    uint64_t grids_loaded = 0, grids_reused = 0;  ///< the subset of media that are VDB grids
    uint64_t bvh_built = 0, bvh_reused = 0;
    uint64_t sky_tables_built = 0, sky_tables_reused = 0;  ///< transmittance + multiple scattering

    ReuseCounts& operator+=(const ReuseCounts& o);
};

/// "reused bvh, 3 meshes; built -" style text for a frame's log line.
std::string reuse_text(const ReuseCounts& c);

class SequenceCache final : public ElementCache {
  public:
    /// `enabled` false: parse and build everything every frame (for measuring what reuse saves).
    explicit SequenceCache(bool enabled = true) : m_enabled(enabled) {}

    Shape shape(const JsonNode& node, const std::map<std::string, uint32_t>& materials,
                const std::string& base_dir) override;
    Light light(const JsonNode& node, size_t index) override;
    Medium medium(const JsonNode& node, size_t index, const std::string& base_dir) override;

    /// The BVH remembered under `key` (see bvh_key), or null.
    std::shared_ptr<const SurfaceScene> surfaces(const std::string& key);
    void remember_surfaces(const std::string& key, std::shared_ptr<const SurfaceScene> bvh);
    /// Counts a BVH built for a frame (with or without remembering it).
    void count_bvh_built() { ++m_counts.bvh_built; }

    /// The sky's sun-independent tables remembered under `key` (see sky_tables_key), or null.
    std::shared_ptr<const SkyLuts> sky_tables(const std::string& key);
    void remember_sky_tables(const std::string& key, std::shared_ptr<const SkyLuts> tables);
    /// Counts sky tables built for a frame (with or without remembering them).
    void count_sky_tables_built() { ++m_counts.sky_tables_built; }

    /// Forgets entries the frame just finished did not use (animated values would otherwise
    /// pile up) and returns that frame's counts.
    ReuseCounts end_frame();
    const ReuseCounts& total() const { return m_total; }

  private:
    template <typename T>
    struct Entry {
        T value;
        uint64_t last_used = 0;
    };

    bool m_enabled;
    uint64_t m_frame = 1;
    std::map<std::string, Entry<Shape>> m_shapes;
    std::map<std::string, Entry<Light>> m_lights;
    std::map<std::string, Entry<Medium>> m_media;
    std::string m_bvh_key;
    std::shared_ptr<const SurfaceScene> m_bvh;
    std::string m_sky_key;
    std::shared_ptr<const SkyLuts> m_sky_tables;
    ReuseCounts m_counts, m_total;
};

/// The key a frame's BVH is cached under: the JSON text of the document's "shapes" and its
/// material names (shapes refer to materials by index in name order).
std::string bvh_key(const Json& frame_doc);

/// The key a frame's sky tables are cached under: the JSON text of the document's "atmosphere"
/// (and the scene file, which resolves its tables), the wavelengths the render transports and
/// the sun's angular radius (the multiple-scattering table integrates the sun's disc above the
/// horizon); everything the tables depend on. Empty (do not cache) without fast-mode sky.
std::string sky_tables_key(const Json& frame_doc, const std::string& scene_path,
                           const SkyScene* sky);

}  // namespace kasumi
