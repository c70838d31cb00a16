// Decomposition tracking (volume/decomposition_tracking.h) against closed forms and a fine
// march. A free flight's contract: over escapes its weight estimates T(ray); over scatterings
// weight * k.sigma_s * g(t) estimates the integral of T(t) sigma_s(t) g(t) dt for any g.
#include "volume/decomposition_tracking.h"

#include "core/rng.h"
#include "tests/sample_mean.h"
#include "tests/volume/smooth_cloud.h"
#include "volume/medium_set.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace kasumi {
namespace {

using test::constant_grid;
using test::grid_media;
using test::smooth_cloud;

/// The two halves of the contract for one flight, red channel: the escape weight, and the
/// scattering estimate weight * sigma_s * g(t) with g = 1 and with g = (t - t_min) / length.
struct FlightSample {
    double escape = 0.0, scattered = 0.0, scattered_t = 0.0;
};

FlightSample flight_sample(const MediumSet& media, const Ray& ray, Pcg32& rng,
                           VolumeCounters& counters) {
    const FreeFlight f = sample_free_flight_decomposition(media, ray, Rgb(1.0f), rng, counters);
    FlightSample s;
    const double w = f.weight.r;
    if (!f.scattered) {
        s.escape = w;
        return s;
    }
    s.scattered = w * f.k.sigma_s.r;
    s.scattered_t = s.scattered * (f.t - ray.t_min) / (ray.t_max - ray.t_min);
    return s;
}

struct FlightMeans {
    MeanAndError escape, scattered, scattered_t;
};

FlightMeans flight_means(const MediumSet& media, const Ray& ray, int n, uint64_t seed,
                         VolumeCounters& counters) {
    SampleMean escape, scattered, scattered_t;
    for (int i = 0; i < n; ++i) {
        Pcg32 rng(seed, static_cast<uint64_t>(i));
        const FlightSample s = flight_sample(media, ray, rng, counters);
        escape.add(s.escape);
        scattered.add(s.scattered);
        scattered_t.add(s.scattered_t);
    }
    return {escape.result(), scattered.result(), scattered_t.result()};
}

/// The three expectations by a 1/64-voxel trapezoid march along the ray inside the medium's
/// box `bounds` (index space is world space in these grids; the media hold nothing outside it):
/// T(t_max), and the integrals of T sigma_s and T sigma_s g.
struct MarchedFlight {
    double transmittance = 1.0, scattered = 0.0, scattered_t = 0.0;
};
MarchedFlight fine_march(const MediumSet& media, const Bounds3& bounds, const Ray& ray) {
    MarchedFlight m;
    const auto span = bounds.clip(ray);
    if (!span)
        return m;
    constexpr double h = 1.0 / 64.0;
    const double t0 = span->first, length = span->second - span->first;
    const int n = std::max(1, static_cast<int>(std::ceil(length / h)));
    const double dt = length / n, scale = 1.0 / (ray.t_max - ray.t_min);
    double tau = 0.0, f_prev = 0.0, g_prev = 0.0;
    PointCoefficients prev;
    for (int i = 0; i <= n; ++i) {
        const double t = t0 + i * dt;
        const PointCoefficients k = media.coefficients(ray.at(static_cast<float>(t)), 1u);
        if (i > 0)
            tau += 0.5 * dt * (prev.sigma_t.r + k.sigma_t.r);
        const double f = std::exp(-tau) * k.sigma_s.r, g = f * (t - ray.t_min) * scale;
        if (i > 0) {
            m.scattered += 0.5 * dt * (f_prev + f);
            m.scattered_t += 0.5 * dt * (g_prev + g);
        }
        f_prev = f;
        g_prev = g;
        prev = k;
    }
    m.transmittance = std::exp(-tau);
    return m;
}

TEST(DecompositionTracking, ConstantBoxIsTheExponentialWithoutLookups) {
    // Minorant = majorant in every brick the ray crosses: the control part is the whole medium,
    // the residual majorant is 0, so no tentative collision and no density lookup is made, and
    // the flight is the exponential distribution exactly: escape weight 1 with probability
    // exp(-tau), else a scattering at t - 9 ~ Exp(sigma_t) (the box starts 9 m along the ray)
    // with weight * k.sigma_s = albedo.
    // Binomial checks within 4 standard errors (false failure 6e-5 per check).
    for (const float sigma_t : {0.01f, 0.1f, 1.0f}) {
        const MediumSet media = grid_media(constant_grid(), sigma_t, test::kConstantBox);
        const Ray ray{Vec3(-2.0f, 10.3f, 11.1f), Vec3(1.0f, 0.0f, 0.0f), 0.0f, 30.0f};
        const double tau = 15.0 * sigma_t, albedo = 0.8;
        VolumeCounters counters;
        const FlightMeans m = flight_means(media, ray, 200000, 3, counters);
        EXPECT_EQ(counters.density_lookups, 0u) << "sigma_t " << sigma_t;
        const double escape = std::exp(-tau);
        EXPECT_NEAR(m.escape.mean, escape, 4.0 * std::sqrt(escape * (1 - escape) / 200000));
        // (+1e-6: the albedo 0.8 in float; the scattering weight has no variance at all here.)
        EXPECT_NEAR(m.scattered.mean, albedo * (1.0 - escape), 4.0 * m.scattered.stderr_ + 1e-6);
        // The scattering point: E[t / 30 ; t < 24] for t - 9 ~ Exp(sigma_t).
        const double mean_t =
            (1.0 - escape * (1.0 + tau)) / sigma_t;  // integral of x sigma e^(-sigma x), 0..15
        EXPECT_NEAR(m.scattered_t.mean, albedo * (9.0 * (1.0 - escape) + mean_t) / 30.0,
                    4.0 * m.scattered_t.stderr_ + 1e-6);
    }
}

TEST(DecompositionTracking, MatchesAFineMarchOnASmoothCloudAndCatchesA2PercentBias) {
    // Four rays (through the centre, off centre, starting inside, through the corner block): each
    // half of the contract within 4 standard errors of the 1/64-voxel march (false failure
    // ~6e-5 per check, 12 checks), with teeth: 4 standard errors are below 1% of each value, so
    // the same means scaled by 1.02 (a planted 2% bias in the weights) are 8 standard errors
    // off and must fail.
    const Bounds3 box{Vec3(0.0f), Vec3(39.0f)};
    const MediumSet media = grid_media(smooth_cloud(), 0.04f, box);
    const Ray rays[] = {
        {Vec3(-5.0f, 19.3f, 20.7f), glm::normalize(Vec3(1.0f, 0.05f, -0.02f)), 0.0f, 60.0f},
        {Vec3(-5.0f, 27.0f, 12.0f), glm::normalize(Vec3(1.0f, -0.1f, 0.15f)), 0.0f, 60.0f},
        {Vec3(20.2f, 21.1f, 19.4f), glm::normalize(Vec3(0.2f, -1.0f, 0.4f)), 0.5f, 30.0f},
        {Vec3(-1.0f, 2.0f, 3.0f), glm::normalize(Vec3(1.0f, 0.9f, 0.8f)), 0.0f, 60.0f},
    };
    const auto within = [](const MeanAndError& e, double exact, double scale) {
        return std::abs(scale * e.mean - exact) < 4.0 * scale * e.stderr_;
    };
    for (const Ray& ray : rays) {
        const MarchedFlight reference = fine_march(media, box, ray);
        ASSERT_GT(reference.transmittance, 0.01);
        ASSERT_LT(reference.transmittance, 0.95);
        VolumeCounters counters;
        const FlightMeans m = flight_means(media, ray, 1000000, 7, counters);
        std::printf(
            "T %.5f +- %.5f (march %.5f), scattered %.5f +- %.5f (%.5f), "
            "t-weighted %.5f +- %.5f (%.5f)\n",
            m.escape.mean, m.escape.stderr_, reference.transmittance, m.scattered.mean,
            m.scattered.stderr_, reference.scattered, m.scattered_t.mean, m.scattered_t.stderr_,
            reference.scattered_t);
        EXPECT_TRUE(within(m.escape, reference.transmittance, 1.0));
        EXPECT_TRUE(within(m.scattered, reference.scattered, 1.0));
        EXPECT_TRUE(within(m.scattered_t, reference.scattered_t, 1.0));
        EXPECT_LT(4.0 * m.escape.stderr_, 0.01 * reference.transmittance);
        EXPECT_LT(4.0 * m.scattered.stderr_, 0.01 * reference.scattered);
        EXPECT_LT(4.0 * m.scattered_t.stderr_, 0.01 * reference.scattered_t);
        EXPECT_FALSE(within(m.escape, reference.transmittance, 1.02));
        EXPECT_FALSE(within(m.scattered, reference.scattered, 1.02));
        EXPECT_FALSE(within(m.scattered_t, reference.scattered_t, 1.02));
    }
}

TEST(DecompositionTracking, SkipsTheLookupsOfTheMinorant) {
    // Across the whole constant grid (16 of its 23 voxels in bricks whose minorant is the
    // majorant, the rest in the edge bricks that hold the zero apron): spectral tracking looks
    // the density up at every tentative collision (rate: the majorant), decomposition tracking
    // only at the residual's (rate: majorant - minorant, 0 inside), so it makes fewer than half
    // the lookups; on the smooth cloud (minorants mostly 0) it makes no more.
    const Ray ray{Vec3(-2.0f, 10.3f, 11.1f), Vec3(1.0f, 0.0f, 0.0f), 0.0f, 30.0f};
    const Ray through_cloud{Vec3(-5.0f, 19.3f, 20.7f), glm::normalize(Vec3(1.0f, 0.05f, -0.02f)),
                            0.0f, 60.0f};
    const MediumSet box = grid_media(constant_grid(), 0.05f, Bounds3{Vec3(0.5f), Vec3(23.5f)});
    const MediumSet cloud = grid_media(smooth_cloud(), 0.07f, Bounds3{Vec3(0.0f), Vec3(39.0f)});
    for (const auto& [media, r] : {std::pair{&box, ray}, std::pair{&cloud, through_cloud}}) {
        VolumeCounters tracking, decomposition;
        for (uint64_t i = 0; i < 20000; ++i) {
            Pcg32 a(5, i), b(5, i);
            sample_free_flight(*media, r, Rgb(1.0f), a, tracking);
            sample_free_flight_decomposition(*media, r, Rgb(1.0f), b, decomposition);
        }
        std::printf("lookups per flight: tracking %.3f, decomposition %.3f\n",
                    tracking.density_lookups / 20000.0, decomposition.density_lookups / 20000.0);
        if (media == &box)
            EXPECT_LT(decomposition.density_lookups, tracking.density_lookups / 2);
        else
            EXPECT_LE(decomposition.density_lookups, tracking.density_lookups);
    }
}

TEST(DecompositionTracking, ExtremeOpticalDepthsStayFinite) {
    // Optical depths ~1e-8 to ~1e4 through the constant box (the exponential, exact: escape
    // with probability exp(-tau)) and through the smooth cloud (weights finite, escape mean in
    // [0, 1], scattering estimate in [0, albedo]).
    for (const double tau : {1e-8, 1e-4, 1.0, 1e2, 1e4}) {
        const float sigma_t = static_cast<float>(tau / 15.0);
        const MediumSet box = grid_media(constant_grid(), sigma_t, test::kConstantBox);
        const Ray ray{Vec3(-2.0f, 10.3f, 11.1f), Vec3(1.0f, 0.0f, 0.0f), 0.0f, 30.0f};
        VolumeCounters counters;
        const FlightMeans m = flight_means(box, ray, 20000, 9, counters);
        const double escape = std::exp(-tau);
        EXPECT_NEAR(m.escape.mean, escape, 4.0 * std::sqrt(escape * (1 - escape) / 20000) + 1e-12)
            << "tau " << tau;
        EXPECT_TRUE(std::isfinite(m.scattered.mean) && std::isfinite(m.scattered_t.mean));
        const MediumSet cloud =
            grid_media(smooth_cloud(), sigma_t / 1.2f, Bounds3{Vec3(0.0f), Vec3(39.0f)});
        const Ray through{Vec3(-5.0f, 19.3f, 20.7f), glm::normalize(Vec3(1.0f, 0.05f, -0.02f)),
                          0.0f, 60.0f};
        for (uint64_t i = 0; i < 2000; ++i) {
            Pcg32 rng(13, i);
            const FlightSample s = flight_sample(cloud, through, rng, counters);
            ASSERT_TRUE(std::isfinite(s.escape) && std::isfinite(s.scattered)) << "tau " << tau;
            ASSERT_GE(s.escape, 0.0);
            ASSERT_GE(s.scattered, 0.0);
        }
        const FlightMeans c = flight_means(cloud, through, 2000, 15, counters);
        EXPECT_LE(c.escape.mean, 1.0 + 4.0 * c.escape.stderr_) << "tau " << tau;
        EXPECT_LE(c.scattered.mean, 0.8 + 4.0 * c.scattered.stderr_) << "tau " << tau;
    }
}

}  // namespace
}  // namespace kasumi
