// The atmosphere model against closed forms: optical depths of exponential and tent layers,
// chords through a uniform shell, the Rayleigh coefficient of standard air.
#include "sky/atmosphere.h"
#include "sky/atmosphere_json.h"
#include "sky/sky_reference.h"

#include <gtest/gtest.h>

namespace kasumi {
namespace {

const std::vector<double> kRgbNm{680.0, 550.0, 440.0};

Atmosphere earth() {
    return default_earth_atmosphere(kRgbNm, kRgbNm);
}

/// Closed-form optical depth straight up from the ground: sigma H (1 - exp(-Z/H)) for an
/// exponential layer over the atmosphere's thickness Z, sigma * half_width for a tent that
/// lies wholly inside it.
Bands zenith_tau_closed_form(const Atmosphere& a) {
    const double z = a.top_radius_m - a.ground_radius_m;
    const double h_r = -1.0 / a.rayleigh.profile.upper.exp_scale_per_m;
    const double h_m = -1.0 / a.mie.profile.upper.exp_scale_per_m;
    const double half_width = 1.0 / a.ozone.profile.lower.linear_per_m;
    Bands tau{};
    for (int i = 0; i < a.bands; ++i) {
        tau[i] =
            (a.rayleigh.scattering[i] + a.rayleigh.absorption[i]) * h_r * -std::expm1(-z / h_r) +
            (a.mie.scattering[i] + a.mie.absorption[i]) * h_m * -std::expm1(-z / h_m) +
            a.ozone.absorption[i] * half_width;
    }
    return tau;
}

TEST(Atmosphere, ZenithTransmittanceEqualsExpOfSummedLayerDepths) {
    const Atmosphere a = earth();
    const Bands expected = zenith_tau_closed_form(a);
    const DVec3 up(0.0, 1.0, 0.0);
    // Converged quadrature: the midpoint rule is second order, kinks of the tent aside.
    const Bands fine = atmosphere_optical_depth(a, DVec3(0.0), up, 0.0, 100e3, 20000);
    // The renderer's default sun-ray node count (32): the error it makes is what we state.
    const Bands coarse = atmosphere_optical_depth(a, DVec3(0.0), up, 0.0, 100e3, 32);
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(std::exp(-fine[i]), std::exp(-expected[i]), 1e-7) << "band " << i;
        EXPECT_NEAR(coarse[i] / expected[i], 1.0, 5e-3) << "band " << i;
    }
    // The usual sea-level figures: total zenith optical depth ~0.12 in green.
    EXPECT_GT(expected[1], 0.1);
    EXPECT_LT(expected[1], 0.15);
}

TEST(Atmosphere, QuadratureConvergesAtSecondOrder) {
    // Rayleigh only, a smooth integrand: halving the step quarters the error.
    Atmosphere a = earth();
    a.mie.scattering.fill(0.0);
    a.mie.absorption.fill(0.0);
    a.ozone.absorption.fill(0.0);
    const double exact = zenith_tau_closed_form(a)[1];
    const DVec3 up(0.0, 1.0, 0.0);
    const double e1 =
        std::abs(atmosphere_optical_depth(a, DVec3(0.0), up, 0.0, 100e3, 16)[1] - exact);
    const double e2 =
        std::abs(atmosphere_optical_depth(a, DVec3(0.0), up, 0.0, 100e3, 32)[1] - exact);
    EXPECT_NEAR(e1 / e2, 4.0, 0.4);
}

TEST(Atmosphere, HorizontalTransmittanceInUniformShellIsChordLength) {
    // Density 1 everywhere between ground and top: tau = sigma * chord, chord from altitude h
    // horizontally = sqrt(R_top² - (R_ground + h)²).
    Atmosphere a = earth();
    a.rayleigh.profile = DensityProfile{};
    a.rayleigh.profile.upper.constant_term = 1.0;
    a.mie.scattering.fill(0.0);
    a.mie.absorption.fill(0.0);
    a.ozone.absorption.fill(0.0);
    for (const double h : {0.0, 1000.0, 30e3, 99e3}) {
        const DVec3 p(0.0, h, 0.0);
        const DVec3 d(1.0, 0.0, 0.0);
        double t0 = 0.0, t1 = 0.0;
        bool ground = false;
        ASSERT_TRUE(atmosphere_segment(a, p, d, t0, t1, ground));
        EXPECT_FALSE(ground);
        const double r = a.ground_radius_m + h;
        const double chord = std::sqrt(a.top_radius_m * a.top_radius_m - r * r);
        EXPECT_NEAR(t1 / chord, 1.0, 1e-9) << "h = " << h;
        const Bands tau = atmosphere_optical_depth(a, p, d, t0, t1, 64);
        for (int i = 0; i < 3; ++i)
            EXPECT_NEAR(std::exp(-tau[i]), std::exp(-a.rayleigh.scattering[i] * chord), 1e-12);
    }
}

TEST(Atmosphere, RayleighCrossSectionOfStandardAirMatchesBatesViaNicolet) {
    // Nicolet 1984 (Planet. Space Sci. 32, 1467) fits Bates's 1984 cross sections of air to
    // within 0.5%: sigma = 4.02e-28 / lambda^(4 + x) cm² (lambda in µm) with
    // x = 0.389 lambda + 0.09426 / lambda - 0.3228 below 0.55 µm and x = 0.04 above.
    for (const double nm : {360.0, 440.0, 500.0, 550.0, 680.0, 800.0}) {
        const double um = nm * 1e-3;
        const double x = um < 0.55 ? 0.389 * um + 0.09426 / um - 0.3228 : 0.04;
        const double nicolet_m2 = 4.02e-28 / std::pow(um, 4.0 + x) * 1e-4;
        EXPECT_NEAR(rayleigh_cross_section_m2(nm) / nicolet_m2, 1.0, 0.01) << nm << " nm";
    }
}

TEST(Atmosphere, RayleighAutoAgainstPublishedSeaLevelCoefficients) {
    // The graphics literature's sea-level coefficients (Bruneton & Neyret 2008, EGSR, §4;
    // Hillaire 2020): 5.8e-6, 13.5e-6, 33.1e-6 1/m at 680, 550, 440 nm. They assume
    // n - 1 = 3e-4 at every wavelength; standard air has n - 1 = 2.78e-4 at 550 nm (Peck &
    // Reeder), so (n² - 1)² is ~15% smaller and our physical values sit ~15% below them.
    const double published[3] = {5.8e-6, 13.5e-6, 33.1e-6};
    for (int i = 0; i < 3; ++i) {
        const double ours = rayleigh_scattering_standard_air(kRgbNm[static_cast<size_t>(i)]);
        EXPECT_GT(ours / published[i], 0.80) << kRgbNm[static_cast<size_t>(i)] << " nm";
        EXPECT_LT(ours / published[i], 0.92) << kRgbNm[static_cast<size_t>(i)] << " nm";
    }
    // Blue over red: lambda^-4 times the dispersion of n and of the King factor (~4% more).
    const double ratio =
        rayleigh_scattering_standard_air(440.0) / rayleigh_scattering_standard_air(680.0);
    EXPECT_GT(ratio, std::pow(680.0 / 440.0, 4.0));
    EXPECT_LT(ratio, 1.08 * std::pow(680.0 / 440.0, 4.0));
}

TEST(Atmosphere, PowerLawInterpolationOfRgbCoefficientsIsExactForLambdaMinusFour) {
    double rgb[3];
    for (int i = 0; i < 3; ++i)
        rgb[i] = std::pow(550.0 / kRgbNm[static_cast<size_t>(i)], 4.0);
    for (const double nm : {380.0, 500.0, 610.0, 800.0})
        EXPECT_NEAR(interpolate_rgb_coefficient(rgb, kRgbNm, nm), std::pow(550.0 / nm, 4.0), 1e-12);
}

TEST(Atmosphere, RaysFromGroundAndSpace) {
    const Atmosphere a = earth();
    double t0 = 0.0, t1 = 0.0;
    bool ground = false;
    // Straight down from 1.5 m hits the ground at 1.5 m.
    ASSERT_TRUE(atmosphere_segment(a, DVec3(0.0, 1.5, 0.0), DVec3(0.0, -1.0, 0.0), t0, t1, ground));
    EXPECT_TRUE(ground);
    EXPECT_NEAR(t1, 1.5, 1e-6);
    // From 200 km looking down: enters at 100 km, ends at the ground 200 km away.
    ASSERT_TRUE(
        atmosphere_segment(a, DVec3(0.0, 200e3, 0.0), DVec3(0.0, -1.0, 0.0), t0, t1, ground));
    EXPECT_NEAR(t0, 100e3, 1e-6);
    EXPECT_NEAR(t1, 200e3, 1e-6);
    // From 200 km looking up: misses the atmosphere.
    EXPECT_FALSE(
        atmosphere_segment(a, DVec3(0.0, 200e3, 0.0), DVec3(0.0, 1.0, 0.0), t0, t1, ground));
}

}  // namespace
}  // namespace kasumi
