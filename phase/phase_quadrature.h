#pragma once
/// Adaptive quadrature in mu for phase-function checks, with panels that crowd toward
/// mu = ±1 so peaks as narrow as 1 - |mu| ~ 1e-9 (HG with |g| = 0.9999) are resolved.
#include <functional>
#include <vector>

namespace kasumi {

/// ∫_a^b f(mu) dmu by adaptive Simpson (Lyness 1969), [a, b] within [-1, 1]. A panel is
/// accepted when its error estimate is below the absolute `tolerance` (shared among panels) or
/// below `relative` times its own value; for functions evaluated in float, `relative` must stay
/// above float rounding (~1e-7) or the recursion chases noise. `breaks` are extra panel edges
/// (the nodes of a piecewise-linear table: Simpson is exact between them).
double integrate_mu(const std::function<double(double)>& f, double a, double b,
                    double tolerance = 1e-10, double relative = 1e-12,
                    const std::vector<double>& breaks = {});

/// Regularised upper incomplete gamma Q(a, x) = Γ(a, x) / Γ(a): the chi-square tail
/// probability P(χ²_k > s) is Q(k/2, s/2). Series for x < a + 1, continued fraction otherwise.
double upper_incomplete_gamma_q(double a, double x);

}  // namespace kasumi
