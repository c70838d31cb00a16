#pragma once
/// The integral of a smooth function over the lit parts of an interval whose visibility is a
/// 0/1 step function, found by shadow rays (render.volume.shadow_intervals; docs/volumes.md).
/// Visibility is tested at K + 1 equally spaced points (the ends nudged inward by 1e-3 of the
/// spacing h, so a shadow ray does not start on the surface that ends the stretch); where two
/// neighbours disagree, bisection locates the boundary to 1/256 of [a, b]
/// (kShadowBoundaryResolution), taken at the middle of the last bracket. The lit parts are
/// then integrated exactly through the interpolant's antiderivative (gauss_interpolant.h).
/// Deterministic and biased; per ray the error is at most
///   - per boundary found, (b - a) / 512 times the largest value of P (mean ~0 over many
///     boundaries: the last bracket's midpoint);
///   - per run of light or shadow shorter than h that falls between two nodes and is missed
///     (both nodes agree), its length (< h) times the largest value of P there: a thin
///     occluder's shaft, or a thin gap in a shadow;
///   - plus the interpolant's own fit error (the unbiased estimator corrects it, this does not).
/// For the equiangular angle theta seen from a point light, the length of a shadow run in
/// theta is the chord cut from the occluder's angular disk as seen from the light by the
/// plane of the ray and the light, so an occluder subtending more than h from the light is
/// never missed by a ray that crosses its shadow through the middle; a ray grazing its shadow
/// can be.
#include "core/color.h"

namespace kasumi {

/// Each lit/shadow boundary is located by bisection to this fraction of [a, b]: 8
/// bisections for K = 1, 4 for K = 16, none from K = 256 on.
inline constexpr float kShadowBoundaryResolution = 1.0f / 256.0f;

/// ∫ over the lit parts of [a, b] of the interpolant p (GaussLegendreInterpolantN on [a, b]),
/// with `intervals` = K >= 1 equal parts; visible(theta) casts one shadow ray.
template <class Interpolant, class Visible>
Rgb lit_interval_integral(Interpolant& p, float a, float b, int intervals, Visible&& visible) {
    const float h = (b - a) / static_cast<float>(intervals);
    if (!(h > 0.0f))
        return Rgb(0.0f);
    const float nudge = 1e-3f * h;
    const float resolution = kShadowBoundaryResolution * (b - a);
    auto at = [&](int i) {
        if (i == 0)
            return a + nudge;
        if (i == intervals)
            return b - nudge;
        return a + h * static_cast<float>(i);
    };
    Rgb lit(0.0f);
    bool lit_before = visible(at(0));
    float run_start = a;  // start of the current run of equal visibility
    Rgb antiderivative_at_start(0.0f);
    for (int i = 1; i <= intervals; ++i) {
        const bool lit_here = visible(at(i));
        if (lit_here == lit_before)
            continue;
        // Boundary in (at(i - 1), at(i)): keep the bracket whose ends disagree.
        float lo = at(i - 1), hi = at(i);
        for (int level = 0; level < 24 && hi - lo > resolution; ++level) {
            const float mid = 0.5f * (lo + hi);
            if (visible(mid) == lit_before) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        const float boundary = 0.5f * (lo + hi);
        const Rgb antiderivative_at_boundary = p.integral_to(boundary);
        if (lit_before)
            lit += antiderivative_at_boundary - antiderivative_at_start;
        run_start = boundary;
        antiderivative_at_start = antiderivative_at_boundary;
        lit_before = lit_here;
    }
    if (lit_before)
        lit += run_start == a ? p.integral() : p.integral() - antiderivative_at_start;
    return lit;
}

}  // namespace kasumi
