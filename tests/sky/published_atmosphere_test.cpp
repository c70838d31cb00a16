// Optical paths through the atmosphere and the light of twilight against published values
// (closed forms and tables typed from the sources cited at each test, not from our own output).
#include "core/error.h"
#include "lights/sun.h"
#include "sky/atmosphere_json.h"
#include "sky/sky_luts.h"
#include "sky/sky_reference.h"
#include "tests/input_error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace kasumi {
namespace {

const std::vector<double> kRgbNm{680.0, 550.0, 440.0};

/// Chapman's function: the optical depth of an exponential atmosphere over a sphere along a
/// ray from radius r at zenith angle chi, in units of the vertical optical depth, with
/// x = r / H (Chapman 1931, Proc. Phys. Soc. 43, 483, "grazing incidence"; this integral form
/// as in Huestis 2001, JQSRT 69, 709):
///   Ch(x, chi) = x sin chi ∫_0^chi exp(x - x sin chi / sin l) / sin² l dl.
/// Composite Simpson on 2^18 intervals: the integrand is a peak of width ~1/(x cot chi) (at
/// most 1/sqrt(x) at the horizon) at l = chi, resolved by thousands of nodes for x <= 1e4.
double chapman(double x, double chi) {
    if (chi == 0.0)
        return 1.0;
    const double s = std::sin(chi);
    const auto f = [&](double l) {
        const double sl = std::sin(l);
        return sl > 0.0 ? std::exp(x - x * s / sl) / (sl * sl) : 0.0;
    };
    const int n = 1 << 18;
    const double h = chi / n;
    double sum = f(0.0) + f(chi);
    for (int i = 1; i < n; ++i)
        sum += f(i * h) * (i % 2 == 1 ? 4.0 : 2.0);
    return x * s * sum * h / 3.0;
}

/// At the horizon Ch(x, 90°) = x e^x K_1(x) (Chapman 1931; Huestis 2001), whose asymptotic
/// series (Abramowitz & Stegun 9.7.2 for K_1) is sqrt(pi x / 2) (1 + 3/(8x) - 15/(128x²) +
/// 105/(1024x³)); the next term is below 1e-12 for x > 100.
double chapman_horizon(double x) {
    return std::sqrt(kPiD * x / 2.0) *
           (1.0 + 3.0 / (8.0 * x) - 15.0 / (128.0 * x * x) + 105.0 / (1024.0 * x * x * x));
}

/// The default atmosphere with its ozone removed: Rayleigh (8 km) and Mie (1.2 km) are both
/// exponential, so slant optical depths are sums of Chapman functions.
Atmosphere exponential_atmosphere() {
    Atmosphere a = default_earth_atmosphere(kRgbNm, kRgbNm);
    a.ozone.absorption = Bands{};
    return a;
}

double deg(double d) {
    return d * kPiD / 180.0;
}

TEST(PublishedChapman, IntegralMatchesTheClosedFormAtTheHorizon) {
    // The two forms of Ch(x, 90°) agree: the quadrature above is a trustworthy reference.
    for (const double x : {795.0, 5300.0})
        EXPECT_NEAR(chapman(x, deg(90.0)) / chapman_horizon(x), 1.0, 1e-9) << x;
    // Far from the horizon Ch tends to sec chi (a flat atmosphere): x = 5300, 60°: 1.99887.
    EXPECT_NEAR(chapman(5300.0, deg(60.0)), 2.0, 2e-3);
}

TEST(PublishedChapman, SlantOpticalDepthsFollowTheChapmanFunction) {
    // x = r / H for the ground at 6360 km: Rayleigh 795, Mie 5300. The relative air mass at
    // the horizon is 35.35 for the air and 91.25 for the aerosols (not sec chi = infinity); the
    // top at 100 km changes these by under 1e-5. Both the reference quadrature (96 nodes
    // crowded toward the ray's lowest point) and the fast mode's transmittance table (256 x 64,
    // Bruneton's parametrisation, bilinear) must give Chapman's optical depth; measured: within
    // 1.4e-4 (Rayleigh) and 7.5e-4 (Mie, the quadrature's second-order error) and within 4e-4
    // (the table, all bands).
    const Atmosphere a = exponential_atmosphere();
    Atmosphere air = a, aerosol = a;
    air.mie.scattering = air.mie.absorption = Bands{};
    aerosol.rayleigh.scattering = Bands{};
    SunDesc sun;
    const auto sky = make_sky_scene(a, sun, SkySettings{});
    const SkyLuts luts(*sky);
    const double x_air = a.ground_radius_m / 8000.0, x_aerosol = a.ground_radius_m / 1200.0;
    const DVec3 ground(0.0, 0.0, 0.0);
    for (const double zenith_deg : {0.0, 60.0, 80.0, 85.0, 88.0, 90.0}) {
        const double chi = deg(zenith_deg);
        const double ch_air = chapman(x_air, chi), ch_aerosol = chapman(x_aerosol, chi);
        const DVec3 d(std::sin(chi), std::cos(chi), 0.0);
        double t0 = 0.0, t1 = 0.0;
        bool hits_ground = false;
        ASSERT_TRUE(atmosphere_segment(a, ground, d, t0, t1, hits_ground));
        const Bands tau_air = atmosphere_optical_depth(air, ground, d, t0, t1, 96);
        const Bands tau_aerosol = atmosphere_optical_depth(aerosol, ground, d, t0, t1, 96);
        Bands table{};
        luts.transmittance(a.ground_radius_m, std::cos(chi), table);
        for (int i = 0; i < 3; ++i) {
            const double vertical_air = a.rayleigh.scattering[i] * 8000.0;
            const double vertical_aerosol = (a.mie.scattering[i] + a.mie.absorption[i]) * 1200.0;
            EXPECT_NEAR(tau_air[i] / (vertical_air * ch_air), 1.0, 5e-4) << zenith_deg;
            EXPECT_NEAR(tau_aerosol[i] / (vertical_aerosol * ch_aerosol), 1.0, 1.5e-3)
                << zenith_deg;
            const double chapman_tau = vertical_air * ch_air + vertical_aerosol * ch_aerosol;
            EXPECT_NEAR(-std::log(table[i]) / chapman_tau, 1.0, 1e-3)
                << zenith_deg << "° band " << i;
        }
    }
}

/// Bodhaine et al. 1999, eq. 30 (below): Rayleigh optical depth above sea level at nm.
double bodhaine_rayleigh_depth(double nm) {
    const double l2 = (nm * 1e-3) * (nm * 1e-3);
    return 0.0021520 * (1.0455996 - 341.29061 / l2 - 0.90230850 * l2) /
           (1.0 + 0.0027059889 / l2 - 85.968563 * l2);
}

/// Relative optical air mass of Kasten & Young 1989 (Appl. Opt. 28, 4735, eq. 3), fitted to
/// the ISO 2533 standard atmosphere with refraction: 1 / (cos z + 0.50572 (96.07995° - z)^-1.6364),
/// z the sun's zenith angle in degrees (37.92 at the horizon).
double kasten_young_air_mass(double zenith_deg) {
    return 1.0 / (std::cos(zenith_deg * kPiD / 180.0) +
                  0.50572 * std::pow(96.07995 - zenith_deg, -1.6364));
}

TEST(PublishedRayleigh, DirectSunThroughStandardAirIsBeerLambertWithPublishedDepthAndAirMass) {
    // The sun's transmittance through standard air alone ("auto" coefficients over the 8448 m
    // that hold Bodhaine's column, below) against Beer-Lambert with published numbers:
    // T = exp(-tau_Bodhaine(lambda) m_KY(z)). Our air mass is the straight-ray Chapman
    // function of an exponential; Kasten & Young's includes refraction and the real profile:
    // they differ by 0.3% up to z = 70° and 0.8% at 80° (2.2% at 85°, not asserted). Asserted:
    // the slant optical depth -ln T within 1% of tau m up to 70°, 1.5% at 80°.
    const std::vector<double> nm{400.0, 550.0, 700.0};
    Atmosphere a = default_earth_atmosphere(nm, kRgbNm);
    a.mie.scattering = a.mie.absorption = a.ozone.absorption = Bands{};
    a.rayleigh.profile = DensityProfile::exponential(2.1520e25 / 2.54743e19 * 1e-2);
    for (size_t i = 0; i < nm.size(); ++i)
        a.rayleigh.scattering[i] = rayleigh_scattering_standard_air(nm[i]);
    SkySettings settings;
    settings.spectral_bands = static_cast<int>(nm.size());
    for (const double zenith_deg : {0.0, 30.0, 48.19, 60.0, 70.0, 80.0}) {
        SunDesc sun;
        sun.elevation_deg = 90.0 - zenith_deg;
        const auto sky = make_sky_scene(a, sun, settings);
        const Bands t = sun_transmittance(*sky, DVec3(0.0), 2000);
        // For docs/sky.md: the default atmosphere's (Bruneton's air, aerosol and ozone).
        const auto earth = make_sky_scene(default_earth_atmosphere(nm, kRgbNm), sun, settings);
        const Bands t_earth = sun_transmittance(*earth, DVec3(0.0), 2000);
        std::printf(
            "z %5.2f: standard air T(400, 550, 700) %.4f %.4f %.4f, Beer-Lambert %.4f "
            "%.4f %.4f; default atmosphere %.4f %.4f %.4f\n",
            zenith_deg, t[0], t[1], t[2],
            std::exp(-bodhaine_rayleigh_depth(400.0) * kasten_young_air_mass(zenith_deg)),
            std::exp(-bodhaine_rayleigh_depth(550.0) * kasten_young_air_mass(zenith_deg)),
            std::exp(-bodhaine_rayleigh_depth(700.0) * kasten_young_air_mass(zenith_deg)),
            t_earth[0], t_earth[1], t_earth[2]);
        for (size_t i = 0; i < nm.size(); ++i) {
            const double published =
                bodhaine_rayleigh_depth(nm[i]) * kasten_young_air_mass(zenith_deg);
            EXPECT_NEAR(-std::log(t[i]) / published, 1.0, zenith_deg <= 70.0 ? 0.01 : 0.015)
                << zenith_deg << "° " << nm[i] << " nm";
        }
    }
    EXPECT_NEAR(kasten_young_air_mass(90.0), 37.92, 0.01);
}

TEST(PublishedRayleigh, ZenithOpticalDepthOfStandardAirFollowsBodhaine1999) {
    // Bodhaine et al. 1999, J. Atmos. Oceanic Technol. 16, 1854, eq. 30: the Rayleigh optical
    // depth of the whole atmosphere above sea level (1013.25 hPa, 45° latitude, 360 ppm CO2),
    // lambda in µm:
    //   tau = 0.0021520 (1.0455996 - 341.29061 lambda^-2 - 0.90230850 lambda²)
    //                 / (1 + 0.0027059889 lambda^-2 - 85.968563 lambda²),
    // 0.0971 at 550 nm; 0.0021520 is 1e-28 cm² times the column of molecules, 2.1520e25 cm^-2.
    // That column spread at the standard-air density of Bucholtz 1995, 2.54743e19 cm^-3, is
    // 8447.7 m thick: our "auto" coefficient of standard air with that scale height must give
    // eq. 30's optical depth at every wavelength (through the reference quadrature).
    const auto bodhaine = bodhaine_rayleigh_depth;
    EXPECT_NEAR(bodhaine(550.0), 0.0971, 1e-4);
    const double column_height_m = 2.1520e25 / 2.54743e19 * 1e-2;
    const std::vector<double> nm{400.0, 450.0, 500.0, 550.0, 600.0, 650.0, 700.0};
    Atmosphere a = default_earth_atmosphere(nm, kRgbNm);
    a.mie.scattering = a.mie.absorption = a.ozone.absorption = Bands{};
    a.rayleigh.profile = DensityProfile::exponential(column_height_m);
    for (size_t i = 0; i < nm.size(); ++i)
        a.rayleigh.scattering[i] = rayleigh_scattering_standard_air(nm[i]);
    const DVec3 up(0.0, 1.0, 0.0);
    const Bands tau =
        atmosphere_optical_depth(a, DVec3(0.0), up, 0.0, a.top_radius_m - a.ground_radius_m, 400);
    for (size_t i = 0; i < nm.size(); ++i)
        EXPECT_NEAR(tau[i] / bodhaine(nm[i]), 1.0, 0.005) << nm[i] << " nm";
    // The default (Bruneton 2017, Hillaire 2020) has 13.558e-6 1/m and 8 km at 550 nm:
    // tau = 0.1085, 12% above eq. 30; "auto" with the default 8 km gives 0.0919, 5% below
    // (documented in docs/sky.md: the 8 km exponential holds less air than the real column).
    EXPECT_NEAR(13.558e-6 * 8000.0 / bodhaine(550.0), 1.117, 0.005);
    EXPECT_NEAR(rayleigh_scattering_standard_air(550.0) * 8000.0 / bodhaine(550.0), 0.947, 0.005);
}

Atmosphere parse(const std::string& json) {
    static Json doc;  // nodes refer to it while parsing
    doc = parse_json_text(json, "scene.json");
    return parse_atmosphere(JsonNode(doc, "scene.json"), kRgbNm, kRgbNm);
}

TEST(PublishedUsStandardAtmosphere, RayleighProfileFollowsTheTableToFortyKilometres) {
    // U.S. Standard Atmosphere 1976 (NOAA/NASA/USAF), Table I, density at geometric altitude,
    // kg/m³: 1.2250 (sea level), 0.73643 (5 km), 0.41351 (10), 0.19476 (15), 0.088910 (20),
    // 0.040084 (25), 0.018410 (30), 0.0039957 (40). "profile": "us_standard_1976" is within
    // 4.2%, 1.7%, 0.6%, 1.0%, 0.2%, 1.2%, 5.9% of them; the 8 km exponential is off by
    // -15% to +107% (+34% at 25 km).
    const Atmosphere a = parse(R"({"rayleigh": {"profile": "us_standard_1976"}})");
    const std::vector<std::pair<double, double>> table = {
        {5e3, 0.73643},   {10e3, 0.41351},  {15e3, 0.19476},  {20e3, 0.088910},
        {25e3, 0.040084}, {30e3, 0.018410}, {40e3, 0.0039957}};
    EXPECT_EQ(a.rayleigh.profile.density(0.0), 1.0);
    for (const auto& [h, rho] : table) {
        EXPECT_NEAR(a.rayleigh.profile.density(h) / (rho / 1.2250), 1.0, h < 35e3 ? 0.045 : 0.065)
            << h;
    }
    // Continuous at the tropopause; the coefficient is the scene's (default Bruneton's).
    EXPECT_NEAR(a.rayleigh.profile.density(11000.0 - 1e-6), a.rayleigh.profile.density(11000.0),
                1e-9);
    EXPECT_NEAR(a.rayleigh.scattering[1], 13.558e-6, 1e-10);
    EXPECT_EQ(parse(R"({"rayleigh": {"profile": "exponential", "scale_height_m": 8000}})")
                  .rayleigh.profile.density(8000.0),
              std::exp(-1.0));
    // Bad input names the pointer.
    EXPECT_NE(input_error([] {
                  parse(R"({"rayleigh": {"profile": "mars"}})");
              }).find("/rayleigh/profile"),
              std::string::npos);
    EXPECT_NE(input_error([] {
                  parse(R"({"rayleigh": {"profile": "us_standard_1976", "scale_height_m": 8000}})");
              }).find("/rayleigh/scale_height_m"),
              std::string::npos);
}

TEST(PublishedHeightFog, ShortSegmentsIntegrateTheExponentialProfile) {
    // The air between the camera and a surface under 1 km away is integrated in one piece
    // (SkyLuts::march). Along a straight path from altitude h0 to h1 at zenith angle theta an
    // exponential layer has the optical depth sigma0 H (e^{-h0/H} - e^{-h1/H}) / cos theta
    // (the height-fog closed form; plane-parallel: over 1 km the Earth's curvature moves the
    // path by < 0.08 m). Taking the coefficients at the segment's middle instead underestimates
    // the aerosols (H = 1.2 km) of a vertical kilometre by 2.8% (their depth by the factor
    // sinh(L/2H) 2H/L) and its in-scattered light likewise. Compared: optical depth against the
    // closed form (relative 2e-4) and radiance against a 4096-node midpoint quadrature of the
    // same integrand through the same tables (relative 2e-3), from 1 m up at zenith angles 0,
    // 45, 75°, toward and away from a 30° sun.
    const Atmosphere a = default_earth_atmosphere(kRgbNm, kRgbNm);
    SunDesc sun;
    sun.elevation_deg = 30.0;
    sun.azimuth_deg = 0.0;
    const auto sky = make_sky_scene(a, sun, SkySettings{});
    const SkyLuts luts(*sky);
    const double length = 999.0, h0 = 1.0;
    for (const double zenith_deg : {0.0, 45.0, 75.0}) {
        for (const double azimuth_deg : {0.0, 180.0}) {
            const double z = deg(zenith_deg), az = deg(azimuth_deg);
            const DVec3 p(0.0, h0, 0.0);
            const DVec3 d = sun_direction(90.0 - zenith_deg, azimuth_deg);
            ASSERT_NEAR(d.y, std::cos(z), 1e-12) << az;
            Bands radiance{}, transmittance{};
            luts.march(*sky, p, d, length, 24, radiance, transmittance);
            // Reference: closed-form depth, fine quadrature of the light.
            const double h1 = h0 + length * std::cos(z);
            const auto layer = [&](double sigma0, double scale_m) {
                return sigma0 * scale_m * (std::exp(-h0 / scale_m) - std::exp(-h1 / scale_m)) /
                       std::cos(z);
            };
            const double mu = glm::dot(d, sky->sun_direction);
            Bands p_r{};
            rayleigh_phase_bands(a, mu, p_r);
            const double p_m = eval_precise(a.mie_phase, mu);
            const int nodes = 4096;
            const double dt = length / nodes;
            Bands fine{}, tau{}, ts{}, ms{};
            for (int k = 0; k < nodes; ++k) {
                const DVec3 x = p + (k + 0.5) * dt * d;
                const DVec3 up = x - a.center();
                const double r = glm::length(up);
                const AtmosphereCoefficients c = atmosphere_coefficients(a, r - a.ground_radius_m);
                luts.sun_transmittance(*sky, x, ts);
                luts.multiple_scattering(r, glm::dot(up / r, sky->sun_direction), ms);
                for (int b = 0; b < 3; ++b) {
                    fine[b] += std::exp(-(tau[b] + 0.5 * c.sigma_t[b] * dt)) * dt *
                               ((c.sigma_s_rayleigh[b] * p_r[b] + c.sigma_s_mie[b] * p_m) * ts[b] +
                                (c.sigma_s_rayleigh[b] + c.sigma_s_mie[b]) * ms[b]);
                    tau[b] += c.sigma_t[b] * dt;
                }
            }
            for (int b = 0; b < 3; ++b) {
                const double depth = layer(a.rayleigh.scattering[b], 8000.0) +
                                     layer(a.mie.scattering[b] + a.mie.absorption[b], 1200.0);
                EXPECT_NEAR(-std::log(transmittance[b]) / depth, 1.0, 2e-4)
                    << zenith_deg << "° az " << azimuth_deg << " band " << b;
                EXPECT_NEAR(radiance[b] / fine[b], 1.0, 2e-3)
                    << zenith_deg << "° az " << azimuth_deg << " band " << b;
            }
        }
    }
}

/// Horizontal illuminance of the sky alone (all orders, the ground's reflections included; the
/// sun's disc is below the horizon), lux, from the fast mode's ground irradiance table.
double sky_illuminance_lux(const Atmosphere& a, double sun_elevation_deg) {
    SunDesc sun;
    sun.elevation_deg = sun_elevation_deg;
    const auto sky = make_sky_scene(a, sun, SkySettings{});
    const SkyLuts luts(*sky);
    Bands e{};
    luts.ground_sky_irradiance(std::sin(deg(sun_elevation_deg)), e);
    return luminance(sky->to_rgb(e));
}

TEST(PublishedTwilight, IlluminanceAtSunsetAndAtTheEndsOfCivilAndNauticalTwilight) {
    // AMS Glossary of Meteorology ("civil twilight", "nautical twilight"): on a clear evening
    // the horizontal illuminance falls from ~410-585 lux when the sun's unrefracted centre
    // sets to ~2-3.5 lux at -6° and ~0.008 lux at -12°. The light there is sunlight scattered
    // by air 10-40 km up, in the Earth's shadow's edge: the test needs the real stratosphere,
    // not the 8 km exponential of the default, whose air at 20-30 km is 1.1-1.6 times too
    // dense (it gives 1086, 8.2 and 0.025 lux: docs/sky.md). So: "profile":
    // "us_standard_1976" (the test above), standard-air Rayleigh ("auto"); Bruneton's aerosol
    // times 20 (optical depth 0.107, a clear evening). Measured (RGB): 846, 2.59, 0.0048 lux (16
    // wavelengths: 817, 2.30, 0.0041). Bounds: sunset and -6° within the published range
    // widened by 2x below and above for the model's idealisations (no refraction, a smooth
    // ground of albedo 0.3, one aerosol), -12° within 2.5x of 0.008 lux. The default's
    // stratosphere fails at -6° (8.2 lux).
    const Atmosphere a =
        parse(R"({"rayleigh": {"scattering": "auto", "profile": "us_standard_1976"},
                                   "mie": {"scattering": 7.992e-5, "extinction": 8.88e-5}})");
    const double sunset = sky_illuminance_lux(a, 0.0);
    EXPECT_GT(sunset, 410.0 / 2.0);
    EXPECT_LT(sunset, 585.0 * 2.0);
    const double civil = sky_illuminance_lux(a, -6.0);
    EXPECT_GT(civil, 2.0 / 2.0);
    EXPECT_LT(civil, 3.5 * 2.0);
    const double nautical = sky_illuminance_lux(a, -12.0);
    EXPECT_GT(nautical, 0.008 / 2.5);
    EXPECT_LT(nautical, 0.008 * 2.5);
    // The default atmosphere is brighter at -6° than the published range allows (its denser
    // stratosphere), which is why the test above models the standard atmosphere.
    EXPECT_GT(sky_illuminance_lux(default_earth_atmosphere(kRgbNm, kRgbNm), -6.0), 2.0 * 3.5);
}

}  // namespace
}  // namespace kasumi
