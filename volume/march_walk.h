#pragma once
/// The fixed-step walk shared by the `march` transmittance estimator and marched single
/// scattering: nodes t_min + (u + i) h on a grid with one random offset u per ray, plus every
/// majorant segment's ends (empty space between segments contributes nothing); the optical
/// depth accumulates by the trapezoid rule between consecutive nodes.
#include "volume/in_scattering.h"
#include "volume/medium_set.h"

#include <cmath>

namespace kasumi {

/// Calls visit(t, x, coefficients, media_mask, tau) at every grid node inside a segment, with tau
/// the optical depth from t_min to t (double, per channel); visit returns false to stop the walk.
/// Returns the optical depth over the walked part (all of it unless visit stopped it).
/// With `skip_constant`, segments whose majorant equals their minorant (constant coefficients)
/// add sigma * length at once without nodes: the trapezoid rule is exact there anyway.
template <class Visit>
glm::dvec3 march_walk(const MediumSet& media, const Ray& ray, float h, float u,
                      const std::vector<MajorantSegment>& segments, bool skip_constant,
                      VolumeCounters& counters, Visit&& visit) {
    glm::dvec3 tau(0.0);
    const RayMediaQuery query(media, ray);
    for (const MajorantSegment& s : segments) {
        if (!(s.t1 < kInfinity)) {
            // An endless stretch: infinite depth in every channel whose extinction is bounded
            // away from zero; the others are left as walked (a tail of zero extinction).
            for (int c = 0; c < 3; ++c)
                if (s.sigma_min[c] > 0.0f)
                    tau[c] = HUGE_VAL;
            return tau;
        }
        if (skip_constant && s.sigma_max == s.sigma_min) {
            tau += static_cast<double>(s.t1 - s.t0) * glm::dvec3(s.sigma_max);
            continue;
        }
        // Ends are evaluated a hair inside so a homogeneous box's face does not round outside.
        const float inset = 1e-6f * (s.t1 - s.t0);
        float t_prev = s.t0;
        Rgb sigma_prev = query.coefficients(s.t0 + inset, s.media_mask).sigma_t;
        ++counters.density_lookups;
        const double first = std::ceil(static_cast<double>(s.t0 - ray.t_min) / h - u);
        for (double i = std::max(first, 0.0);; i += 1.0) {
            const float t = ray.t_min + static_cast<float>((u + i) * h);
            if (!(t < s.t1))
                break;
            if (!(t > t_prev))
                continue;
            const Vec3 x = ray.at(t);
            const PointCoefficients k = query.coefficients(t, s.media_mask);
            ++counters.density_lookups;
            tau += 0.5 * static_cast<double>(t - t_prev) * glm::dvec3(sigma_prev + k.sigma_t);
            t_prev = t;
            sigma_prev = k.sigma_t;
            if (!visit(t, x, k, s.media_mask, tau))
                return tau;
        }
        const Rgb sigma_end = query.coefficients(s.t1 - inset, s.media_mask).sigma_t;
        ++counters.density_lookups;
        tau += 0.5 * static_cast<double>(s.t1 - t_prev) * glm::dvec3(sigma_prev + sigma_end);
    }
    return tau;
}

}  // namespace kasumi
