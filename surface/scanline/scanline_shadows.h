#pragma once
/// The scanline method of shadows (Appel 1968, "Some techniques for shading machine renderings
/// of solids"; Bouknight & Kelley 1970, "An algorithm for producing half-tone computer
/// graphics presentations with shadows and movable light sources"): a scanline renderer of
/// polygons that, for the span of a visible face S1 on the current scanline, projects the
/// faces between S1 and the light onto S1's plane and intersects them with the scanline,
/// giving the shadowed sub-spans.
///
/// Visibility: the triangles of boxes, quads and meshes are clipped to the near plane and
/// projected; a polygon table sorted by first scanline ranks them, and their edges go into an
/// edge table sorted by first scanline feeding an active edge list (active_edge_list.h); on
/// each scanline every polygon crossing it gives a span (its active edges' x, stepped by dx/dy);
/// the spans' ends cut the scanline into segments, and depth is compared per segment: the
/// nearest face at both ends of a segment is the nearest over all of it, as inverse depth is
/// linear along the scanline (Watkins 1970), else the segment is halved. Shadows: the runs of
/// pixels won by one face are its visible spans; for each, every occluder that may shadow the
/// face (light-facing triangles of closed meshes, all of open ones; culled by their bounding
/// cones from the light, computed once per face and kept: Bouknight & Kelley's "shadow
/// pairs") is projected onto the face's plane (surface/shadows/shadow_projection.h), and each
/// edge line of the projection, pulled back along the scanline, is one linear inequality in
/// the pixel's x: the shadowed sub-span is an interval, exact, with no ray per pixel.
/// Analytic spheres are not drawn (they are not polygons; tessellating them is not done).
#include "core/math.h"
#include "surface/shadows/light_centre.h"
#include "surface/shape.h"

#include <cstdint>
#include <vector>

namespace kasumi {

/// A pinhole camera: pixel (x, y) (from the top left corner, pixel centres at + 0.5) looks
/// along forward + sx right + sy up with sx = (2x/w − 1) half_width and
/// sy = (1 − 2y/h) half_width h/w. Unit, orthonormal axes; world space, metres.
struct ScanlineCamera {
    Vec3 eye{0.0f}, forward{0.0f, 0.0f, -1.0f}, right{1.0f, 0.0f, 0.0f}, up{0.0f, 1.0f, 0.0f};
    double half_width = 1.0;  ///< tan of half the horizontal field of view
    int width = 0, height = 0;
};

/// Per pixel, row by row: the visible shape and its triangle (−1 where no polygon is seen)
/// and whether the light is hidden there (1) or not (0).
struct ScanlineImage {
    int width = 0, height = 0;
    std::vector<int32_t> shape, primitive;
    std::vector<uint8_t> shadowed;
    size_t spans = 0;              ///< visible spans shadowed by the method
    size_t shadow_pairs = 0;       ///< (face, occluder) pairs kept after culling
    size_t covered_pixels = 0;     ///< pixels inside some face's span (a Z-buffer's depth tests)
    size_t depth_evaluations = 0;  ///< pixels whose depths the per-span comparison evaluated
};

/// Renders the visibility and shadows of `shapes`' polygons for a point or parallel light.
/// Rows run in parallel bands of fixed rows (TBB, the caller's arena); the result is the same
/// for any number of threads.
ScanlineImage render_scanline_shadows(const std::vector<Shape>& shapes, const LightCentre& light,
                                      const ScanlineCamera& camera);

/// The visibility part of render_scanline_shadows alone (no light: `shadowed` stays 0 and no
/// shadow pairs are formed): render.surface "scanline" (scanline_surface.h).
ScanlineImage render_scanline_visibility(const std::vector<Shape>& shapes,
                                         const ScanlineCamera& camera);

}  // namespace kasumi
