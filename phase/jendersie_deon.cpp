#include "phase/jendersie_deon.h"

#include "phase/draine.h"
#include "phase/henyey_greenstein.h"

namespace kasumi {

JendersieDeonFit jendersie_deon_fit(float diameter_um) {
    const double d = diameter_um;
    double g_hg, g_d, alpha, w_d;
    if (d <= 0.1) {
        g_hg = 13.8 * d * d;
        g_d = 1.1456 * d * std::sin(9.29044 * d);
        alpha = 250.0;
        w_d = 0.252977 - 312.983 * std::pow(d, 4.3);
    } else if (d < 1.5) {
        const double l = std::log(d);
        g_hg = 0.862 - 0.143 * l * l;
        g_d = 0.379685 * std::cos(1.19692 * std::cos((l - 0.238604) * (l + 1.00667) /
                                                     (0.507522 - 0.15677 * l)) +
                                  1.37932 * l + 0.0625835) +
              0.344213;
        alpha = 250.0;
        w_d = 0.146209 * std::cos(3.38707 * l + 2.11193) + 0.316072 + 0.0778917 * l;
    } else if (d < 5.0) {
        const double l = std::log(d);
        g_hg = 0.0604931 * std::log(l) + 0.940256;
        g_d = 0.500411 - 0.081287 / (-2.0 * l + std::tan(l) + 1.27551);
        alpha = 7.30354 * l + 6.31675;
        w_d = 0.026914 * (l - std::cos(5.68947 * (std::log(l) - 0.0292149))) + 0.376475;
    } else {
        g_hg = std::exp(-0.0990567 / (d - 1.67154));
        g_d = std::exp(-2.20679 / (d + 3.91029) - 0.428934);
        alpha = std::exp(3.62489 - 8.29288 / (d + 5.52825));
        w_d = std::exp(-0.599085 / (d - 0.641583) - 0.665888);
    }
    return JendersieDeonFit{static_cast<float>(g_hg), static_cast<float>(g_d),
                            static_cast<float>(alpha), static_cast<float>(w_d)};
}

JendersieDeon make_jendersie_deon(float diameter_um) {
    return JendersieDeon{diameter_um, jendersie_deon_fit(diameter_um)};
}

double eval_precise(const JendersieDeon& p, double mu) {
    const JendersieDeonFit& f = p.fit;
    const double w_d = f.w_d;
    return (1.0 - w_d) * eval_precise(HenyeyGreenstein{f.g_hg}, mu) +
           w_d * eval_precise(Draine{f.g_d, f.alpha}, mu);
}

float eval(const JendersieDeon& p, float mu) {
    return static_cast<float>(eval_precise(p, mu));
}

float pdf(const JendersieDeon& p, float mu) {
    return eval(p, mu);
}

PhaseSample sample(const JendersieDeon& p, const Vec3& wo, Vec2 u) {
    const JendersieDeonFit& f = p.fit;
    double mu;
    if (u.x < f.w_d) {
        const float v = std::min(u.x / f.w_d, 1.0f - 0x1p-24f);
        mu = sample_draine_cosine(f.g_d, f.alpha, v);
    } else {
        const float v = std::min((u.x - f.w_d) / (1.0f - f.w_d), 1.0f - 0x1p-24f);
        mu = sample_hg_cosine(f.g_hg, v);
    }
    return phase_sample_about(wo, mu, kTwoPi * u.y, eval_precise(p, mu));
}

float mean_cosine(const JendersieDeon& p) {
    const JendersieDeonFit& f = p.fit;
    return (1.0f - f.w_d) * f.g_hg + f.w_d * mean_cosine(Draine{f.g_d, f.alpha});
}

}  // namespace kasumi
