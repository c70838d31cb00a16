// The fast sky (tables after Hillaire 2020) against the reference (quadrature + Monte Carlo
// orders) over the sky dome: relative luminance error for sun elevations 90, 30, 5, 0, -4 deg.
// The printed table is the one in docs/sky.md and the README.
#include "sky/atmosphere_json.h"
#include "sky/sky_dome_psnr.h"
#include "sky/sky_luts.h"
#include "sky/sky_reference.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <vector>

namespace kasumi {
namespace {

const std::vector<double> kRgbNm{680.0, 550.0, 440.0};

struct DomeError {
    double max_rel = 0.0;
    double mean_rel = 0.0;
    double max_ref_stderr = 0.0;  ///< largest relative standard error of the reference
    double mean_signed = 0.0;     ///< mean of (fast - reference) / reference
    /// Largest |fast - reference| over the dome's brightest reference direction: in deep
    /// twilight single scattering lights only a thin band of sky and the relative error of
    /// directions 1e-4 as bright as that band says nothing about the image.
    double max_over_peak = 0.0;
};

double luminance_of(const SkyScene& sky, const Bands& b) {
    return static_cast<double>(luminance(sky.to_rgb(b)));
}

/// Sky dome of 6 elevations (2 to 80 deg) x 6 azimuths from the sun (0 to 180 deg; the sky is
/// symmetric about the sun's vertical plane), camera 1.5 m above the ground.
int env_int(const char* name, int fallback) {
    const char* v = std::getenv(name);
    return v != nullptr ? std::atoi(v) : fallback;
}

/// `seed` moves the reference's random streams (0: the asserted reference).
DomeError measure(double sun_elevation_deg, int reference_paths, int orders, uint64_t seed = 0) {
    SunDesc sun;
    sun.elevation_deg = sun_elevation_deg;
    sun.azimuth_deg = 0.0;
    SkySettings settings;
    settings.mode = SkyMode::Reference;
    settings.orders = orders;
    settings.view_steps = 64;
    settings.sun_steps = 24;
    const auto sky = make_sky_scene(default_earth_atmosphere(kRgbNm, kRgbNm), sun, settings);
    SkyLuts luts(*sky);
    if (orders == 1)
        luts.disable_multiple_scattering();
    const DVec3 camera(0.0, 1.5, 0.0);
    luts.build_sky_view(*sky, camera);
    DomeError out;
    int count = 0;
    double peak = 0.0, max_abs = 0.0;
    for (const double elev : {2.0, 10.0, 20.0, 35.0, 55.0, 80.0}) {
        for (const double az : {0.0, 36.0, 72.0, 108.0, 144.0, 180.0}) {
            const DVec3 d = sun_direction(elev, az);
            Bands fast{};
            luts.sky_view(*sky, d, fast);
            const double y_fast = luminance_of(*sky, fast);
            double sum = 0.0, sum_sq = 0.0;
            for (int k = 0; k < reference_paths; ++k) {
                Pcg32 rng(static_cast<uint64_t>(k) * 7919u + 17u + seed * 1000003u,
                          static_cast<uint64_t>(count));
                const double y = luminance_of(
                    *sky,
                    reference_sky(*sky, camera, d, 1e30, false, settings.orders, rng).radiance);
                sum += y;
                sum_sq += y * y;
            }
            const double n = reference_paths;
            const double y_ref = sum / n;
            const double stderr_ref =
                n > 1 ? std::sqrt(std::max(0.0, sum_sq / n - y_ref * y_ref) / (n - 1.0)) : 0.0;
            if (!(y_ref > 0.0) && !(y_fast > 0.0))
                continue;  // both dark (single scattering in the Earth's shadow)
            const double rel = std::abs(y_fast - y_ref) / y_ref;
            out.max_rel = std::max(out.max_rel, rel);
            peak = std::max(peak, y_ref);
            max_abs = std::max(max_abs, std::abs(y_fast - y_ref));
            out.mean_rel += rel;
            out.mean_signed += (y_fast - y_ref) / y_ref;
            out.max_ref_stderr = std::max(out.max_ref_stderr, stderr_ref / y_ref);
            ++count;
        }
    }
    out.mean_rel /= count;
    out.mean_signed /= count;
    out.max_over_peak = peak > 0.0 ? max_abs / peak : 0.0;
    return out;
}

TEST(FastSky, SingleScatteringTablesAgainstReference) {
    // Deterministic: single scattering through the tables (transmittance LUT, sky-view LUT,
    // 40 nodes) against the double-precision quadrature (64 view x 24 sun nodes). From -6 deg
    // down the sky's single scattering comes from a thin band of lit air toward the sun and
    // the relative error of the rest (1e-4 of that band and less) is not meaningful: the
    // twilight bounds are on the error over the dome's brightest direction (max_over_peak;
    // measured 0.2-0.4%, bound 1%) and the mean relative error (measured 4-9%, bound 15%); the
    // max relative error (29x at -6 deg, where the reference is 7e-6 cd/m²) is not bounded.
    struct Case {
        double sun_elevation_deg, max_bound, mean_bound, peak_bound;
    };
    const Case cases[] = {{90.0, 0.015, 0.005, 0.015}, {30.0, 0.015, 0.005, 0.015},
                          {5.0, 0.015, 0.005, 0.015},  {0.0, 0.015, 0.005, 0.015},
                          {-4.0, 0.04, 0.015, 0.04},   {-6.0, 1e9, 0.15, 0.01},
                          {-8.0, 1e9, 0.15, 0.01},     {-10.0, 1e9, 0.15, 0.01}};
    std::printf("single scattering\nsun_deg  max_rel  mean_rel  max_over_peak\n");
    for (const Case& c : cases) {
        const DomeError e = measure(c.sun_elevation_deg, 1, 1);
        std::printf("%7.1f  %7.4f  %8.4f  %8.5f\n", c.sun_elevation_deg, e.max_rel, e.mean_rel,
                    e.max_over_peak);
        EXPECT_LT(e.max_rel, c.max_bound) << "sun " << c.sun_elevation_deg;
        EXPECT_LT(e.mean_rel, c.mean_bound) << "sun " << c.sun_elevation_deg;
        EXPECT_LT(e.max_over_peak, c.peak_bound) << "sun " << c.sun_elevation_deg;
    }
}

TEST(FastSky, LuminanceErrorAgainstReferenceOverTheDome) {
    // Documented bounds (docs/sky.md) on the relative luminance error against a 6-order
    // reference of 48 paths per direction with fixed seeds (the result is deterministic).
    // Measured against an independent 512-path reference the tables' own error is max 4-7%,
    // mean ~2% with the sun at or above the horizon, max 17% (the reference's noise: 13%),
    // mean 4% at -4 deg; the reference's own noise at 48 paths is up to 7% (34% at -4 deg).
    // The max and mean bounds allow for that noise; the mean signed error averages it over 36
    // directions (its standard error ~1%, ~2% at -4 deg) and catches bias: the previous
    // tables (Hillaire's local geometric series for orders above two) were biased by -3.7%,
    // -5.6%, -5.7% and -10% at 30, 5, 0 and -4 deg and fail it.
    struct Case {
        double sun_elevation_deg;
        double max_bound;
        double mean_bound;
        double signed_bound;
    };
    const Case cases[] = {{90.0, 0.25, 0.06, 0.025},
                          {30.0, 0.25, 0.06, 0.025},
                          {5.0, 0.25, 0.06, 0.03},
                          {0.0, 0.25, 0.06, 0.03},
                          {-4.0, 0.40, 0.12, 0.06}};
    std::printf("all orders (reference: 6 orders, 48 paths per direction)\n");
    std::printf("sun_deg  max_rel  mean_rel  ref_rel_stderr_max  mean_signed\n");
    for (const Case& c : cases) {
        const DomeError e = measure(c.sun_elevation_deg, 48, 6);
        std::printf("%7.1f  %7.4f  %8.4f  %8.4f  %+8.4f\n", c.sun_elevation_deg, e.max_rel,
                    e.mean_rel, e.max_ref_stderr, e.mean_signed);
        EXPECT_LT(e.max_rel, c.max_bound) << "sun " << c.sun_elevation_deg;
        EXPECT_LT(e.mean_rel, c.mean_bound) << "sun " << c.sun_elevation_deg;
        EXPECT_LT(std::abs(e.mean_signed), c.signed_bound) << "sun " << c.sun_elevation_deg;
    }
    // The documented figures (docs/sky.md): KASUMI_SKY_SUN (one elevation), KASUMI_SKY_PATHS,
    // KASUMI_SKY_ORDERS and KASUMI_SKY_SEED print one more row measured their way. They only
    // add output: the asserted rows above never depend on the environment.
    const char* sun = std::getenv("KASUMI_SKY_SUN");
    if (sun != nullptr || std::getenv("KASUMI_SKY_PATHS") != nullptr ||
        std::getenv("KASUMI_SKY_ORDERS") != nullptr || std::getenv("KASUMI_SKY_SEED") != nullptr) {
        std::vector<double> elevations = {90.0, 30.0, 5.0, 0.0, -4.0};
        if (sun != nullptr)
            elevations = {std::atof(sun)};
        const int paths = env_int("KASUMI_SKY_PATHS", 48), orders = env_int("KASUMI_SKY_ORDERS", 6);
        const int seed = env_int("KASUMI_SKY_SEED", 0);
        std::printf("not asserted (%d orders, %d paths, seed %d):\n", orders, paths, seed);
        for (const double elevation : elevations) {
            const DomeError e =
                measure(elevation, paths, orders, static_cast<uint64_t>(std::max(seed, 0)));
            std::printf("%7.1f  %7.4f  %8.4f  %8.4f  %+8.4f\n", elevation, e.max_rel, e.mean_rel,
                        e.max_ref_stderr, e.mean_signed);
        }
    }
}

TEST(FastSky, DomePsnrOfLuminanceAgainstTwoHalfReference) {
    // Issue #22's accuracy target at the sunset: PSNR of luminance over the dome >= 40 dB with
    // the sun at 2 deg (sky/sky_dome_psnr.h: peak the dome's brightest reference direction, the
    // reference's noise taken out with two independent halves). A reduced dome of 6 x 8
    // equal-area directions and a 6-order reference of 128 paths with fixed seeds
    // (deterministic; measured 43.4 dB, noise 47.4 dB, single scattering 70.5 dB);
    // bench/sky_accuracy.sh measures 12 x 16 directions at 512 paths (47.8 dB). The bound on
    // noise_db keeps the measurement meaningful. (At 30 deg this cost's reference is too noisy
    // to assert 45 dB: noise 40.8 dB.)
    DomePsnrOptions options;
    options.rings = 6;
    options.azimuths = 8;
    options.paths = 128;
    const DomePsnr p = dome_psnr(2.0, options);
    std::printf(
        "sun 2 deg: psnr %.2f dB, raw %.2f, noise %.2f, single %.2f, march %.2f, "
        "signed %+.4f\n",
        p.psnr_db, p.raw_db, p.noise_db, p.single_db, p.march_db, p.signed_rel);
    EXPECT_GE(p.psnr_db, 40.0);
    EXPECT_GE(p.noise_db, 43.0);
    // Single scattering through the tables is nearly exact.
    EXPECT_GE(p.single_db, 60.0);
}

TEST(FastSky, SkyViewFiniteNonNegativeAndSeamlessInDeepTwilightAndFromSpace) {
    // The sky-view table with the sun at -10 deg from the ground, and from the top of the
    // atmosphere (100 km) and space (120 km) with the sun at -10 and 30 deg: every direction of
    // a 1-degree grid (elevations -90 to 90) finite and >= 0, and no seam where the table's
    // azimuth wraps (toward the sun): +-0.01 deg either side agree to 1e-3.
    for (const double camera_m : {1.5, 100e3, 120e3}) {
        for (const double sun_deg : {-10.0, 30.0}) {
            SunDesc sun;
            sun.elevation_deg = sun_deg;
            sun.azimuth_deg = 0.0;
            const auto sky = make_sky_scene(default_earth_atmosphere(kRgbNm, kRgbNm), sun, {});
            SkyLuts luts(*sky);
            luts.build_sky_view(*sky, DVec3(0.0, camera_m, 0.0));
            for (int e = -90; e <= 90; ++e) {
                for (int az = 0; az < 360; ++az) {
                    Bands l{};
                    luts.sky_view(*sky, sun_direction(e, az), l);
                    for (int i = 0; i < 3; ++i)
                        ASSERT_TRUE(std::isfinite(l[i]) && l[i] >= 0.0)
                            << camera_m << " m, sun " << sun_deg << ", " << e << "/" << az;
                }
                Bands a{}, b{};
                luts.sky_view(*sky, sun_direction(e, 0.01), a);
                luts.sky_view(*sky, sun_direction(e, -0.01), b);
                const double ya = luminance_of(*sky, a), yb = luminance_of(*sky, b);
                EXPECT_LE(std::abs(ya - yb), 1e-3 * std::max(ya, yb) + 1e-12)
                    << camera_m << " m, sun " << sun_deg << ", elevation " << e;
            }
        }
    }
}

TEST(FastSky, TablesIdenticalWithOneAndTwoThreads) {
    // The transmittance, multiple-scattering and ground-irradiance tables (built with
    // tbb::parallel_for; each texel's sums in a fixed order) do not depend on the thread count:
    // every lookup on a grid of radii and cosines equal bit for bit with 1 and 2 threads.
    SunDesc sun;
    sun.elevation_deg = 30.0;
    const auto sky = make_sky_scene(default_earth_atmosphere(kRgbNm, kRgbNm), sun, {});
    const auto build = [&](int threads) {
        std::unique_ptr<SkyLuts> luts;
        tbb::task_arena(threads).execute([&] { luts = std::make_unique<SkyLuts>(*sky); });
        return luts;
    };
    const auto one = build(1), two = build(2);
    const double rg = sky->atmosphere.ground_radius_m, rt = sky->atmosphere.top_radius_m;
    for (int k = 0; k <= 20; ++k) {
        const double r = rg + (rt - rg) * k * k / 400.0;
        for (int m = -20; m <= 20; ++m) {
            const double mu = m / 20.0;
            Bands a{}, b{};
            one->multiple_scattering(r, mu, a);
            two->multiple_scattering(r, mu, b);
            EXPECT_EQ(a, b) << "multiple scattering r " << r << " mu_s " << mu;
            one->transmittance(r, mu, a);
            two->transmittance(r, mu, b);
            EXPECT_EQ(a, b) << "transmittance r " << r << " mu " << mu;
            one->ground_sky_irradiance(mu, a);
            two->ground_sky_irradiance(mu, b);
            EXPECT_EQ(a, b) << "ground irradiance mu_s " << mu;
        }
    }
}

TEST(FastSky, GroundSkyIrradianceIsFiniteNonNegativeAndFallsThroughTwilight) {
    // The sky's irradiance on the ground (table built with the multiple-scattering table):
    // finite and non-negative for every sun cosine, decreasing as the sun sinks from 45 deg into
    // the night (near the zenith it may grow slightly: the longer slant path scatters more), and
    // of the right size at noon: a clear sky adds about 10-20% to the direct sun's horizontal
    // irradiance (our default atmosphere: direct 0.74 at the zenith sun, per unit TOA
    // irradiance), so the bound [0.05, 0.3] fails a table off by a factor of 2 either way.
    const SunDesc sun;
    SkySettings settings;
    const auto sky = make_sky_scene(default_earth_atmosphere(kRgbNm, kRgbNm), sun, settings);
    const SkyLuts luts(*sky);
    double previous = 1e30;
    for (double mu_s = 1.0; mu_s >= -1.0; mu_s -= 0.01) {
        Bands e{};
        luts.ground_sky_irradiance(mu_s, e);
        for (int i = 0; i < 3; ++i) {
            ASSERT_TRUE(std::isfinite(e[i])) << mu_s;
            ASSERT_GE(e[i], 0.0) << mu_s;
        }
        const double y = luminance_of(*sky, e) / sun.illuminance_lux;
        if (mu_s < 0.7) {
            EXPECT_LE(y, previous * 1.0001 + 1e-9) << "mu_s " << mu_s;
        }
        previous = y;
        if (std::abs(mu_s - 1.0) < 1e-9) {
            EXPECT_GT(y, 0.05);
            EXPECT_LT(y, 0.3);
        }
    }
}

}  // namespace
}  // namespace kasumi
