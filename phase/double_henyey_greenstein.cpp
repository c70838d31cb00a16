#include "phase/double_henyey_greenstein.h"

#include "core/sampling.h"
#include "phase/henyey_greenstein.h"

namespace kasumi {

float eval(const DoubleHenyeyGreenstein& p, float mu) {
    return p.w * eval(HenyeyGreenstein{p.g1}, mu) + (1.0f - p.w) * eval(HenyeyGreenstein{p.g2}, mu);
}

float pdf(const DoubleHenyeyGreenstein& p, float mu) {
    return eval(p, mu);
}

PhaseSample sample(const DoubleHenyeyGreenstein& p, const Vec3& wo, Vec2 u) {
    float mu;
    // Reusing the selection variable keeps the sampler a deterministic map of u; the rescaled
    // value stays uniform on [0, 1) within each branch.
    if (u.x < p.w) {
        mu = sample_hg_cosine(p.g1, std::min(u.x / p.w, 1.0f - 0x1p-24f));
    } else {
        const float rest = 1.0f - p.w;
        mu = sample_hg_cosine(p.g2, std::min((u.x - p.w) / rest, 1.0f - 0x1p-24f));
    }
    const Vec3 propagation = direction_about(wo, mu, kTwoPi * u.y);
    const float value = eval(p, mu);
    return PhaseSample{-propagation, value, value};
}

float mean_cosine(const DoubleHenyeyGreenstein& p) {
    return p.w * p.g1 + (1.0f - p.w) * p.g2;
}

}  // namespace kasumi
