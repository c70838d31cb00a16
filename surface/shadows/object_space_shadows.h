#pragma once
/// Pass 2 of the object-space shadow method (Atherton, Weiler & Greenberg 1978): a visible
/// point is lit or not by the detail polygon of its face that contains it (surface/shadows/
/// shadow_polygons.h), found by a point-in-polygon test through a grid per face; no shadow
/// ray is traced for polygons. Spheres are not polygons: a point on a sphere takes a shadow ray
/// against the whole scene, and a point on a polygon one against the spheres alone (the stated
/// fallback, as for shadow volumes).
///
/// The detail polygons depend on the light and the geometry only, so a sequence whose frames
/// keep both reuses them (surface/shadows/shadow_polygon_cache.h).
#include "surface/shadows/light_centre.h"
#include "surface/shadows/polygon_grid.h"
#include "surface/shadows/shadow_polygons.h"
#include "surface/surface_scene.h"

#include <memory>
#include <vector>

namespace kasumi {

/// The detail polygons of one light, ready for point queries. Thread-safe after construction.
class ObjectSpaceShadows {
  public:
    /// `scene` (the shapes' Embree scene) must outlive this object.
    ObjectSpaceShadows(std::shared_ptr<const ShadowPolygons> polygons, const LightCentre& light,
                       const std::vector<Shape>& shapes, const SurfaceScene& scene);
    ~ObjectSpaceShadows();

    /// True when the light is hidden from the visible point `hit`; `origin` is the point offset
    /// off the surface toward the light (used by the sphere fallback's shadow rays).
    bool in_shadow(const SurfaceHit& hit, const Vec3& origin) const;

    const ShadowPolygons& polygons() const { return *m_polygons; }

  private:
    std::shared_ptr<const ShadowPolygons> m_polygons;
    LightCentre m_light;
    std::vector<std::vector<PolygonGrid>> m_grids;  ///< [shape][primitive], shadowed pieces
    const SurfaceScene* m_scene;
    std::unique_ptr<SurfaceScene> m_spheres;  ///< null when the scene has no spheres
};

/// Object-space shadows for every light of the scene with "shadows": "object-space" (others:
/// null). The detail polygons come from the process's cache when light and geometry match a
/// previous build.
class ObjectSpaceShadowSet {
  public:
    ObjectSpaceShadowSet(const std::vector<Shape>& shapes, const std::vector<Light>& lights,
                         const SurfaceScene& scene);
    const ObjectSpaceShadows* shadows(size_t light) const { return m_shadows[light].get(); }
    size_t reused() const { return m_reused; }  ///< lights whose polygons came from the cache

  private:
    std::vector<std::unique_ptr<ObjectSpaceShadows>> m_shadows;
    size_t m_reused = 0;
};

}  // namespace kasumi
