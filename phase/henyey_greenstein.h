#pragma once
/// Henyey-Greenstein phase function (Henyey & Greenstein 1941, ApJ 93, 70):
/// p(mu) = (1 - g²) / (4π (1 + g² - 2 g mu)^{3/2}) per steradian. g in (-1, 1) is the mean
/// cosine; g > 0 scatters forward (mu = +1).
#include "phase/phase_sample.h"

namespace kasumi {

struct HenyeyGreenstein {
    float g = 0.0f;
};

float eval(const HenyeyGreenstein& p, float mu);
/// p(mu) in double precision; eval() is this value rounded to float.
double eval_precise(const HenyeyGreenstein& p, double mu);
float pdf(const HenyeyGreenstein& p, float mu);
/// Exact inversion of the HG cumulative distribution in mu; pdf per steradian.
PhaseSample sample(const HenyeyGreenstein& p, const Vec3& wo, Vec2 u);
float mean_cosine(const HenyeyGreenstein& p);

/// Inverse CDF of HG in mu for u in [0, 1): the cosine of the deflection.
double sample_hg_cosine(double g, double u);

/// 1 + g² - 2 g mu, written as (1 - g)² + 2 g (1 - mu) for g >= 0 and (1 + g)² - 2 g (1 + mu)
/// for g < 0: the textbook form cancels catastrophically in the peak (mu -> sign(g), |g| -> 1).
/// mu is clamped to [-1, 1] first.
double hg_denominator(double g, double mu);

}  // namespace kasumi
