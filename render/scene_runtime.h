#pragma once
/// What the renderer builds from a scene description, stage by stage as the plan says: the
/// Embree scene only with shapes, the media only with media.
#include "core/camera.h"
#include "core/scene_queries.h"
#include "render/plan.h"
#include "render/scene.h"
#include "surface/surface_scene.h"
#include "volume/medium_set.h"
#include "volume/sky_renderer.h"

#include <memory>

namespace kasumi {

class GiMethod;

/// Occlusion by the scene's surfaces for the volume and surface stages.
class SurfaceOcclusion final : public OcclusionQuery {
  public:
    explicit SurfaceOcclusion(const SurfaceScene& scene) : m_scene(scene) {}
    bool occluded(const Vec3& from, const Vec3& to) const override;
    bool occluded_direction(const Vec3& from, const Vec3& direction) const override;

  private:
    const SurfaceScene& m_scene;
};

class SceneRuntime {
  public:
    explicit SceneRuntime(SceneDesc desc);
    /// As above, but takes `surfaces` as the scene's BVH instead of building one when the plan
    /// needs it (null: build). The caller guarantees it was built from the same desc.shapes
    /// (render/sequence.h reuses one across the frames of a sequence).
    SceneRuntime(SceneDesc desc, std::shared_ptr<const SurfaceScene> surfaces);

    const SceneDesc& desc() const { return m_desc; }
    const Plan& plan() const { return m_plan; }
    const Camera& camera() const { return m_camera; }
    const SurfaceScene* surfaces() const { return m_surfaces.get(); }
    std::shared_ptr<const SurfaceScene> shared_surfaces() const { return m_surfaces; }
    const MediumSet& media() const { return m_media; }
    /// The sky (atmosphere, sun, tables); null without an atmosphere.
    const SkyRenderer* sky() const { return m_sky.get(); }
    /// Null when the plan has no shadow rays.
    const OcclusionQuery* occlusion() const { return m_occlusion.get(); }
    /// The render.gi method and its precomputation (render/gi.h); null for "none".
    const GiMethod* gi() const { return m_gi.get(); }

  private:
    SceneDesc m_desc;
    Plan m_plan;
    Camera m_camera;
    std::shared_ptr<const SurfaceScene> m_surfaces;
    std::unique_ptr<SurfaceOcclusion> m_occlusion;
    MediumSet m_media;
    std::unique_ptr<SkyRenderer> m_sky;
    std::shared_ptr<const GiMethod> m_gi;
};

}  // namespace kasumi
