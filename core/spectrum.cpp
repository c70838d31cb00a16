#include "core/spectrum.h"

namespace kasumi {

glm::dvec3 xyz_to_rec709(const glm::dvec3& xyz) {
    return glm::dvec3(3.2404542 * xyz.x - 1.5371385 * xyz.y - 0.4985314 * xyz.z,
                      -0.9692660 * xyz.x + 1.8760108 * xyz.y + 0.0415560 * xyz.z,
                      0.0556434 * xyz.x - 0.2040259 * xyz.y + 1.0572252 * xyz.z);
}

std::vector<double> spectral_wavelengths_nm(int n) {
    std::vector<double> out(static_cast<size_t>(std::max(n, 0)));
    const double bin = spectral_bin_nm(n);
    for (int i = 0; i < n; ++i)
        out[static_cast<size_t>(i)] = 360.0 + (i + 0.5) * bin;
    return out;
}

double spectral_bin_nm(int n) {
    return n > 0 ? (830.0 - 360.0) / n : 0.0;
}

double planck_radiance(double lambda_nm, double temperature_k) {
    // CODATA 2018 exact constants: h, c, k_B.
    constexpr double h = 6.62607015e-34, c = 299792458.0, k_b = 1.380649e-23;
    const double lambda = lambda_nm * 1e-9;
    const double x = h * c / (lambda * k_b * temperature_k);
    // W/(m² sr m) -> per nm.
    return 2.0 * h * c * c / (std::pow(lambda, 5) * std::expm1(x)) * 1e-9;
}

}  // namespace kasumi
