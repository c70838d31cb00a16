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

/// Scattering cosine for the convention wo toward the viewer, wi toward the light:
/// mu = +1 is forward (undeflected) scattering.
inline float scattering_cosine(const Vec3& wo, const Vec3& wi) {
    return -glm::dot(wo, wi);
}

}  // namespace kasumi
