#pragma once
/// Draine's phase function (Draine 2003, ApJ 598, 1017, eq. 4):
/// p(mu) = (1 - g²) / (4π (1 + g² - 2 g mu)^{3/2}) · (1 + alpha mu²) / (1 + alpha (1 + 2g²) / 3)
/// per steradian: Henyey-Greenstein reweighted by 1 + alpha mu². g in (-1, 1), alpha >= 0;
/// alpha = 0 is HG and alpha = 1 is Cornette-Shanks.
#include "phase/phase_sample.h"

namespace kasumi {

struct Draine {
    float g = 0.0f;
    float alpha = 1.0f;
};

float eval(const Draine& p, float mu);
/// p(mu) in double precision (draine_value); eval() is this value rounded to float.
double eval_precise(const Draine& p, double mu);
float pdf(const Draine& p, float mu);
/// Numerical inversion of the closed-form CDF (exact to ~1e-12); pdf per steradian.
PhaseSample sample(const Draine& p, const Vec3& wo, Vec2 u);
/// Closed form (Draine 2003): g (1 + alpha (3 + 2g²)/5) / (1 + alpha (1 + 2g²)/3).
float mean_cosine(const Draine& p);

/// Draine's p(mu) in double precision, per steradian.
double draine_value(double g, double alpha, double mu);
/// Inverse CDF in mu for u in [0, 1].
double sample_draine_cosine(double g, double alpha, double u);

}  // namespace kasumi
