// The reference sky against closed forms of single scattering, and its behaviour at twilight,
// at the horizon and from space (finite, non-negative, no seam).
#include "sky/sky_reference.h"
#include "sky/atmosphere_json.h"
#include "sky/sky_renderer.h"

#include <gtest/gtest.h>

namespace kasumi {
namespace {

const std::vector<double> kRgbNm{680.0, 550.0, 440.0};

std::shared_ptr<const SkyScene> make_sky(double sun_elevation_deg, int orders, bool rayleigh_only) {
    Atmosphere a = default_earth_atmosphere(kRgbNm, kRgbNm);
    if (rayleigh_only) {
        a.mie.scattering.fill(0.0);
        a.mie.absorption.fill(0.0);
        a.ozone.absorption.fill(0.0);
        a.ground_albedo.fill(0.0);
    }
    SunDesc sun;
    sun.elevation_deg = sun_elevation_deg;
    sun.azimuth_deg = 180.0;
    SkySettings settings;
    settings.mode = SkyMode::Reference;
    settings.orders = orders;
    settings.view_steps = 2000;
    settings.sun_steps = 2000;
    return make_sky_scene(a, sun, settings);
}

double zenith_tau(const Atmosphere& a, int band) {
    const double h = -1.0 / a.rayleigh.profile.upper.exp_scale_per_m;
    return a.rayleigh.scattering[band] * h * -std::expm1(-(a.top_radius_m - a.ground_radius_m) / h);
}

/// The Rayleigh phase at mu = ±1 of band i: 3 (1 + gamma) / (8 pi (1 + 2 gamma)),
/// gamma = rho / (2 - rho) (Bucholtz 1995, eq. 12 at Theta = 0).
double forward_phase(const Atmosphere& a, int band) {
    const double rho = a.rayleigh_depolarization[band];
    const double gamma = rho / (2.0 - rho);
    return 3.0 * (1.0 + gamma) / (8.0 * kPiD * (1.0 + 2.0 * gamma));
}

TEST(ReferenceSky, SingleScatteringLookingUpAtTheZenithSun) {
    // Sun at the zenith, looking straight up from the ground, Rayleigh only: the view and sun
    // paths together always cross the whole column, so T_view T_sun = exp(-tau) at every
    // height and L = p(mu = 1) tau exp(-tau) per unit irradiance.
    const auto sky = make_sky(90.0, 1, true);
    Pcg32 rng(1, 2);
    const SkySample s = reference_sky(*sky, DVec3(0.0), DVec3(0.0, 1.0, 0.0), 1e30, false, 1, rng);
    for (int i = 0; i < 3; ++i) {
        const double tau = zenith_tau(sky->atmosphere, i);
        // p(±1) = 3 (1 + gamma) / (8 pi (1 + 2 gamma)) with the band's depolarisation
        // (Bucholtz 1995, eq. 12); 3 / (8 pi) without.
        const double expected = forward_phase(sky->atmosphere, i) * tau * std::exp(-tau);
        EXPECT_NEAR(s.radiance[i] / expected, 1.0, 1e-5) << "band " << i;
        EXPECT_NEAR(s.transmittance[i], std::exp(-tau), 1e-7);  // midpoint rule, 2000 nodes
    }
}

TEST(ReferenceSky, SingleScatteringLookingDownFromTheTop) {
    // From the top looking straight down, sun at the zenith, black ground, Rayleigh only:
    // with x = tau(h, top), L = p(-1) int_0^tau e^{-2x} dx = p(-1) (1 - e^{-2 tau}) / 2.
    const auto sky = make_sky(90.0, 1, true);
    Pcg32 rng(1, 2);
    const double top = sky->atmosphere.top_radius_m - sky->atmosphere.ground_radius_m;
    const SkySample s = reference_sky(*sky, DVec3(0.0, top - 1e-3, 0.0), DVec3(0.0, -1.0, 0.0),
                                      1e30, false, 1, rng);
    for (int i = 0; i < 3; ++i) {
        const double tau = zenith_tau(sky->atmosphere, i);
        const double expected = forward_phase(sky->atmosphere, i) * 0.5 * -std::expm1(-2.0 * tau);
        EXPECT_NEAR(s.radiance[i] / expected, 1.0, 1e-5) << "band " << i;
    }
}

/// Radiance per band along elevation `elev_deg`, azimuth 180 (toward the sun) or 0.
Bands look(const SkyScene& sky, const DVec3& p, double elev_deg, double az_deg, int orders,
           uint64_t seed = 7) {
    Pcg32 rng(seed, 3);
    return reference_sky(sky, p, sun_direction(elev_deg, az_deg), 1e30, false, orders, rng)
        .radiance;
}

TEST(ReferenceSky, TwilightHorizonAndSpaceAreFiniteAndNonNegative) {
    for (const double sun_elev : {5.0, 0.0, -4.0, -10.0}) {
        auto sky = make_sky(sun_elev, 1, false);
        auto coarse = std::make_shared<SkyScene>(*sky);
        coarse->settings.view_steps = 96;
        coarse->settings.sun_steps = 32;
        for (const double cam_h : {1.5, 10e3, 100e3, 400e3}) {
            for (double e = -90.0; e <= 90.0; e += 0.25) {
                for (const double az : {0.0, 90.0, 180.0}) {
                    const Bands l = look(*coarse, DVec3(0.0, cam_h, 0.0), e, az, 1);
                    for (int i = 0; i < 3; ++i) {
                        ASSERT_TRUE(std::isfinite(l[i])) << sun_elev << " " << cam_h << " " << e;
                        ASSERT_GE(l[i], 0.0) << sun_elev << " " << cam_h << " " << e;
                    }
                }
            }
        }
    }
}

TEST(ReferenceSky, ContinuousAsTheSunCrossesTheHorizon) {
    // The disc sinks through the horizon over 2 x 0.27 deg: the sky toward it must dim smoothly
    // (no step when the disc centre crosses), sampled every 0.02 deg of sun elevation.
    double previous = -1.0;
    double largest_step = 0.0, value_at_top = 0.0;
    for (double sun_elev = 0.6; sun_elev >= -0.6; sun_elev -= 0.02) {
        auto sky = std::make_shared<SkyScene>(*make_sky(sun_elev, 1, false));
        sky->settings.view_steps = 96;
        sky->settings.sun_steps = 32;
        const double l = look(*sky, DVec3(0.0, 1.5, 0.0), 2.0, 180.0, 1)[1];
        if (previous >= 0.0)
            largest_step = std::max(largest_step, std::abs(l - previous));
        else
            value_at_top = l;
        previous = l;
    }
    // A seam would jump by a large fraction of the value; smooth dimming moves < 5% per step.
    EXPECT_LT(largest_step, 0.05 * value_at_top);
}

TEST(ReferenceSky, ContinuousInViewElevationJustAboveTheHorizon) {
    // Second differences of the sky toward the horizon stay small: no seam or spike at grazing
    // rays (camera at 1.5 m, sun at 5 deg and -4 deg).
    for (const double sun_elev : {5.0, -4.0}) {
        auto sky = std::make_shared<SkyScene>(*make_sky(sun_elev, 1, false));
        sky->settings.view_steps = 96;
        sky->settings.sun_steps = 32;
        std::vector<double> l;
        for (double e = 0.0; e <= 1.0; e += 0.05)
            l.push_back(look(*sky, DVec3(0.0, 1.5, 0.0), e, 180.0, 1)[1]);
        const double peak = *std::max_element(l.begin(), l.end());
        for (size_t k = 1; k + 1 < l.size(); ++k)
            EXPECT_LT(std::abs(l[k + 1] - 2.0 * l[k] + l[k - 1]), 0.05 * peak) << "k = " << k;
    }
}

TEST(ReferenceSky, HigherOrdersAddLightAndConverge) {
    // Orders > 1 add light (expected value of a positive continuation), and the mean over many
    // paths is stable: two independent halves agree within 5 standard errors (false-failure
    // rate ~6e-7 for a normal mean).
    const auto sky = std::make_shared<SkyScene>(*make_sky(30.0, 4, false));
    auto fast = std::make_shared<SkyScene>(*sky);
    fast->settings.view_steps = 48;
    fast->settings.sun_steps = 24;
    const DVec3 p(0.0, 1.5, 0.0);
    const double single = look(*fast, p, 45.0, 0.0, 1)[1];
    const int n = 400;
    double sum[2] = {0, 0}, sum_sq[2] = {0, 0};
    for (int k = 0; k < n; ++k) {
        const double v = look(*fast, p, 45.0, 0.0, 4, 1000 + static_cast<uint64_t>(k))[1];
        sum[k % 2] += v;
        sum_sq[k % 2] += v * v;
    }
    const double half = n / 2.0;
    double mean[2], var_of_mean[2];
    for (int h = 0; h < 2; ++h) {
        mean[h] = sum[h] / half;
        var_of_mean[h] = (sum_sq[h] / half - mean[h] * mean[h]) / (half - 1.0);
    }
    EXPECT_GT(0.5 * (mean[0] + mean[1]), single * 1.05);
    EXPECT_LT(std::abs(mean[0] - mean[1]), 5.0 * std::sqrt(var_of_mean[0] + var_of_mean[1]));
}

TEST(SunThroughTheAir, PlaneParallelAirMassAtHighSun) {
    // At 60 deg elevation the curvature of the shell changes the slant path by < 0.1%, so the
    // sun's transmittance is exp(-tau_zenith / sin(60 deg)) with tau_zenith in closed form.
    auto sky = std::make_shared<SkyScene>(*make_sky(60.0, 1, true));
    const Bands t = sun_transmittance(*sky, DVec3(0.0), 400);
    for (int i = 0; i < 3; ++i) {
        const double expected = std::exp(-zenith_tau(sky->atmosphere, i) / std::sin(kPiD / 3.0));
        EXPECT_NEAR(t[i] / expected, 1.0, 1e-3) << "band " << i;
    }
}

TEST(SunThroughTheAir, WhiteSunReddensTowardTheHorizon) {
    // The sun light handed to surfaces: dimmer and redder as the path through the air grows
    // (a white wall turns orange at sunset). At 2 deg the air mass is ~20 (Kasten & Young
    // 1989), and the blue-red optical depth difference ~0.23 makes red/blue > 10.
    double last_luminance = 1e30, last_ratio = 0.0;
    for (const double elevation : {60.0, 30.0, 10.0, 2.0}) {
        const auto sky = make_sky(elevation, 1, false);
        const Light sun = make_sun_light(*sky, true);
        const Rgb e = std::get<DirectionalLight>(sun.emitter).illuminance;
        EXPECT_LT(luminance(e), last_luminance) << elevation;
        EXPECT_GT(e.r / e.b, last_ratio) << elevation;
        last_luminance = luminance(e);
        last_ratio = e.r / e.b;
    }
    EXPECT_GT(last_ratio, 10.0);
}

}  // namespace
}  // namespace kasumi
