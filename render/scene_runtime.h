#pragma once
/// What the renderer builds from a scene description, stage by stage as the plan says: the
/// Embree scene only with shapes, the media only with media.
#include "core/camera.h"
#include "core/occlusion_query.h"
#include "render/gi_method.h"
#include "scene/plan.h"
#include "scene/scene.h"
#include "sky/sky_renderer.h"
#include "surface/scanline/scanline_shadow_set.h"
#include "surface/scanline/scanline_surface.h"
#include "surface/shadows/object_space_shadows.h"
#include "surface/shadows/shadow_map.h"
#include "surface/shadows/shadow_volume.h"
#include "surface/surface_scene.h"
#include "volume/medium_set.h"

#include <memory>

namespace kasumi {

/// Occlusion by the scene's surfaces for the volume and surface stages.
class SurfaceOcclusion final : public OcclusionQuery {
  public:
    explicit SurfaceOcclusion(const SurfaceScene& scene) : m_scene(scene) {}
    bool occluded(const Vec3& from, const Vec3& to) const override;
    bool occluded_direction(const Vec3& from, const Vec3& direction) const override;

  private:
    const SurfaceScene& m_scene;
};

/// Wall seconds spent building each part of a SceneRuntime; negative: not built by it (not
/// needed, or reused from an earlier frame of a sequence).
struct BuildTimes {
    double bvh_s = -1.0;             ///< Embree BVH of the shapes
    double shadow_maps_s = -1.0;     ///< depth maps rendered from the lights
    double shadow_volumes_s = -1.0;  ///< silhouettes extruded into volumes
    double object_space_s = -1.0;    ///< detail polygons clipped from the lights (or reused)
    double scanline_s = -1.0;  ///< scanline passes (visibility, shadowed sub-spans, the surface)
    double media_s = -1.0;     ///< the media set (majorants, overlaps)
    double sky_s = -1.0;       ///< the sky's tables (all, or the sun-dependent ones)
    double gi_s = -1.0;        ///< radiosity solve or photon maps
};

class SceneRuntime {
  public:
    /// Builds every stage the plan calls for, the GI method last by `make_gi` (gi/gi.h's
    /// make_gi_method; it sees the built surfaces, media and sky). Without `make_gi`, a scene
    /// whose render.gi is not "none" is an input error naming the scene file.
    explicit SceneRuntime(SceneDesc desc, const GiFactory& make_gi = nullptr);
    /// As above, but takes `surfaces` as the scene's BVH instead of building one when the plan
    /// needs it (null: build), and `sky_tables` as the sky's sun-independent tables (fast mode;
    /// null: build). The caller guarantees the BVH was built from the same desc.shapes and the
    /// tables for the same atmosphere, wavelengths and sun angular radius (sequence/sequence.h
    /// reuses both across the frames of a sequence).
    SceneRuntime(SceneDesc desc, std::shared_ptr<const SurfaceScene> surfaces,
                 std::shared_ptr<const SkyLuts> sky_tables, const GiFactory& make_gi);

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
    /// Visibility in [0, 1] of `light_point` (the light's position, or a sampled point on it)
    /// of light `light` from the surface point p (unit geometric normal n; `origin` is p offset
    /// off the surface toward the light; `wo` points toward the viewer) by the light's shadow
    /// maps, shadow volumes, detail polygons or scanline pass (the point is `hit`'s position,
    /// on its face); 1 for lights with other shadow modes.
    float staged_visibility(size_t light, const SurfaceHit& hit, const Vec3& n, const Vec3& origin,
                            const Vec3& light_point, const Vec3& wo) const;
    /// Null unless the plan has shadow maps (built once, with the runtime).
    const ShadowMapSet* shadow_maps() const { return m_shadow_maps.get(); }
    /// Null unless the plan has shadow volumes.
    const ShadowVolumeSet* shadow_volumes() const { return m_shadow_volumes.get(); }
    /// Null unless the plan has object-space shadows.
    const ObjectSpaceShadowSet* object_space_shadows() const { return m_object_space.get(); }
    /// Null unless the plan has scanline shadows.
    const ScanlineShadowSet* scanline_shadows() const { return m_scanline.get(); }
    /// The camera's visible surfaces by scanline; null unless render.surface is "scanline".
    const ScanlineSurface* scanline_surface() const { return m_scanline_surface.get(); }
    /// The render.gi method and its precomputation (render/gi_method.h); null for "none".
    const GiMethod* gi() const { return m_gi.get(); }
    /// Time spent building each part in the constructor.
    const BuildTimes& build_times() const { return m_build_times; }

  private:
    /// The scanline surface of render.surface "scanline" (after the scanline shadow passes).
    std::unique_ptr<ScanlineSurface> make_scanline_surface() const;

    SceneDesc m_desc;
    Plan m_plan;
    Camera m_camera;
    std::shared_ptr<const SurfaceScene> m_surfaces;
    std::unique_ptr<SurfaceOcclusion> m_occlusion;
    std::unique_ptr<ShadowMapSet> m_shadow_maps;
    std::unique_ptr<ShadowVolumeSet> m_shadow_volumes;
    std::unique_ptr<ObjectSpaceShadowSet> m_object_space;
    std::unique_ptr<ScanlineShadowSet> m_scanline;
    std::unique_ptr<ScanlineSurface> m_scanline_surface;
    MediumSet m_media;
    std::unique_ptr<SkyRenderer> m_sky;
    std::shared_ptr<const GiMethod> m_gi;
    BuildTimes m_build_times;
};

}  // namespace kasumi
