#pragma once
/// The scanline method as a render mode ("shadows": "scanline"): one scanline pass per light
/// (surface/scanline/scanline_shadows.h) at the film's resolution through the camera's pixel
/// centres, run once when the runtime is built; a visible point takes the pass's lit/unlit
/// answer when it is the camera's primary hit at a pixel centre.
///
/// Which points fall back to a shadow ray (toward the light's centre, against the whole scene):
/// points that do not project to within kPixelCentreTolerance of a pixel centre (jittered
/// camera samples, film.jitter true; secondary rays: Whitted reflections and refractions, GI,
/// volume paths), points whose shape and triangle are not the pass's visible face at that pixel
/// (a secondary hit on the ray of a pixel centre, spheres, a face the pass resolved otherwise),
/// and points on spheres. A point the pass answers lit also takes a shadow ray against the
/// scene's spheres alone (the pass draws no spheres), as object-space shadows do.
#include "core/camera.h"
#include "lights/light.h"
#include "surface/scanline/scanline_shadows.h"
#include "surface/surface_scene.h"

#include <memory>
#include <vector>

namespace kasumi {

/// Pixels: how far a point's projection may lie from a pixel centre and still be that pixel's
/// primary hit (float rounding of the camera ray and of the hit is ~1e-4 pixel at 4k).
constexpr double kPixelCentreTolerance = 1e-2;

/// The scanline camera of a kasumi pinhole camera (core/camera.h; vertical fov_deg).
ScanlineCamera scanline_camera(const CameraDesc& camera, int width, int height);

/// One light's scanline pass, ready for point queries. Thread-safe after construction.
class ScanlineShadows {
  public:
    /// `scene` (the shapes' Embree scene) must outlive this object.
    ScanlineShadows(const std::vector<Shape>& shapes, const LightCentre& light,
                    const ScanlineCamera& camera, const SurfaceScene& scene);
    ~ScanlineShadows();

    /// True when the light is hidden from the visible point `hit`; `origin` is the point offset
    /// off the surface toward the light (used by the fallback's shadow rays). `by_pass`, when
    /// given, is set to whether the pass answered (else a shadow ray did).
    bool in_shadow(const SurfaceHit& hit, const Vec3& origin, bool* by_pass = nullptr) const;

    const ScanlineImage& image() const { return m_image; }

  private:
    /// The pixel index whose centre `p` projects to, or −1.
    int64_t pixel_at_centre(const Vec3& p) const;

    ScanlineImage m_image;
    ScanlineCamera m_camera;
    LightCentre m_light;
    const SurfaceScene* m_scene;
    std::unique_ptr<SurfaceScene> m_spheres;  ///< null when the scene has no spheres
};

/// Scanline shadows for every light with "shadows": "scanline" (others: null).
class ScanlineShadowSet {
  public:
    ScanlineShadowSet(const std::vector<Shape>& shapes, const std::vector<Light>& lights,
                      const CameraDesc& camera, int width, int height, const SurfaceScene& scene);
    const ScanlineShadows* shadows(size_t light) const { return m_shadows[light].get(); }

  private:
    std::vector<std::unique_ptr<ScanlineShadows>> m_shadows;
};

}  // namespace kasumi
