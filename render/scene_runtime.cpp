#include "render/scene_runtime.h"

#include "core/error.h"
#include "scene/gi_plan.h"

#include <algorithm>
#include <chrono>

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

float SceneRuntime::staged_visibility(size_t light, const SurfaceHit& hit, const Vec3& n,
                                      const Vec3& origin, const Vec3& light_point,
                                      const Vec3& wo) const {
    const Vec3& p = hit.position;
    if (m_shadow_maps != nullptr) {
        if (const LightShadowMaps* maps = m_shadow_maps->maps(light))
            return maps->visibility(p, n, light_point);
    }
    if (m_shadow_volumes != nullptr) {
        // Depth-fail counting along the eye ray continued beyond the point.
        if (const ShadowVolumes* volumes = m_shadow_volumes->volumes(light))
            return volumes->in_shadow(origin, -wo) ? 0.0f : 1.0f;
    }
    if (m_object_space != nullptr) {
        if (const ObjectSpaceShadows* shadows = m_object_space->shadows(light))
            return shadows->in_shadow(hit, origin) ? 0.0f : 1.0f;
    }
    if (m_scanline != nullptr) {
        if (const ScanlineShadows* shadows = m_scanline->shadows(light))
            return shadows->in_shadow(hit, origin) ? 0.0f : 1.0f;
    }
    return 1.0f;
}

std::unique_ptr<ScanlineSurface> SceneRuntime::make_scanline_surface() const {
    const ScanlineCamera view =
        scanline_camera(m_desc.camera, m_desc.film.width, m_desc.film.height);
    // A light's scanline shadow pass has already resolved the same visibility: reuse it.
    ScanlineImage visibility;
    const ScanlineShadows* pass = nullptr;
    for (size_t i = 0; m_scanline != nullptr && i < m_desc.lights.size() && pass == nullptr; ++i)
        pass = m_scanline->shadows(i);
    if (pass != nullptr)
        visibility = pass->image();
    else
        visibility = render_scanline_visibility(m_desc.shapes, view);
    return std::make_unique<ScanlineSurface>(m_desc.shapes, std::move(visibility), view,
                                             *m_surfaces);
}

SceneRuntime::SceneRuntime(SceneDesc desc, const GiFactory& make_gi)
    : SceneRuntime(std::move(desc), nullptr, nullptr, make_gi) {}

SceneRuntime::SceneRuntime(SceneDesc desc, std::shared_ptr<const SurfaceScene> surfaces,
                           std::shared_ptr<const SkyLuts> sky_tables, const GiFactory& make_gi)
    : m_desc(std::move(desc)),
      m_plan(make_plan(m_desc)),
      m_camera(m_desc.camera, m_desc.film.width, m_desc.film.height) {
    using Clock = std::chrono::steady_clock;
    auto since = [](Clock::time_point start) {
        return std::chrono::duration<double>(Clock::now() - start).count();
    };
    if (m_plan.surfaces) {
        const auto start = Clock::now();
        const bool build = surfaces == nullptr;
        m_surfaces = build ? std::make_shared<SurfaceScene>(m_desc.shapes) : std::move(surfaces);
        if (build)
            m_build_times.bvh_s = since(start);
    }
    if (m_plan.shadow_rays)
        m_occlusion = std::make_unique<SurfaceOcclusion>(*m_surfaces);
    if (m_plan.shadow_maps) {
        const auto start = Clock::now();
        m_shadow_maps = std::make_unique<ShadowMapSet>(m_desc.lights, *m_surfaces);
        m_build_times.shadow_maps_s = since(start);
    }
    if (m_plan.shadow_volumes) {
        const auto start = Clock::now();
        m_shadow_volumes =
            std::make_unique<ShadowVolumeSet>(m_desc.shapes, m_desc.lights, m_surfaces->bounds());
        m_build_times.shadow_volumes_s = since(start);
    }
    if (m_plan.object_space_shadows) {
        const auto start = Clock::now();
        m_object_space =
            std::make_unique<ObjectSpaceShadowSet>(m_desc.shapes, m_desc.lights, *m_surfaces);
        m_build_times.object_space_s = since(start);
    }
    if (m_plan.scanline_shadows) {
        const auto start = Clock::now();
        m_scanline =
            std::make_unique<ScanlineShadowSet>(m_desc.shapes, m_desc.lights, m_desc.camera,
                                                m_desc.film.width, m_desc.film.height, *m_surfaces);
        m_build_times.scanline_s = since(start);
    }
    if (m_plan.scanline_surface) {
        const auto start = Clock::now();
        m_scanline_surface = make_scanline_surface();
        m_build_times.scanline_s = std::max(0.0, m_build_times.scanline_s) + since(start);
    }
    if (m_plan.volume) {
        const auto start = Clock::now();
        m_media = MediumSet(m_desc.media);
        m_media.set_stochastic_filter(m_desc.render.volume.stochastic_filter);
        m_build_times.media_s = since(start);
    }
    if (m_desc.sky) {
        const auto start = Clock::now();
        m_sky = std::make_unique<SkyRenderer>(
            m_desc.sky, m_desc.camera.position, std::move(sky_tables),
            make_view_frustum(m_camera, m_desc.film.width, m_desc.film.height));
        m_build_times.sky_s = since(start);
    }
    if (m_desc.render.gi != GiMode::None) {
        if (!make_gi)
            throw_input_error(m_desc.file + ": render.gi = " + gi_mode_name(m_desc.render.gi) +
                              ": this program was built without global illumination");
        const auto start = Clock::now();
        m_gi = make_gi(*this);
        if (m_gi)
            m_build_times.gi_s = since(start);
    }
    if (m_gi)
        add_gi_summary(m_plan, m_gi->summary());
}

}  // namespace kasumi
