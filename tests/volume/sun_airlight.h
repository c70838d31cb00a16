#pragma once
// The airlight integral of Sun, Ramamoorthi, Narasimhan & Nayar 2005, "A Practical Analytic
// Single Scattering Model for Real Time Rendering", ACM TOG 24(3), eqs. 3-5, and the scene it
// describes, shared by the tests of the integrators that must reproduce it: an isotropic point
// light of intensity I at distance D_sv from the viewer, in a purely scattering medium of
// coefficient beta with isotropic phase, seen at angle gamma from the light's direction, over a
// view ray of length D_vp:
//   L = A0 [F(A1, pi/4 + atan((T_vp - T_sv cos g) / (T_sv sin g)) / 2) - F(A1, g/2)],
//   A0 = beta^2 I exp(-T_sv cos g) / (2 pi T_sv sin g), A1 = T_sv sin g, T = beta D,
// with the upper limit pi/2 for an endless ray.
#include "core/math.h"
#include "lights/light.h"
#include "volume/medium_set.h"

#include <cmath>
#include <vector>

namespace kasumi::test {

/// F(u, v) = int_0^v exp(-u tan xi) dxi (eq. 5), by Simpson's rule on 20000 intervals.
inline double sun_f(double u, double v) {
    const int n = 20000;
    const double h = v / n;
    double s = 0.0;
    for (int i = 0; i <= n; ++i) {
        const double f = std::exp(-u * std::tan(i * h));
        s += (i == 0 || i == n ? 1.0 : (i % 2 ? 4.0 : 2.0)) * f;
    }
    return s * h / 3.0;
}

/// The scene of eqs. 3-5: beta = 0.4 /m everywhere (no bounds), the viewer at the origin, the
/// lamp (100 cd) at z = -2 m.
struct SunAirlight {
    static constexpr double beta = 0.4, intensity = 100.0, d_sv = 2.0;
    const MediumSet fog{
        {Medium{"fog", HomogeneousMedium{std::nullopt, Rgb(0.0f), Rgb(static_cast<float>(beta)),
                                         Isotropic{}}}}};
    const std::vector<Light> lamp{
        Light{"lamp", PointLight{Vec3(0.0f, 0.0f, static_cast<float>(-d_sv)),
                                 Rgb(static_cast<float>(intensity))}}};

    /// The view ray at gamma_deg from the direction to the lamp, of length d_vp (kInfinity:
    /// endless).
    static Ray ray(double gamma_deg, double d_vp) {
        const double g = gamma_deg * kPiD / 180.0;
        return Ray{Vec3(0.0f),
                   Vec3(static_cast<float>(std::sin(g)), 0.0f, static_cast<float>(-std::cos(g))),
                   0.0f, static_cast<float>(d_vp)};
    }

    /// L along ray(gamma_deg, d_vp), cd/m² (eq. 3).
    static double radiance(double gamma_deg, double d_vp) {
        const double g = gamma_deg * kPiD / 180.0;
        const double t_sv = beta * d_sv, a1 = t_sv * std::sin(g);
        const double upper =
            d_vp >= kInfinity
                ? kPiD / 2.0
                : kPiD / 4.0 + 0.5 * std::atan((beta * d_vp - t_sv * std::cos(g)) / a1);
        return beta * beta * intensity * std::exp(-t_sv * std::cos(g)) / (2.0 * kPiD * a1) *
               (sun_f(a1, upper) - sun_f(a1, g / 2.0));
    }
};

}  // namespace kasumi::test
