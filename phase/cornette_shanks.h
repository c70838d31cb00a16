#pragma once
/// Cornette-Shanks phase function (Cornette & Shanks 1992, Appl. Opt. 31, 3152, eq. 8):
/// p(mu) = 3 (1 - g²) (1 + mu²) / (8π (2 + g²) (1 + g² - 2 g mu)^{3/2}) per steradian,
/// g in (-1, 1). It equals Draine's function with alpha = 1, which provides its sampler.
/// Note g is a shape parameter: the mean cosine is 3 g (4 + g²) / (5 (2 + g²)), not g.
#include "phase/phase_sample.h"

namespace kasumi {

struct CornetteShanks {
    float g = 0.0f;
};

float eval(const CornetteShanks& p, float mu);
/// p(mu) in double precision; eval() is this value rounded to float.
double eval_precise(const CornetteShanks& p, double mu);
float pdf(const CornetteShanks& p, float mu);
PhaseSample sample(const CornetteShanks& p, const Vec3& wo, Vec2 u);
float mean_cosine(const CornetteShanks& p);

}  // namespace kasumi
