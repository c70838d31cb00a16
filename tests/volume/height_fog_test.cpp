// Height fog (volume/height_fog.h): sigma(x) = sigma(h0) exp(-(y - h0) / H), y up. The
// closed-form optical depth against independent references (the vertical and horizontal closed
// forms, a Taylor series for nearly horizontal rays, Simpson quadrature in long double), the
// unbiased trackers against it, marched single scattering against a quadrature of the exact
// integral, the limit H -> infinity against the homogeneous medium, and bad input as located
// input errors.
#include "volume/height_fog.h"
#include "core/json_node.h"
#include "core/rng.h"
#include "lights/light.h"
#include "volume/medium_json.h"
#include "volume/medium_set.h"
#include "volume/transmittance.h"
#include "volume/volume_path.h"

#include "../input_error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iterator>
#include <string>

namespace kasumi {
namespace {

Medium parse(const std::string& text) {
    return parse_medium(JsonNode(parse_json_text(text, "fog.json"), "fog.json", "/media/0"), 0);
}

std::string error_of(const std::string& text) {
    return input_error([&] { parse(text); });
}

HeightFogMedium fog(float sigma_a, float sigma_s, double h0, double H) {
    HeightFogMedium m;
    m.sigma_a = Rgb(sigma_a);
    m.sigma_s = Rgb(sigma_s);
    m.reference_height_m = h0;
    m.scale_height_m = H;
    m.cap_density();
    return m;
}

Medium as_medium(const HeightFogMedium& m) {
    return Medium{"fog", m};
}

Vec3 direction(double dy) {
    return Vec3(static_cast<float>(std::sqrt(1.0 - dy * dy)), static_cast<float>(dy), 0.0f);
}

/// Simpson's rule in long double of sigma_t(h0) exp(-(y(t) - h0) / H) over [t0, t1].
double simpson_depth(double sigma_t, double h0, double H, double oy, double dy, double t0,
                     double t1, int n = 20000) {
    const long double h = (static_cast<long double>(t1) - t0) / n;
    long double sum = 0.0L;
    for (int i = 0; i <= n; ++i) {
        const long double t = t0 + h * i;
        const long double f = std::exp(-(oy + dy * t - h0) / static_cast<long double>(H));
        sum += f * (i == 0 || i == n ? 1 : (i % 2 == 1 ? 4 : 2));
    }
    return static_cast<double>(sigma_t * sum * h / 3.0L);
}

// Vertical rays: tau = sigma_t(h0) H (e^{-(y_a - h0)/H} - e^{-(y_b - h0)/H}) exactly, up and down.
TEST(HeightFog, VerticalRaysMatchTheClosedForm) {
    const HeightFogMedium m = fog(0.01f, 0.04f, 2.0, 25.0);
    const MediumSet media({as_medium(m)});
    const double sigma_t = m.sigma_t().r;
    const double up =
        sigma_t * 25.0 * (std::exp(-(-3.0 - 2.0) / 25.0) - std::exp(-(97.0 - 2.0) / 25.0));
    const Rgb tau_up = media.optical_depth(Ray{Vec3(1, -3, 4), Vec3(0, 1, 0), 0.0f, 100.0f});
    EXPECT_NEAR(tau_up.g, up, up * 1e-6);
    const Rgb tau_down = media.optical_depth(Ray{Vec3(1, 97, 4), Vec3(0, -1, 0), 0.0f, 100.0f});
    EXPECT_NEAR(tau_down.g, up, up * 1e-6);
    const Rgb t = media.transmittance(Ray{Vec3(1, -3, 4), Vec3(0, 1, 0), 0.0f, 100.0f});
    EXPECT_NEAR(t.r, std::exp(-up), std::exp(-up) * 1e-6);
    // An endless ray up sees the whole column above: sigma_t(h0) H e^{-(y - h0)/H}.
    const double column = sigma_t * 25.0 * std::exp(-(-3.0 - 2.0) / 25.0);
    const Rgb tau_all = media.optical_depth(Ray{Vec3(1, -3, 4), Vec3(0, 1, 0), 0.0f, kInfinity});
    EXPECT_NEAR(tau_all.b, column, column * 1e-6);
}

// Horizontal and nearly horizontal rays (d_y = 0, +-1e-9, +-1e-4) and a slanted one, against the
// exact horizontal value and a Taylor series of g(x) = (1 - e^{-x}) / x (5 terms: error < x^5/720
// < 2e-18 for x <= 1e-3), and Simpson quadrature: no cancellation at any slope.
TEST(HeightFog, HorizontalAndSlantedRaysAreStable) {
    const double h0 = 1.0, H = 10.0, L = 100.0, oy = 4.0;
    const HeightFogMedium m = fog(0.0f, 0.05f, h0, H);
    const MediumSet media({as_medium(m)});
    const double sigma_t = m.sigma_t().r;
    for (const double dy : {0.0, 1e-9, -1e-9, 1e-4, -1e-4}) {
        const Vec3 d = direction(dy);
        const double dyf = d.y;  // the slope the ray really has (float)
        const double y_low = dyf >= 0.0 ? oy : oy + dyf * L;
        const double x = std::abs(dyf) * L / H;
        const double g = 1.0 - x / 2.0 + x * x / 6.0 - x * x * x / 24.0 + x * x * x * x / 120.0;
        const double expected = sigma_t * std::exp(-(y_low - h0) / H) * L * g;
        const Rgb tau = media.optical_depth(Ray{Vec3(0, oy, 0), d, 0.0f, float(L)});
        EXPECT_NEAR(tau.r, expected, expected * 1e-6) << "d_y = " << dy;
        EXPECT_NEAR(height_fog_column(m, oy, dyf, 0.0, L) * sigma_t, expected, expected * 1e-12)
            << "d_y = " << dy;
    }
    EXPECT_EQ(one_minus_exp_over(0.0), 1.0);
    EXPECT_NEAR(one_minus_exp_over(1e-12), 1.0 - 0.5e-12, 1e-16);
    for (const double dy : {0.3, -0.3, 0.9}) {
        const Vec3 d = direction(dy);
        const double expected = simpson_depth(sigma_t, h0, H, oy, d.y, 0.0, L);
        const Rgb tau = media.optical_depth(Ray{Vec3(0, oy, 0), d, 0.0f, float(L)});
        EXPECT_NEAR(tau.r, expected, expected * 1e-6) << "d_y = " << dy;
    }
}

// Box bounds clip the ray: a slanted ray from below the box through it and out of its top sees
// the closed form over the clipped stretch only.
TEST(HeightFog, BoxBoundsClipTheRay) {
    const Medium medium = parse(R"({"type": "height_fog", "bounds": [[-50, 0, -50], [50, 20, 50]],
        "sigma_a": 0.002, "sigma_s": 0.03, "scale_height_m": 8, "reference_height_m": 0})");
    const auto& m = std::get<HeightFogMedium>(medium.model);
    const MediumSet media({medium});
    const Vec3 d = direction(0.5);
    const Ray ray{Vec3(-40, -10, 0), d, 0.0f, 200.0f};
    const double t_in = 10.0 / d.y, t_out = 30.0 / d.y;  // y = 0 and y = 20
    const double expected = simpson_depth(m.sigma_t().r, 0.0, 8.0, -10.0, d.y, t_in, t_out);
    const Rgb tau = media.optical_depth(ray);
    EXPECT_NEAR(tau.g, expected, expected * 1e-5);
    // Outside the box: nothing.
    EXPECT_EQ(media.optical_depth(Ray{Vec3(-40, 30, 0), Vec3(1, 0, 0), 0.0f, 100.0f}).r, 0.0f);
    const PointCoefficients inside = media.coefficients(Vec3(0, 4, 0), 1u);
    EXPECT_NEAR(inside.sigma_s.r, 0.03f * std::exp(-0.5f), 1e-7f);
}

// Far above the fog's mass the depth underflows to 0 and T = 1; far below it is huge and T = 0;
// never NaN or inf in a transmittance, by the closed form or any estimator.
TEST(HeightFog, FarAboveAndFarBelowStayFinite) {
    const MediumSet media({as_medium(fog(0.01f, 0.05f, 0.0, 10.0))});
    Pcg32 rng(3, 5);
    VolumeCounters counters;
    for (const float y : {1e4f, 1e6f, -1e4f, -1e6f}) {
        for (const double dy : {0.0, 0.2, -0.2}) {
            for (const float t_max : {100.0f, kInfinity}) {
                const Ray ray{Vec3(0, y, 0), direction(dy), 0.0f, t_max};
                const Rgb tau = media.optical_depth(ray);
                const Rgb t = media.transmittance(ray);
                EXPECT_FALSE(std::isnan(tau.r)) << y << " " << dy;
                EXPECT_GE(tau.r, 0.0f);
                EXPECT_TRUE(std::isfinite(t.r) && t.r >= 0.0f && t.r <= 1.0f);
                // (An endless horizontal ray has an infinite column at any height: T = 0.)
                const bool clear = y > 0.0f && (dy > 0.0 || (dy == 0.0 && t_max < kInfinity));
                if (clear) {
                    EXPECT_EQ(t.r, 1.0f) << y << " " << dy;
                }
                if (y < 0.0f) {
                    EXPECT_EQ(t.r, 0.0f) << y << " " << dy;
                }
                for (const Estimator e : {Estimator::March, Estimator::Delta, Estimator::Ratio,
                                          Estimator::ResidualRatio}) {
                    const Rgb est = estimate_transmittance(media, ray, e, 0.5f, rng, counters);
                    EXPECT_TRUE(std::isfinite(est.r) && est.r >= 0.0f && est.r <= 1.0f)
                        << estimator_name(e) << " y " << y << " d_y " << dy;
                    if (y < 0.0f) {
                        EXPECT_EQ(est.r, 0.0f) << estimator_name(e);
                    }
                    if (clear) {
                        EXPECT_EQ(est.r, 1.0f) << estimator_name(e);
                    }
                }
            }
        }
    }
}

// The unbiased trackers over the e-fold majorant segments average to the closed form. N = 20000
// estimates per case; the bound is 5 standard errors (delta: the binomial sqrt(T (1 - T) / N);
// ratio trackers: the sample's own standard error, at least 1e-4), so each of the 12 checks fails
// falsely with probability about 6e-7 (normal approximation; fixed seeds: deterministic).
TEST(HeightFog, TrackersAverageToTheClosedForm) {
    const MediumSet media({as_medium(fog(0.01f, 0.05f, 0.0, 6.0))});
    const Ray rays[] = {
        {Vec3(0, 2, 0), direction(0.25), 0.0f, 60.0f},      // up through 2.5 e-folds
        {Vec3(0, 20, 0), direction(-0.3), 0.0f, 70.0f},     // down into the dense part
        {Vec3(0, 5, 0), direction(1e-4), 0.0f, 40.0f},      // nearly horizontal
        {Vec3(0, 8, 0), direction(0.05), 0.0f, kInfinity},  // endless, up: a finite column
    };
    const int n = 20000;
    for (size_t i = 0; i < std::size(rays); ++i) {
        const double expected = media.transmittance(rays[i]).g;
        ASSERT_GT(expected, 0.05);
        ASSERT_LT(expected, 0.95);
        for (const Estimator e : {Estimator::Delta, Estimator::Ratio, Estimator::ResidualRatio}) {
            Pcg32 rng(11 + i, 17);
            VolumeCounters counters;
            double sum = 0.0, sum2 = 0.0;
            for (int k = 0; k < n; ++k) {
                const double x = estimate_transmittance(media, rays[i], e, 0.0f, rng, counters).g;
                sum += x;
                sum2 += x * x;
            }
            const double mean = sum / n;
            const double se =
                e == Estimator::Delta
                    ? std::sqrt(expected * (1.0 - expected) / n)
                    : std::max(std::sqrt(std::max(sum2 / n - mean * mean, 0.0) / n), 1e-4);
            EXPECT_NEAR(mean, expected, 5.0 * se) << "ray " << i << ", " << estimator_name(e);
        }
    }
}

// The march estimator of a set whose media all have closed forms is its limit h -> 0: the
// closed form itself (no step error), also with a homogeneous box overlapping the fog.
TEST(HeightFog, MarchTransmittanceIsTheClosedForm) {
    HomogeneousMedium box;
    box.bounds = Bounds3{Vec3(0, 0, -5), Vec3(10, 10, 5)};
    box.sigma_s = Rgb(0.03f);
    const MediumSet media({as_medium(fog(0.01f, 0.05f, 0.0, 6.0)), Medium{"box", box}});
    EXPECT_TRUE(media.closed_form());
    EXPECT_FALSE(media.all_homogeneous());
    Pcg32 rng(1, 2);
    VolumeCounters counters;
    const Ray ray{Vec3(-5, 3, 0), direction(0.2), 0.0f, 50.0f};
    const Rgb exact = media.transmittance(ray);
    const Rgb march = estimate_transmittance(media, ray, Estimator::March, 2.0f, rng, counters);
    EXPECT_EQ(march, exact);
    const double tau =
        height_fog_column(fog(0.01f, 0.05f, 0.0, 6.0), 3.0, ray.direction.y, 0.0, 50.0) * 0.06 +
        0.03 * 10.0 / ray.direction.x;
    EXPECT_NEAR(exact.g, std::exp(-tau), std::exp(-tau) * 1e-5);
}

// The majorant segments bound the point coefficients: at 64 points of every segment of rays in
// every direction class (up, down, horizontal, endless, through a box), sigma_min <= sigma_t <=
// sigma_max, and no two segments overlap. Deterministic.
TEST(HeightFog, MajorantSegmentsBoundTheDensity) {
    HeightFogMedium boxed = fog(0.01f, 0.05f, 3.0, 4.0);
    boxed.bounds = Bounds3{Vec3(-30, -10, -30), Vec3(30, 25, 30)};
    const HeightFogMedium open = fog(0.01f, 0.05f, 3.0, 4.0);
    std::vector<MajorantSegment> segments;
    for (const HeightFogMedium& m : {boxed, open}) {
        const MediumSet media({as_medium(m)});
        for (const double dy : {0.0, 1e-4, -1e-4, 0.3, -0.3, 0.95, -0.95}) {
            for (const float t_max : {80.0f, kInfinity}) {
                const Ray ray{Vec3(-20, 10, 1), direction(dy), 0.0f, t_max};
                media.majorants(ray, segments);
                ASSERT_FALSE(segments.empty()) << dy;
                float last = 0.0f;
                for (const MajorantSegment& s : segments) {
                    EXPECT_GE(s.t0, last);
                    last = s.t1;
                    const float t1 = std::min(s.t1, s.t0 + 1e4f);
                    for (int k = 0; k <= 64; ++k) {
                        const float t = s.t0 + (t1 - s.t0) * k / 64.0f;
                        const float sigma = media.coefficients(ray.at(t), 1u).sigma_t.r;
                        EXPECT_LE(sigma, s.sigma_max.r) << dy << " t " << t;
                        EXPECT_GE(sigma, s.sigma_min.r) << dy << " t " << t;
                    }
                }
            }
        }
    }
}

// Single scattering of a sun straight overhead, marched, against the exact integral: along a
// slanted camera ray x(t) the radiance is
//   int sigma_s(y(t)) (1 / 4 pi) E exp(-tau_cam(0, t)) exp(-tau_up(y(t))) dt
// with both depths in closed form (tau_up from y to the box top), integrated by Simpson's rule
// (20000 intervals). The march of a lone height fog is unbiased (stratified in the column with
// exact transmittances, below): at h = 0.05 m (~500 nodes) its spread is far below the bound,
// 1e-3 over 8 jitters (deterministic: fixed seeds).
TEST(HeightFog, MarchedSingleScatteringMatchesQuadrature) {
    const double H = 6.0, sigma_s = 0.06, sigma_a = 0.01, top = 30.0;
    HeightFogMedium m = fog(float(sigma_a), float(sigma_s), 0.0, H);
    m.bounds = Bounds3{Vec3(-100, -5, -100), Vec3(100, float(top), 100)};
    const MediumSet media({as_medium(m)});
    const float lux = 3.0f;
    const std::vector<Light> sun{Light{"sun", DirectionalLight{Vec3(0, -1, 0), Rgb(lux)}}};
    const Vec3 d = direction(-0.2);
    const Ray ray{Vec3(-50, 15, 0), d, 0.0f, 80.0f};
    const double st = sigma_s + sigma_a;
    auto rho = [&](double y) { return std::exp(-y / H); };
    const int n = 20000;
    const double L = 80.0, h = L / n;
    double sum = 0.0;
    for (int i = 0; i <= n; ++i) {
        const double t = h * i, y = 15.0 + double(d.y) * t;
        const double tau_cam = height_fog_column(m, 15.0, d.y, 0.0, t) * st;
        const double tau_up = st * H * (rho(y) - rho(top));
        const double f = sigma_s * rho(y) / (4.0 * M_PI) * lux * std::exp(-tau_cam - tau_up);
        sum += f * (i == 0 || i == n ? 1 : (i % 2 == 1 ? 4 : 2));
    }
    const double expected = sum * h / 3.0;
    VolumeSettings settings;
    settings.estimator = Estimator::March;
    settings.integrator = VolumeIntegrator::Single;
    settings.step_m = 0.05f;
    for (uint64_t seed = 0; seed < 8; ++seed) {
        Pcg32 rng(seed, 3);
        VolumeCounters counters;
        const VolumeResult r =
            integrate_media(media, sun, nullptr, nullptr, ray, settings, true, rng, counters);
        EXPECT_NEAR(r.radiance.g, expected, expected * 1e-3) << "seed " << seed;
        const double t = std::exp(-height_fog_column(m, 15.0, d.y, 0.0, L) * st);
        EXPECT_NEAR(r.transmittance.g, t, t * 1e-3);
    }
}

// The marched single scattering of a lone height fog samples the column c from
// e^{-sigma' c}, sigma' = sigma (1 - d_y / s_y) (volume/march_single.cpp, march_single_height_fog):
// it is unbiased for any step. At a coarse step (a few nodes per ray) the mean of 4000 estimates
// matches a Simpson quadrature (20000 intervals, long rays: 1e-5 relative) of
//   int sigma_s,c rho(t) p(mu) E T_cam,c(t) T_sun,c(x(t)) dt
// within 5 standard errors per channel (false-failure rate ~6e-7 per check, 27 checks): a ray
// rising more steeply than the sun (sigma' < 0), a falling one (sigma' > sigma), a sun too low
// to shape the pdf (s_y < 0.02), with a chromatic extinction, through a box whose sides cut the
// sun's path for part of the ray; T_cam and T_sun in the quadrature are the closed forms tested
// above.
TEST(HeightFog, MarchedSingleScatteringIsUnbiasedAtCoarseSteps) {
    HeightFogMedium m;
    m.sigma_a = Rgb(0.004f, 0.01f, 0.03f);
    m.sigma_s = Rgb(0.05f, 0.04f, 0.03f);
    m.reference_height_m = 0.0;
    m.scale_height_m = 8.0;
    m.phase = HenyeyGreenstein{0.5f};
    m.bounds = Bounds3{Vec3(-60, -2, -60), Vec3(60, 40, 60)};
    m.cap_density();
    const MediumSet media({as_medium(m)});
    struct Case {
        Vec3 sun_wi;  // toward the sun
        double ray_dy;
        float step;
    };
    const Case cases[] = {
        {glm::normalize(Vec3(0.8f, 0.3f, 0.2f)), 0.6, 3.0f},     // rises faster than the sun
        {glm::normalize(Vec3(-0.5f, 0.7f, 0.3f)), -0.35, 5.0f},  // falls
        {glm::normalize(Vec3(1.0f, 0.01f, 0.0f)), -0.1, 2.0f},   // sun too low for the pdf
    };
    for (const Case& k : cases) {
        const std::vector<Light> sun{Light{"sun", DirectionalLight{-k.sun_wi, Rgb(2.0f)}}};
        const Vec3 d = direction(k.ray_dy);
        const Ray ray{Vec3(-40, 12, 5), d, 0.0f, 120.0f};
        const float p = eval(m.phase, scattering_cosine(-d, k.sun_wi));
        const int n = 20000;
        const auto span = m.bounds->clip(ray);
        ASSERT_TRUE(span.has_value());
        const double t0 = span->first, t1 = span->second, h = (t1 - t0) / n;
        double acc[3] = {0, 0, 0};
        for (int i = 0; i <= n; ++i) {
            const double t = t0 + h * i;
            const Vec3 x = ray.at(static_cast<float>(t));
            const double rho = std::exp(-double(x.y) / 8.0);
            const double cam = height_fog_column(m, 12.0, d.y, t0, t);
            const Rgb t_sun = media.transmittance(Ray{x, k.sun_wi, 0.0f, kInfinity});
            const double w = i == 0 || i == n ? 1 : (i % 2 == 1 ? 4 : 2);
            for (int c = 0; c < 3; ++c)
                acc[c] +=
                    w * m.sigma_s[c] * rho * p * 2.0 * std::exp(-m.sigma_t()[c] * cam) * t_sun[c];
        }
        VolumeSettings settings;
        settings.estimator = Estimator::March;
        settings.integrator = VolumeIntegrator::Single;
        settings.step_m = k.step;
        const int runs = 4000;
        double mean[3] = {0, 0, 0}, sq[3] = {0, 0, 0};
        uint64_t nodes = 0;
        for (int r = 0; r < runs; ++r) {
            Pcg32 rng(17, static_cast<uint64_t>(r));
            VolumeCounters counters;
            const VolumeResult v =
                integrate_media(media, sun, nullptr, nullptr, ray, settings, true, rng, counters);
            nodes += counters.steps;
            for (int c = 0; c < 3; ++c) {
                mean[c] += v.radiance[c];
                sq[c] += double(v.radiance[c]) * v.radiance[c];
            }
        }
        EXPECT_LT(nodes, 40u * runs) << "a coarse march: few nodes per ray";
        for (int c = 0; c < 3; ++c) {
            const double expected = acc[c] * h / 3.0;
            const double mu = mean[c] / runs;
            const double se = std::sqrt(std::max(0.0, sq[c] / runs - mu * mu) / (runs - 1));
            EXPECT_NEAR(mu, expected, 5.0 * se + 1e-6 * expected)
                << "sun y " << k.sun_wi.y << ", ray dy " << k.ray_dy << ", channel " << c;
            EXPECT_LT(se, 0.02 * expected) << "too noisy to tell";
        }
    }
}

// Point lights in the march of a lone height fog take stratified equiangular distances with
// exact camera transmittance: the mean of 2000 marches at a coarse step matches a Simpson
// quadrature (2e5 intervals) of int sigma_s,c rho p(mu) I / r^2 T_cam,c T_light,c dt along a ray
// passing 1.5 m from the light within 5 standard errors per channel (false-failure rate ~6e-7
// per check), with a relative spread per march below 10% (the light sampled at the column-
// stratified nodes instead, as before: 21%, measured).
TEST(HeightFog, MarchedPointLightIsEquiangularAndUnbiased) {
    HeightFogMedium m;
    m.sigma_a = Rgb(0.01f, 0.02f, 0.04f);
    m.sigma_s = Rgb(0.06f);
    m.reference_height_m = 0.0;
    m.scale_height_m = 5.0;
    m.phase = HenyeyGreenstein{0.3f};
    m.bounds = Bounds3{Vec3(-40, -2, -40), Vec3(40, 30, 40)};
    m.cap_density();
    const MediumSet media({as_medium(m)});
    const Vec3 lamp(3.0f, 4.5f, 1.5f);
    const std::vector<Light> lights{Light{"lamp", PointLight{lamp, Rgb(50.0f)}}};
    const Vec3 d = direction(-0.05);
    const Ray ray{Vec3(-30, 6, 0), d, 0.0f, 70.0f};
    const auto span = m.bounds->clip(ray);
    ASSERT_TRUE(span.has_value());
    const int n = 200000;
    const double t0 = span->first, t1 = span->second, h = (t1 - t0) / n;
    double acc[3] = {0, 0, 0};
    for (int i = 0; i <= n; ++i) {
        const double t = t0 + h * i;
        const Vec3 x = ray.at(static_cast<float>(t));
        const Vec3 to = lamp - x;
        const float r = glm::length(to);
        const Vec3 wi = to / r;
        const double rho = std::exp(-double(x.y) / 5.0);
        const double cam = height_fog_column(m, 6.0, d.y, t0, t);
        const Rgb t_light = media.transmittance(Ray{x, wi, 0.0f, r});
        const double p = eval(m.phase, scattering_cosine(-d, wi));
        const double w = i == 0 || i == n ? 1 : (i % 2 == 1 ? 4 : 2);
        for (int c = 0; c < 3; ++c)
            acc[c] += w * m.sigma_s[c] * rho * p * 50.0 / (double(r) * r) *
                      std::exp(-m.sigma_t()[c] * cam) * t_light[c];
    }
    VolumeSettings settings;
    settings.estimator = Estimator::March;
    settings.integrator = VolumeIntegrator::Single;
    settings.step_m = 4.0f;
    const int runs = 2000;
    double mean[3] = {0, 0, 0}, sq[3] = {0, 0, 0};
    for (int r = 0; r < runs; ++r) {
        Pcg32 rng(23, static_cast<uint64_t>(r));
        VolumeCounters counters;
        const VolumeResult v =
            integrate_media(media, lights, nullptr, nullptr, ray, settings, true, rng, counters);
        for (int c = 0; c < 3; ++c) {
            mean[c] += v.radiance[c];
            sq[c] += double(v.radiance[c]) * v.radiance[c];
        }
    }
    for (int c = 0; c < 3; ++c) {
        const double expected = acc[c] * h / 3.0;
        const double mu = mean[c] / runs;
        const double spread = std::sqrt(std::max(0.0, sq[c] / runs - mu * mu));
        EXPECT_NEAR(mu, expected, 5.0 * spread / std::sqrt(runs - 1.0) + 1e-6 * expected)
            << "channel " << c;
        EXPECT_LT(spread, 0.1 * expected) << "channel " << c;
    }
}

// As H -> infinity the fog is homogeneous: the same depth on any ray and the same coefficients.
TEST(HeightFog, InfiniteScaleHeightIsHomogeneous) {
    HeightFogMedium f = fog(0.02f, 0.03f, 5.0, 1e12);
    f.bounds = Bounds3{Vec3(-10, -10, -10), Vec3(10, 10, 10)};
    HomogeneousMedium h;
    h.bounds = f.bounds;
    h.sigma_a = f.sigma_a;
    h.sigma_s = f.sigma_s;
    const MediumSet a({as_medium(f)}), b({Medium{"h", h}});
    for (const double dy : {0.0, 0.4, -0.9, 1.0}) {
        const Ray ray{Vec3(-15, 0.5f, 0.3f), glm::normalize(Vec3(1, float(dy), 0.1f)), 0.0f, 40.0f};
        const Rgb ta = a.transmittance(ray), tb = b.transmittance(ray);
        EXPECT_NEAR(ta.r, tb.r, 1e-6f) << dy;
    }
    EXPECT_NEAR(a.coefficients(Vec3(0, 8, 0), 1u).sigma_t.r, 0.05f, 1e-6f);
}

TEST(HeightFog, VisibilityKeysGiveSigmaAtTheReferenceHeight) {
    const Medium medium = parse(R"({"type": "height_fog", "visibility_m": 300,
        "reference_height_m": 2, "scale_height_m": 40, "albedo": 0.9})");
    const auto& m = std::get<HeightFogMedium>(medium.model);
    EXPECT_NEAR(m.sigma_t().r * 300.0f, -std::log(0.05f), 1e-5f);
    EXPECT_NEAR(m.sigma_s.r, 0.9f * m.sigma_t().r, 1e-7f);
    // A horizontal ray at h0 over V keeps 5%.
    const Rgb t =
        MediumSet({medium}).transmittance(Ray{Vec3(0, 2, 0), Vec3(1, 0, 0), 0.0f, 300.0f});
    EXPECT_NEAR(t.r, 0.05f, 1e-6f);
}

// The example scene's fog: 80 m MOR at the valley floor (a horizontal ray there keeps 5% over
// 80 m), e^{45/12} times thinner at the camera's height.
TEST(HeightFog, ExampleSceneFog) {
    const std::string path = std::string(KASUMI_SOURCE_DIR) + "/data/scenes/fog_height.json";
    const Json doc = read_json_file(path);
    const Medium fog_medium = parse_medium(JsonNode(doc["media"][0], path, "/media/0"), 0);
    const MediumSet media({fog_medium});
    const Rgb t = media.transmittance(Ray{Vec3(0, 0, 0), Vec3(0, 0, -1), 0.0f, 80.0f});
    EXPECT_NEAR(t.g, 0.05f, 0.05f * 1e-5f);
    const float floor = media.coefficients(Vec3(0, 0, 0), 1u).sigma_t.g;
    const float camera = media.coefficients(Vec3(0, 45, 0), 1u).sigma_t.g;
    EXPECT_NEAR(floor / camera, std::exp(45.0f / 12.0f), 1e-3f);
}

TEST(HeightFog, BadInputIsLocated) {
    const std::string head = R"({"type": "height_fog", "sigma_a": 0.01, "sigma_s": 0.02, )";
    for (const char* bad : {R"("scale_height_m": 0})", R"("scale_height_m": -3})"}) {
        const std::string e = error_of(head + bad);
        EXPECT_NE(e.find("fog.json: /media/0/scale_height_m"), std::string::npos) << e;
        EXPECT_NE(e.find("> 0"), std::string::npos) << e;
    }
    // (A non-finite number cannot come from JSON: 1e999 fails in the JSON parser.)
    std::string e = error_of(R"({"type": "height_fog", "sigma_a": 0.01, "sigma_s": 0.02})");
    EXPECT_NE(e.find("scale_height_m"), std::string::npos) << e;
    e = error_of(head + R"("scale_height_m": 5, "scale_height": 5})");
    EXPECT_NE(e.find("/media/0/scale_height"), std::string::npos) << e;
    e = error_of(head + R"("scale_height_m": 5, "reference_height_m": "low"})");
    EXPECT_NE(e.find("/media/0/reference_height_m"), std::string::npos) << e;
    e = error_of(
        R"({"type": "height_fog", "scale_height_m": 5, "visibility_m": 100, "sigma_s": 1})");
    EXPECT_NE(e.find("/media/0/visibility_m"), std::string::npos) << e;
    e = error_of(R"({"type": "hieght_fog"})");
    EXPECT_NE(e.find("height_fog"), std::string::npos) << e;
}

}  // namespace
}  // namespace kasumi
