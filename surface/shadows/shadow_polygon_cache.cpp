#include "surface/shadows/shadow_polygon_cache.h"

#include "surface/shadows/welded_mesh.h"

#include <algorithm>
#include <cstring>
#include <deque>
#include <mutex>
#include <utility>

namespace kasumi {

namespace {

constexpr size_t kEntries = 8;

std::vector<float> key_of(const std::vector<Shape>& shapes, const LightCentre& light) {
    std::vector<float> key = {light.at_infinity ? 1.0f : 0.0f};
    const Vec3& c = light.at_infinity ? light.direction : light.position;
    key.insert(key.end(), {c.x, c.y, c.z});
    for (const Shape& shape : shapes) {
        // Spheres hold no detail polygons, but a shape turning into one shifts the indices.
        key.push_back(static_cast<float>(shape.geometry.index()));
        if (const auto mesh = welded_mesh(shape)) {
            key.push_back(static_cast<float>(mesh->triangles.size()));
            for (const auto& t : mesh->triangles)
                for (uint32_t i : t) {
                    const Vec3& p = mesh->positions[i];
                    key.insert(key.end(), {p.x, p.y, p.z});
                }
        }
    }
    return key;
}

/// Bitwise equality (so that -0 and +0 differ, and a NaN key never matches).
bool same_key(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](float x, float y) {
               return std::memcmp(&x, &y, sizeof(float)) == 0;
           });
}

struct Cache {
    std::mutex mutex;
    std::deque<std::pair<std::vector<float>, std::shared_ptr<const ShadowPolygons>>> entries;
};

Cache& cache() {
    static Cache c;
    return c;
}

}  // namespace

std::shared_ptr<const ShadowPolygons> cached_shadow_polygons(const std::vector<Shape>& shapes,
                                                             const LightCentre& light,
                                                             bool* reused) {
    std::vector<float> key = key_of(shapes, light);
    Cache& c = cache();
    {
        const std::lock_guard<std::mutex> lock(c.mutex);
        for (const auto& [k, polygons] : c.entries)
            if (same_key(k, key)) {
                if (reused != nullptr)
                    *reused = true;
                return polygons;
            }
    }
    // Built outside the lock: two threads missing at once both build (the same result).
    auto polygons = std::make_shared<const ShadowPolygons>(build_shadow_polygons(shapes, light));
    const std::lock_guard<std::mutex> lock(c.mutex);
    c.entries.emplace_front(std::move(key), polygons);
    if (c.entries.size() > kEntries)
        c.entries.pop_back();
    if (reused != nullptr)
        *reused = false;
    return polygons;
}

}  // namespace kasumi
