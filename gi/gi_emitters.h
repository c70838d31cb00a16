#pragma once
/// Emissive surfaces as light sources for next-event estimation: every triangle of a quad, box
/// or mesh whose material emits, picked in proportion to its power and sampled uniformly in area.
#include "scene/scene.h"

#include <optional>
#include <vector>

namespace kasumi {

/// A point sampled on an emissive triangle.
struct EmitterSample {
    Vec3 position{0.0f};
    Vec3 normal{0.0f};      ///< unit front normal
    Rgb radiance{0.0f};     ///< cd/m², emitted from the front side
    float pdf_area = 0.0f;  ///< per m², the triangle pick times 1/area
};

class EmissiveTriangles {
  public:
    explicit EmissiveTriangles(const SceneDesc& scene);

    bool empty() const { return m_triangles.empty(); }
    /// One point: triangle by power (luminance × area), then uniform in its area. u in [0, 1)³.
    std::optional<EmitterSample> sample(float u_pick, Vec2 u) const;
    /// The area density (per m²) with which sample() picks a point on a triangle of a shape with
    /// emitted radiance `radiance`: luminance(radiance) / Σ luminance × area. Zero for shapes
    /// not sampled (spheres; is_sampled says which).
    float pdf_area(const Rgb& radiance) const;
    /// True if sample() can return points on shape `shape` (emissive, not a sphere).
    bool is_sampled(uint32_t shape) const;
    /// Σ luminance × area over the sampled triangles, cd/m² · m² (= flux / π, lm).
    float total_weight() const { return m_total; }

  private:
    struct Triangle {
        Vec3 p0, e1, e2;
        Vec3 normal;
        Rgb radiance;
    };
    std::vector<Triangle> m_triangles;
    std::vector<float> m_cdf;  ///< cumulative weights normalised to 1
    std::vector<bool> m_sampled_shape;
    float m_total = 0.0f;
};

}  // namespace kasumi
