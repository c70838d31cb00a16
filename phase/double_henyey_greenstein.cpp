#include "phase/double_henyey_greenstein.h"

#include "phase/henyey_greenstein.h"

namespace kasumi {

double eval_precise(const DoubleHenyeyGreenstein& p, double mu) {
    const double w = p.w;
    return w * eval_precise(HenyeyGreenstein{p.g1}, mu) +
           (1.0 - w) * eval_precise(HenyeyGreenstein{p.g2}, mu);
}

float eval(const DoubleHenyeyGreenstein& p, float mu) {
    return static_cast<float>(eval_precise(p, mu));
}

float pdf(const DoubleHenyeyGreenstein& p, float mu) {
    return eval(p, mu);
}

PhaseSample sample(const DoubleHenyeyGreenstein& p, const Vec3& wo, Vec2 u) {
    double mu;
    // Reusing the selection variable keeps the sampler a deterministic map of u; the rescaled
    // value stays uniform on [0, 1) within each branch.
    if (u.x < p.w) {
        mu = sample_hg_cosine(p.g1, std::min(u.x / p.w, 1.0f - 0x1p-24f));
    } else {
        const float rest = 1.0f - p.w;
        mu = sample_hg_cosine(p.g2, std::min((u.x - p.w) / rest, 1.0f - 0x1p-24f));
    }
    return phase_sample_about(wo, mu, kTwoPi * u.y, eval_precise(p, mu));
}

float mean_cosine(const DoubleHenyeyGreenstein& p) {
    return p.w * p.g1 + (1.0f - p.w) * p.g2;
}

}  // namespace kasumi
