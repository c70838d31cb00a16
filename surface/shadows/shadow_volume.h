#pragma once
/// Shadow volumes of a point or parallel light (Crow 1977, "Shadow algorithms for computer
/// graphics"): the region an occluder hides from the light is bounded by the occluder's
/// light-facing triangles (near cap), quads extruded away from the light from its silhouette
/// edges (sides: along the rays from a point light, along the light's direction for a parallel
/// one) and the near cap pushed out beyond the scene (far cap). A point is in shadow when it lies
/// inside at least one volume, decided by counting the volume faces a ray crosses.
///
/// Counting: depth-fail ("z-fail", Carmack's reverse; Everitt & Kilgard 2002, "Practical and
/// robust stenciled shadow volumes"): along the eye ray continued beyond the point to infinity,
/// count +1 for each face left (outward normal along the ray) and −1 for each face entered.
/// Every volume is closed, so the count is the number of volumes containing the point whatever
/// the eye's position: an eye inside a shadow volume needs no correction, unlike depth-pass
/// counting from the eye (also provided, for comparison). The faces are intersected with a
/// separate Embree scene (surface/surface_scene.h), one closest hit after another.
///
/// Occluders: boxes and meshes (closed meshes contribute their light-facing triangles; open
/// meshes and quads every triangle turned to face the light, so that each still bounds a
/// closed volume). Analytic spheres have no silhouette edges: they are tested with shadow rays
/// instead (the documented fallback).
#include "core/bounds.h"
#include "core/math.h"
#include "lights/light.h"
#include "surface/shadows/light_centre.h"
#include "surface/shape.h"
#include "surface/surface_scene.h"

#include <array>
#include <memory>
#include <vector>

namespace kasumi {

/// The polygons of the shadow volumes, outward-facing (counter-clockwise seen from outside).
/// Coincident faces (a wall shared by two volumes at a fold of an open mesh, a cap modelled twice)
/// are stored once with a multiplicity: a ray crossing them at one t must count each.
struct ShadowVolumeGeometry {
    std::vector<std::array<Vec3, 3>> near_caps;
    std::vector<std::array<Vec3, 3>> far_caps;  ///< far_caps[i] closes near_caps[i]
    std::vector<int> cap_weights;               ///< multiplicity of near_caps[i] and far_caps[i]
    std::vector<std::array<Vec3, 4>> sides;     ///< a, a', b', b for silhouette edge a → b
    std::vector<int> side_weights;              ///< multiplicity of sides[i]
    size_t silhouette_edges = 0;
};

/// Builds the volumes of every box, quad and mesh in `shapes` for `light`. Far caps lie beyond
/// every point of the sphere (c, r) bounding `scene_bounds`: 2 (|light − c| + r) + 1 m from a
/// point light, 4 r + 1 m along the light's direction from each vertex for a parallel light.
ShadowVolumeGeometry build_shadow_volumes(const std::vector<Shape>& shapes,
                                          const LightCentre& light, const Bounds3& scene_bounds);

/// The volumes of one light, ready to count crossings. Thread-safe after construction.
class ShadowVolumes {
  public:
    ShadowVolumes(const std::vector<Shape>& shapes, const LightCentre& light,
                  const Bounds3& scene_bounds);
    ~ShadowVolumes();

    /// Depth-fail count at p: the number of volumes containing p, counted along the ray from p
    /// in `direction` (unit; the eye ray's direction) to infinity.
    int depth_fail_count(const Vec3& p, const Vec3& direction) const;
    /// Depth-pass count: faces entered minus faces left along the segment from `eye` to p.
    /// Equals depth_fail_count when the eye is in no volume.
    int depth_pass_count(const Vec3& eye, const Vec3& p) const;

    /// True when p is shadowed: inside a volume (depth-fail along `view_direction`), or a
    /// sphere blocks the segment from p to the light.
    bool in_shadow(const Vec3& p, const Vec3& view_direction) const;

    const ShadowVolumeGeometry& geometry() const { return m_geometry; }

  private:
    int count_crossings(const Ray& ray, float sign_of_exit) const;

    LightCentre m_light;
    ShadowVolumeGeometry m_geometry;
    /// The volume faces of one shape, with the multiplicity of each triangle.
    struct ShapeFaces {
        std::unique_ptr<SurfaceScene> scene;
        std::vector<int> weights;
        size_t max_crossings = 0;
    };
    std::vector<ShapeFaces> m_faces;          ///< shapes that cast a volume
    std::unique_ptr<SurfaceScene> m_spheres;  ///< null when the scene has no spheres
};

/// Volumes for every light of the scene with shadow-volume shadows (others: null).
class ShadowVolumeSet {
  public:
    ShadowVolumeSet(const std::vector<Shape>& shapes, const std::vector<Light>& lights,
                    const Bounds3& scene_bounds);
    const ShadowVolumes* volumes(size_t index) const { return m_volumes[index].get(); }

  private:
    std::vector<std::unique_ptr<ShadowVolumes>> m_volumes;
};

}  // namespace kasumi
