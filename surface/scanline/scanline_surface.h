#pragma once
/// render.surface "scanline": the camera's visible surfaces from a scanline renderer of polygons
/// (Bouknight & Kelley 1970; Watkins 1970) instead of primary rays. The scanline pass
/// (scanline_shadows.h: edge table, active edge list, a span per polygon, depth per span
/// segment) gives the visible triangle at every pixel centre; across a run of pixels of one
/// triangle the hit is interpolated perspective-correctly: along a scanline the camera
/// direction d(X) is linear in the pixel coordinate X, and so are the Möller–Trumbore
/// numerators and denominator, det = −n·d, det·u = (e2 × s)·d, det·v = (s × e1)·d
/// (s = eye − v0, e1 = v1 − v0, e2 = v2 − v0; Möller & Trumbore 1997): the inverse depth
/// 1/t = det/((s × e1)·e2) and u/t, v/t are linear along the scanline and (t, u, v) are their
/// ratios. The hit is then built exactly as an Embree hit (SurfaceScene::hit_on_triangle).
///
/// Spheres are not polygons: each pixel's camera ray is cast against the spheres alone (their
/// own Embree scene) up to the scanline face, and the nearer wins. Only pixel centres are drawn
/// (the loader refuses film.jitter with render.surface "scanline").
#include "surface/scanline/scanline_shadows.h"
#include "surface/surface_scene.h"

#include <memory>
#include <optional>
#include <vector>

namespace kasumi {

class ScanlineSurface {
  public:
    /// `visibility`: a scanline pass over `shapes` through `camera` (render_scanline_visibility,
    /// or a light's render_scanline_shadows); `scene`: the shapes' Embree scene, which must
    /// outlive this object.
    ScanlineSurface(const std::vector<Shape>& shapes, ScanlineImage visibility,
                    const ScanlineCamera& camera, const SurfaceScene& scene);
    ~ScanlineSurface();

    /// The visible surface at the centres of pixels (x[i], y), i < count, seen along rays[i]
    /// (the camera rays through those centres: unit directions, origin at the eye): hits[i], or
    /// empty where nothing is seen. Thread-safe.
    void first_hits(int y, const int* x, const Ray* rays, size_t count,
                    std::optional<SurfaceHit>* hits) const;

    const ScanlineImage& visibility() const { return m_visibility; }

  private:
    /// One triangle's plane equations along one scanline: det(X), det·u(X), det·v(X) as
    /// (value at X = 0, slope per pixel), det·t constant (t per unit of d(X) = d0 + X d1).
    struct SpanPlane {
        uint32_t shape = 0, primitive = 0;
        int y = 0;
        DVec3 d0{0.0}, d1{0.0};
        glm::dvec2 det{0.0}, det_u{0.0}, det_v{0.0};
        double det_t = 0.0;
    };
    /// The plane equations of triangle (shape, primitive) along scanline y (empty: a sphere).
    std::optional<SpanPlane> span_plane(uint32_t shape, uint32_t primitive, int y) const;
    /// The hit at pixel centre (x + 0.5, y + 0.5), empty when behind the eye or edge on.
    std::optional<SurfaceHit> hit_at(const SpanPlane& plane, int x, const Ray& ray) const;

    ScanlineImage m_visibility;
    ScanlineCamera m_camera;
    const SurfaceScene* m_scene;
    std::unique_ptr<SurfaceScene> m_spheres;  ///< null when the scene has no spheres
    std::vector<uint32_t> m_sphere_shape;     ///< shape index of each sphere in m_spheres
};

}  // namespace kasumi
