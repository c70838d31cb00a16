#pragma once
/// Isotropic phase function: p(mu) = 1/(4π) per steradian.
#include "phase/phase_sample.h"

namespace kasumi {

struct Isotropic {};

float eval(const Isotropic& p, float mu);
/// p(mu) in double precision (see eval_precise(PhaseFunction)).
double eval_precise(const Isotropic& p, double mu);
float pdf(const Isotropic& p, float mu);
PhaseSample sample(const Isotropic& p, const Vec3& wo, Vec2 u);
float mean_cosine(const Isotropic& p);

}  // namespace kasumi
