#pragma once
/// Height fog: extinction falling off exponentially with height.
///
/// Model: sigma_{a,s}(x) = sigma_{a,s}(h0) * exp(-(h(x) - h0) / H), with h = x.y (the world up
/// axis: kasumi's scenes are y up, docs/scene-format.md, camera `up` default [0, 1, 0]), h0 the
/// reference height and H > 0 the scale height, both in metres; coefficients in 1/m. Optionally
/// confined to an axis-aligned box. Along a ray x(t) = o + t d (|d| = 1, t in metres) the
/// optical depth over [t0, t1] has the closed form
///   tau = sigma_t(h0) * H * (e^{-(h_a - h0)/H} - e^{-(h_b - h0)/H}) / d_y,
/// evaluated here as sigma_t(h0) * e^{-(h_low - h0)/H} * L * g(|d_y| L / H) with h_low the lower
/// end, L = t1 - t0 and g(x) = (1 - e^{-x}) / x = -expm1(-x) / x (g(0) = 1): no cancellation
/// for nearly horizontal rays and no overflow of the intermediate exponentials.
#include "core/bounds.h"
#include "core/color.h"
#include "phase/phase_function.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace kasumi {

/// Far below the reference height the point coefficients (trackers, march, scattering) are
/// capped where sigma_t reaches this, 1/m: the optical depth of a nanometre is then 1e11, so the
/// cap changes no transmittance a float can hold, and it keeps the trackers' majorants finite.
/// The closed-form optical depth is not capped.
inline constexpr double kHeightFogMaxSigmaT = 1e20;

struct HeightFogMedium {
    std::optional<Bounds3> bounds;
    Rgb sigma_a{0.0f};                ///< absorption coefficient at the reference height, 1/m
    Rgb sigma_s{0.0f};                ///< scattering coefficient at the reference height, 1/m
    double reference_height_m = 0.0;  ///< h0, on the y axis
    double scale_height_m = 1.0;      ///< H > 0
    PhaseFunction phase = Isotropic{};
    /// Most e-folds of density increase below h0 (kHeightFogMaxSigmaT); set by cap_density().
    double max_e_folds = 60.0;

    Rgb sigma_t() const { return sigma_a + sigma_s; }

    /// Sets max_e_folds from the coefficients (call after setting them).
    void cap_density() {
        const double s = max_component(sigma_t());
        max_e_folds = s > 0.0 ? std::clamp(std::log(kHeightFogMaxSigmaT / s), 0.0, 700.0) : 0.0;
    }

    /// exp(-(y - h0) / H) at height y, capped at exp(max_e_folds) (see above).
    double relative_density(double y) const {
        return std::exp(std::min(-(y - reference_height_m) / scale_height_m, max_e_folds));
    }
};

/// (1 - e^{-x}) / x for x >= 0 without cancellation; 1 at x = 0.
inline double one_minus_exp_over(double x) {
    return x > 0.0 ? -std::expm1(-x) / x : 1.0;
}

/// (1 - e^{-x}) / x for any x without cancellation (e^{|x|} / |x| for x -> -inf); 1 at x = 0.
inline double one_minus_exp_over_signed(double x) {
    return x != 0.0 ? -std::expm1(-x) / x : 1.0;
}

/// Integral of exp(-(y(t) - h0) / H) dt over [t0, t1] along a ray with origin height `oy` and
/// unit-direction y-component `dy` (metres; no density cap: the exact column). Returns +inf
/// for an infinite column (horizontal or descending ray without end).
inline double height_fog_column(const HeightFogMedium& m, double oy, double dy, double t0,
                                double t1) {
    if (!(t1 > t0))
        return 0.0;
    const double H = m.scale_height_m;
    const double ya = oy + dy * t0;
    const double L = t1 - t0;
    if (L >= static_cast<double>(kInfinity)) {  // a ray without end
        if (!(dy > 0.0))
            return HUGE_VAL;
        return std::exp(-(ya - m.reference_height_m) / H) * H / dy;  // e^{-a} H / d_y
    }
    const double y_low = dy >= 0.0 ? ya : oy + dy * t1;
    const double x = std::abs(dy) * L / H;
    return std::exp(-(y_low - m.reference_height_m) / H) * L * one_minus_exp_over(x);
}

/// Optical depth of the fog along [ray.t_min, ray.t_max] (clipped to its box), per channel,
/// exact; +inf where the column is infinite and the channel extinguishes, 0 where it does not.
inline Rgb height_fog_optical_depth(const HeightFogMedium& m, const Ray& ray) {
    double t0 = ray.t_min, t1 = ray.t_max;
    if (m.bounds) {
        const auto span = m.bounds->clip(ray);
        if (!span)
            return Rgb(0.0f);
        t0 = span->first;
        t1 = span->second;
    }
    const double column = height_fog_column(m, ray.origin.y, ray.direction.y, t0, t1);
    const Rgb sigma_t = m.sigma_t();
    Rgb tau(0.0f);
    for (int c = 0; c < 3; ++c) {
        if (sigma_t[c] > 0.0f && column > 0.0)
            tau[c] = static_cast<float>(std::min(double(sigma_t[c]) * column, 1e30));
    }
    return tau;
}

}  // namespace kasumi
