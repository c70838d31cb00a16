#pragma once
/// The fixed-step walk shared by the `march` transmittance estimator and marched single
/// scattering: nodes t_min + (u + i) h on a grid with one random offset u per ray, plus every
/// majorant segment's ends (empty space between segments contributes nothing; abutting segments
/// over the same media form one run with nodes only at its ends); the optical depth accumulates
/// by the trapezoid rule between consecutive nodes.
#include "volume/in_scattering.h"
#include "volume/medium_set.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace kasumi {

/// The most march nodes one ray takes through the media: 2^16. A finer step is lengthened to
/// 1/65536 of the ray's way through them (counted in counters.bounded_marches and reported after
/// the render): beyond that a march costs without bound (render.volume.step_m = 1e-30 never
/// ended) and its nodes approach the float resolution of t (2^-24 of the distance).
constexpr double kMaxMarchSteps = 65536.0;

/// The march step for a ray whose way through the media is `extent` long (same units as h):
/// h, or extent / kMaxMarchSteps when h would take more nodes than that.
inline float bounded_march_step(float h, double extent, VolumeCounters& counters) {
    if (!(extent < static_cast<double>(kInfinity)) || !(extent > h * kMaxMarchSteps))
        return h;
    ++counters.bounded_marches;
    return static_cast<float>(extent / kMaxMarchSteps);
}

/// The way a ray goes through `segments`, from the first segment's start to the last finite end.
inline double march_extent(const std::vector<MajorantSegment>& segments) {
    double end = 0.0;
    for (const MajorantSegment& s : segments)
        if (s.t1 < kInfinity)
            end = s.t1;
    return segments.empty() ? 0.0 : std::max(end - static_cast<double>(segments.front().t0), 0.0);
}

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
    const auto constant = [&](const MajorantSegment& s) {
        return skip_constant && s.sigma_max == s.sigma_min;
    };
    const size_t n = segments.size();
    for (size_t i = 0; i < n;) {
        const MajorantSegment& s = segments[i];
        if (!(s.t1 < kInfinity)) {
            // An endless stretch: infinite depth in every channel whose extinction is bounded
            // away from zero; the others are left as walked (a tail of zero extinction).
            for (int c = 0; c < 3; ++c)
                if (s.sigma_min[c] > 0.0f)
                    tau[c] = HUGE_VAL;
            return tau;
        }
        if (constant(s)) {
            tau += static_cast<double>(s.t1 - s.t0) * glm::dvec3(s.sigma_max);
            ++i;
            continue;
        }
        // A run of abutting segments over the same media: the coefficients are continuous
        // across their shared ends (trilinear grids), so the trapezoid rule walks the run as one
        // stretch and only the run's own ends (where empty space or another medium begins) get
        // extra nodes. Per-brick segments would otherwise cost two end lookups per brick.
        size_t j = i;
        while (j + 1 < n && segments[j + 1].t0 == segments[j].t1 &&
               segments[j + 1].media_mask == s.media_mask && segments[j + 1].t1 < kInfinity &&
               !constant(segments[j + 1]))
            ++j;
        const float t0 = s.t0, t1 = segments[j].t1;
        const uint32_t mask = s.media_mask;
        i = j + 1;
        // Ends are evaluated a hair inside so a homogeneous box's face does not round outside.
        const float inset = 1e-6f * (t1 - t0);
        float t_prev = t0;
        Rgb sigma_prev = query.coefficients(t0 + inset, mask).sigma_t;
        ++counters.density_lookups;
        const double first = std::ceil(static_cast<double>(t0 - ray.t_min) / h - u);
        for (double k = std::max(first, 0.0);; k += 1.0) {
            const float t = ray.t_min + static_cast<float>((u + k) * h);
            if (!(t < t1))
                break;
            if (!(t > t_prev))
                continue;
            const Vec3 x = ray.at(t);
            const PointCoefficients c = query.coefficients(t, mask);
            ++counters.density_lookups;
            tau += 0.5 * static_cast<double>(t - t_prev) * glm::dvec3(sigma_prev + c.sigma_t);
            t_prev = t;
            sigma_prev = c.sigma_t;
            if (!visit(t, x, c, mask, tau))
                return tau;
        }
        const Rgb sigma_end = query.coefficients(t1 - inset, mask).sigma_t;
        ++counters.density_lookups;
        tau += 0.5 * static_cast<double>(t1 - t_prev) * glm::dvec3(sigma_prev + sigma_end);
    }
    return tau;
}

}  // namespace kasumi
