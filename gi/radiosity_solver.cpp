#include "gi/radiosity_solver.h"

#include <cmath>

namespace kasumi {

namespace {

double source_power(const RadiositySystem& s) {
    double total = 0.0;
    for (size_t i = 0; i < s.size(); ++i)
        total += s.area[i] * luminance(s.source[i]);
    return total;
}

/// Σ_j F_ij L_j in double precision.
glm::dvec3 gathered(const RadiositySystem& s, size_t i, const std::vector<Rgb>& radiance) {
    glm::dvec3 sum(0.0);
    const float* row = &s.form_factor[i * s.size()];
    for (size_t j = 0; j < s.size(); ++j) {
        if (row[j] != 0.0f)
            sum += static_cast<double>(row[j]) * glm::dvec3(radiance[j]);
    }
    return sum;
}

}  // namespace

double radiosity_residual(const RadiositySystem& s, const std::vector<Rgb>& radiance) {
    const double total = source_power(s);
    if (!(total > 0.0))
        return 0.0;
    double r = 0.0;
    for (size_t i = 0; i < s.size(); ++i) {
        const glm::dvec3 expected =
            glm::dvec3(s.source[i]) + glm::dvec3(s.rho[i]) * gathered(s, i, radiance);
        const glm::dvec3 diff = glm::abs(expected - glm::dvec3(radiance[i]));
        r += s.area[i] * (kLumaR * diff.x + kLumaG * diff.y + kLumaB * diff.z);
    }
    return r / total;
}

RadiosityResult solve_shooting(const RadiositySystem& s, double tolerance, int max_iterations) {
    const size_t n = s.size();
    RadiosityResult result;
    std::vector<glm::dvec3> radiance(n), unshot(n);
    for (size_t i = 0; i < n; ++i)
        radiance[i] = unshot[i] = glm::dvec3(s.source[i]);
    const double total = source_power(s);
    while (total > 0.0 && result.iterations < max_iterations) {
        size_t shooter = 0;
        double most = -1.0, remaining = 0.0;
        for (size_t i = 0; i < n; ++i) {
            const double power =
                s.area[i] * (kLumaR * unshot[i].x + kLumaG * unshot[i].y + kLumaB * unshot[i].z);
            remaining += power;
            if (power > most) {
                most = power;
                shooter = i;
            }
        }
        if (remaining <= tolerance * total) {
            result.converged = true;
            break;
        }
        const glm::dvec3 shot = unshot[shooter];
        unshot[shooter] = glm::dvec3(0.0);
        const double a_i = s.area[shooter];
        for (size_t j = 0; j < n; ++j) {
            const float f_ij = s.f(shooter, j);
            if (f_ij == 0.0f || j == shooter)
                continue;
            // Reciprocity: F_ji = F_ij A_i / A_j.
            const glm::dvec3 add = glm::dvec3(s.rho[j]) * (f_ij * a_i / s.area[j]) * shot;
            radiance[j] += add;
            unshot[j] += add;
        }
        ++result.iterations;
    }
    if (!(total > 0.0))
        result.converged = true;
    result.radiance.resize(n);
    for (size_t i = 0; i < n; ++i)
        result.radiance[i] = Rgb(radiance[i]);
    result.residual = radiosity_residual(s, result.radiance);
    return result;
}

RadiosityResult solve_gauss_seidel(const RadiositySystem& s, double tolerance, int max_iterations) {
    const size_t n = s.size();
    RadiosityResult result;
    result.radiance = s.source;
    while (result.iterations < max_iterations) {
        for (size_t i = 0; i < n; ++i) {
            result.radiance[i] = Rgb(glm::dvec3(s.source[i]) +
                                     glm::dvec3(s.rho[i]) * gathered(s, i, result.radiance));
        }
        ++result.iterations;
        result.residual = radiosity_residual(s, result.radiance);
        if (result.residual <= tolerance) {
            result.converged = true;
            break;
        }
    }
    result.residual = radiosity_residual(s, result.radiance);
    return result;
}

}  // namespace kasumi
