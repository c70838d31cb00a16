#pragma once
/// Jendersie & d'Eon 2023, "An Approximate Mie Scattering Function for Fog and Cloud
/// Rendering" (SIGGRAPH 2023 Talks, doi:10.1145/3587421.3595409): a blend
/// p = (1 - w_D) HG(g_HG) + w_D Draine(g_D, alpha) fitted to Lorenz-Mie scattering by water
/// droplets in air, averaged over the visible spectrum, as a function of the droplet diameter
/// d in µm, d in (0, 50]. Per steradian.
#include "phase/phase_sample.h"

namespace kasumi {

/// The four fitted parameters for one droplet diameter.
struct JendersieDeonFit {
    float g_hg = 0.0f;
    float g_d = 0.0f;
    float alpha = 0.0f;
    float w_d = 0.0f;
};

/// The paper's fit formulas for d in (0, 0.1], (0.1, 1.5), [1.5, 5), [5, 50] µm.
JendersieDeonFit jendersie_deon_fit(float diameter_um);

struct JendersieDeon {
    float diameter_um = 10.0f;
    JendersieDeonFit fit = jendersie_deon_fit(10.0f);
};

/// Builds the model for a diameter in (0, 50] µm (the caller validates the range).
JendersieDeon make_jendersie_deon(float diameter_um);

float eval(const JendersieDeon& p, float mu);
/// p(mu) in double precision; eval() is this value rounded to float.
double eval_precise(const JendersieDeon& p, double mu);
float pdf(const JendersieDeon& p, float mu);
/// Picks a lobe with u.x, then inverts that lobe's CDF with the rescaled u.x.
PhaseSample sample(const JendersieDeon& p, const Vec3& wo, Vec2 u);
float mean_cosine(const JendersieDeon& p);

}  // namespace kasumi
