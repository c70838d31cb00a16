#include "surface/shadows/object_space_shadows.h"

#include "surface/shadows/shadow_polygon_cache.h"
#include "surface/shadows/sphere_shadow_rays.h"

namespace kasumi {

ObjectSpaceShadows::ObjectSpaceShadows(std::shared_ptr<const ShadowPolygons> polygons,
                                       const LightCentre& light, const std::vector<Shape>& shapes,
                                       const SurfaceScene& scene)
    : m_polygons(std::move(polygons)), m_light(light), m_scene(&scene) {
    m_grids.resize(m_polygons->faces.size());
    for (size_t s = 0; s < m_polygons->faces.size(); ++s)
        for (const FaceDetail& face : m_polygons->faces[s])
            m_grids[s].emplace_back(face.shadowed);
    m_spheres = sphere_scene(shapes);
}

ObjectSpaceShadows::~ObjectSpaceShadows() = default;

bool ObjectSpaceShadows::in_shadow(const SurfaceHit& hit, const Vec3& origin) const {
    const std::vector<std::vector<FaceDetail>>& faces = m_polygons->faces;
    if (hit.shape >= faces.size() || hit.primitive >= faces[hit.shape].size())
        return shadow_ray_blocked(*m_scene, origin, m_light);  // a sphere: not a polygon
    const FaceDetail& face = faces[hit.shape][hit.primitive];
    if (!face.faces_light)
        return true;
    if (m_grids[hit.shape][hit.primitive].contains(to_frame(face.frame, DVec3(hit.position))))
        return true;
    return m_spheres != nullptr && shadow_ray_blocked(*m_spheres, origin, m_light);
}

ObjectSpaceShadowSet::ObjectSpaceShadowSet(const std::vector<Shape>& shapes,
                                           const std::vector<Light>& lights,
                                           const SurfaceScene& scene) {
    for (const Light& light : lights) {
        if (light.shadows != ShadowMode::ObjectSpace) {
            m_shadows.push_back(nullptr);
            continue;
        }
        const LightCentre centre = light_centre(light);
        bool reused = false;
        auto polygons = cached_shadow_polygons(shapes, centre, &reused);
        m_reused += reused ? 1 : 0;
        m_shadows.push_back(
            std::make_unique<ObjectSpaceShadows>(std::move(polygons), centre, shapes, scene));
    }
}

}  // namespace kasumi
