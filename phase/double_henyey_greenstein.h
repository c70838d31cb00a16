#pragma once
/// Two-lobe Henyey-Greenstein mixture (Kattawar 1975, JQSRT 15, 839):
/// p(mu) = w HG(mu; g1) + (1 - w) HG(mu; g2) per steradian, g1, g2 in (-1, 1), w in [0, 1].
/// Typically g1 > 0 is the forward lobe and g2 < 0 the backward one.
#include "phase/phase_sample.h"

namespace kasumi {

struct DoubleHenyeyGreenstein {
    float g1 = 0.0f;
    float g2 = 0.0f;
    float w = 1.0f;
};

float eval(const DoubleHenyeyGreenstein& p, float mu);
/// p(mu) in double precision; eval() is this value rounded to float.
double eval_precise(const DoubleHenyeyGreenstein& p, double mu);
float pdf(const DoubleHenyeyGreenstein& p, float mu);
/// Picks a lobe with u.x and reuses the rescaled u.x to invert that lobe; pdf per steradian.
PhaseSample sample(const DoubleHenyeyGreenstein& p, const Vec3& wo, Vec2 u);
float mean_cosine(const DoubleHenyeyGreenstein& p);

}  // namespace kasumi
