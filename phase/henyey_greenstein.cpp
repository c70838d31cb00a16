#include "phase/henyey_greenstein.h"

#include "core/sampling.h"

namespace kasumi {

float eval(const HenyeyGreenstein& p, float mu) {
    const float g = p.g;
    const float denom = 1.0f + g * g - 2.0f * g * mu;
    return kInv4Pi * (1.0f - g * g) / (denom * safe_sqrt(denom));
}

float pdf(const HenyeyGreenstein& p, float mu) {
    return eval(p, mu);
}

float sample_hg_cosine(float g, float u) {
    // Near g = 0 the inversion formula divides by g; its limit is the uniform cosine.
    if (std::abs(g) < 1e-3f)
        return 1.0f - 2.0f * u;
    const float s = (1.0f - g * g) / (1.0f - g + 2.0f * g * u);
    return std::clamp((1.0f + g * g - s * s) / (2.0f * g), -1.0f, 1.0f);
}

PhaseSample sample(const HenyeyGreenstein& p, const Vec3& wo, Vec2 u) {
    const float mu = sample_hg_cosine(p.g, u.x);
    // Light arriving along -wi leaves along wo, so mu = dot(-wi, wo): draw -wi about wo.
    const Vec3 propagation = direction_about(wo, mu, kTwoPi * u.y);
    const float value = eval(p, mu);
    return PhaseSample{-propagation, value, value};
}

float mean_cosine(const HenyeyGreenstein& p) {
    return p.g;
}

}  // namespace kasumi
