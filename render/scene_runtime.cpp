#include "render/scene_runtime.h"

#include "render/gi.h"
#include "render/gi_plan.h"
namespace kasumi {

bool SurfaceOcclusion::occluded(const Vec3& from, const Vec3& to) const {
    const Vec3 d = to - from;
    const float distance = glm::length(d);
    if (!(distance > 0.0f))
        return false;
    // Stop just short of the end point so a light sitting on a surface is not self-blocked.
    return m_scene.occluded(Ray{from, d / distance, 0.0f, distance * (1.0f - 1e-5f)});
}

bool SurfaceOcclusion::occluded_direction(const Vec3& from, const Vec3& direction) const {
    return m_scene.occluded(Ray{from, direction, 0.0f, kInfinity});
}

SceneRuntime::SceneRuntime(SceneDesc desc) : SceneRuntime(std::move(desc), nullptr) {}

SceneRuntime::SceneRuntime(SceneDesc desc, std::shared_ptr<const SurfaceScene> surfaces)
    : m_desc(std::move(desc)),
      m_plan(make_plan(m_desc)),
      m_camera(m_desc.camera, m_desc.film.width, m_desc.film.height) {
    if (m_plan.surfaces) {
        m_surfaces =
            surfaces ? std::move(surfaces) : std::make_shared<SurfaceScene>(m_desc.shapes);
    }
    if (m_plan.shadow_rays)
        m_occlusion = std::make_unique<SurfaceOcclusion>(*m_surfaces);
    if (m_plan.volume)
        m_media = MediumSet(m_desc.media);
    if (m_desc.sky)
        m_sky = std::make_unique<SkyRenderer>(m_desc.sky, m_desc.camera.position);
    m_gi = make_gi_method(*this);
    if (m_gi)
        add_gi_summary(m_plan, *m_gi);
}

}  // namespace kasumi
