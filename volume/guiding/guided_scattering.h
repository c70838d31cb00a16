#pragma once
/// Guided scattering directions: the one-sample mixture of the product of a learnt
/// incident-radiance histogram and the phase function, and the phase function alone
/// (Herholz, Zhao, Georgiev, Keller & Lensch 2019, sec. 5: directions from a mixture of the
/// guiding distribution, which approximates L_i times the phase function, and the phase function):
///   pdf(wi) = mix * G(wi) + (1 - mix) * phase(mu),   per steradian,
///   G(wi)   = h_b p(mu_b) / (sum_j h_j p(mu_j) * 4 pi / kBins),   b = the bin of wi,
/// with h_j the histogram's bin probabilities and mu_j the scattering cosine of bin j's centre:
/// G is piecewise constant over the bins, so it is exact to sample and evaluate. The path
/// weight sigma_s p(mu) / pdf(wi) is that of one-sample MIS with the balance heuristic (Veach
/// 1997, sec. 9.2.4): unbiased wherever the phase function is positive, and at most
/// 1 / (1 - mix) times the phase-sampled weight.
/// Used for one scattering medium at the point (a single bit in `mask`); the caller falls back
/// to MediumSet::sample_scattering otherwise.
#include "volume/guiding/directional_histogram.h"
#include "volume/medium_set.h"

namespace kasumi {

/// The mixture density of direction `wi` at a point of medium `medium` (index into the set),
/// per steradian. `wo` points back along the arriving path.
float guided_pdf(const MediumSet& media, uint32_t medium, const DirectionalHistogram& guide,
                 float mix, const Vec3& wo, const Vec3& wi);

/// A direction from the mixture: from the guide when u_choose < mix, else from the phase
/// function with `u`; its scattering sigma_s p(mu) (1/(m sr), from `k`, the coefficients at p)
/// and its mixture pdf. pdf 0 when nothing scatters.
MixtureSample sample_guided_scattering(const MediumSet& media, uint32_t medium,
                                       const DirectionalHistogram& guide, float mix,
                                       const PointCoefficients& k, const Vec3& wo, float u_choose,
                                       Vec2 u);

}  // namespace kasumi
