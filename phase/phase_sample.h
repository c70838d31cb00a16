#pragma once
/// The result of importance-sampling a phase function.
#include "core/math.h"

namespace kasumi {

/// wi points away from the scattering point toward where light comes from; `value` is the
/// phase function p(mu) in 1/sr and `pdf` the density of wi per steradian (equal to value for
/// models sampled exactly).
struct PhaseSample {
    Vec3 wi;
    float value = 0.0f;
    float pdf = 0.0f;
};

/// The sample for a scattering cosine mu drawn in double precision, at azimuth phi (radians)
/// about wo, with value == pdf == `density` per steradian (the model's eval_precise at mu).
/// Why double: near mu = ±1 float spacing (6e-8) is wider than the peak of |g| = 0.9999
/// (1 - |mu| ~ 1e-8), so a float mu would snap half the samples onto the pole. sin θ formed
/// from (1 - mu)(1 + mu) in double keeps the deflection (~1e-4 rad), which the float direction
/// holds to ~1e-3 relative.
inline PhaseSample phase_sample_about(const Vec3& wo, double mu, float phi, double density) {
    const double sin_theta = std::sqrt(std::max(0.0, (1.0 - mu) * (1.0 + mu)));
    const Vec3 local(static_cast<float>(sin_theta * std::cos(phi)),
                     static_cast<float>(sin_theta * std::sin(phi)), static_cast<float>(mu));
    // Light arriving along -wi leaves along wo, so mu = dot(-wi, wo): draw -wi about wo.
    const Vec3 propagation = Frame(wo).to_world(local);
    const auto value = static_cast<float>(density);
    return PhaseSample{-propagation, value, value};
}

/// Scattering cosine for the convention wo toward the viewer, wi toward the light:
/// mu = +1 is forward (undeflected) scattering.
inline float scattering_cosine(const Vec3& wo, const Vec3& wi) {
    return -glm::dot(wo, wi);
}

}  // namespace kasumi
