#pragma once
/// Rayleigh phase function with depolarisation (Chandrasekhar 1950, "Radiative Transfer",
/// §18; form used by Penndorf 1957 and Bucholtz 1995, Appl. Opt. 34, 2765, eq. 12):
/// p(mu) = 3 / (16π (1 + 2γ)) · ((1 + 3γ) + (1 - γ) mu²), γ = rho / (2 - rho), per steradian.
/// rho in [0, 1) is the depolarisation factor; rho = 0 gives 3/(16π)(1 + mu²).
#include "phase/phase_sample.h"

namespace kasumi {

struct Rayleigh {
    float rho = 0.0f;
};

/// p(mu) for depolarisation factor rho, in double precision (the form above).
double rayleigh_phase(double rho, double mu);
float eval(const Rayleigh& p, float mu);
/// p(mu) in double precision; eval() is this value rounded to float.
double eval_precise(const Rayleigh& p, double mu);
float pdf(const Rayleigh& p, float mu);
/// Exact inversion of the cumulative distribution (a cubic in mu); pdf per steradian.
PhaseSample sample(const Rayleigh& p, const Vec3& wo, Vec2 u);
float mean_cosine(const Rayleigh& p);

/// Inverse CDF in mu of the density proportional to 1 + a mu² on [-1, 1], for a >= 0 and
/// u in [0, 1]. Shared by Rayleigh and the g = 0 limit of Draine.
double sample_quadratic_cosine(double a, double u);

}  // namespace kasumi
