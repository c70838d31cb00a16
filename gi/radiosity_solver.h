#pragma once
/// The radiosity system over N patches, in radiance (cd/m²), per RGB channel
/// (Cohen & Wallace 1993, eq. 2.5 with B = π L):
///   L_i = L0_i + ρ_i Σ_j F_ij L_j,
/// L0_i = emitted radiance plus light reflected directly from the light sources, ρ_i the diffuse
/// reflectance, F_ij the form factor from i to j (row sums <= 1). Solved by progressive
/// refinement (shooting, Cohen, Chen, Wallace & Greenberg 1988) or Gauss-Seidel.
#include "core/color.h"

#include <cstdint>
#include <vector>

namespace kasumi {

struct RadiositySystem {
    std::vector<double> area;  ///< m²
    std::vector<Rgb> rho;      ///< diffuse reflectance, each channel in [0, 1]
    std::vector<Rgb> source;   ///< L0, cd/m²
    /// Row-major N × N form factors F_ij (from i to j).
    std::vector<float> form_factor;
    size_t size() const { return area.size(); }
    float f(size_t i, size_t j) const { return form_factor[i * size() + j]; }
};

struct RadiosityResult {
    std::vector<Rgb> radiance;  ///< L, cd/m²
    /// Σ_i A_i luminance(|L0_i + ρ_i Σ_j F_ij L_j − L_i|) / Σ_i A_i luminance(L0_i): the relative
    /// residual of the returned solution (0 when nothing emits).
    double residual = 0.0;
    int iterations = 0;  ///< shots or sweeps
    bool converged = false;
};

/// Shooting: repeatedly distributes the unshot radiance of the patch with the most unshot power
/// (A_i · luminance) to all others, ΔL_j += ρ_j F_ji ΔL_i with F_ji = F_ij A_i / A_j, until the
/// unshot power (which is the residual of the system, Cohen & Wallace §5.3.3) is below
/// `tolerance` times the source power, or max_iterations shots.
RadiosityResult solve_shooting(const RadiositySystem& system, double tolerance, int max_iterations);

/// Gauss-Seidel: sweeps L_i ← L0_i + ρ_i Σ_j F_ij L_j in place until the relative residual falls
/// below `tolerance`, or max_iterations sweeps.
RadiosityResult solve_gauss_seidel(const RadiositySystem& system, double tolerance,
                                   int max_iterations);

/// The relative residual of `radiance` (as defined in RadiosityResult).
double radiosity_residual(const RadiositySystem& system, const std::vector<Rgb>& radiance);

}  // namespace kasumi
