/// Statistical checks of the extended lights' samplers: the sampled unshadowed illuminance is
/// unbiased against the closed form, and the sampled points follow the stated pdf (chi-square).
/// Every check uses a fixed seed; the false-failure rates below are for a fresh seed.
#include "core/rng.h"
#include "light_test_util.h"

#include <gtest/gtest.h>

namespace kasumi {
namespace {

/// |mean − E| < 5 standard errors: a two-sided normal tail of 5.7e-7 per case (the CLT holds:
/// every estimator here is bounded). The standard error must also be below 0.5% of E so that a
/// 2.5% bias cannot pass.
void expect_unbiased(const Light& light, const Vec3& p, const Vec3& n, const char* what) {
    const double expected = luminance(unshadowed_irradiance(light, p, n));
    ASSERT_GT(expected, 0.0) << what;
    Pcg32 rng(7, 11);
    const int samples = 200000;
    double sum = 0.0, sum_sq = 0.0;
    for (int i = 0; i < samples; ++i) {
        const IncidentLight in = sample_incident(light, p, rng.next_vec2());
        const double x = luminance(in.irradiance) * std::max(0.0f, glm::dot(n, in.wi));
        sum += x;
        sum_sq += x * x;
    }
    const double mean = sum / samples;
    const double se = std::sqrt(std::max(0.0, sum_sq / samples - mean * mean) / (samples - 1));
    EXPECT_LT(std::abs(mean - expected), 5.0 * se + 1e-12 * expected)
        << what << ": mean " << mean << " closed form " << expected << " se " << se;
    EXPECT_LT(se, 0.005 * expected) << what << ": relative standard error " << se / expected;
}

TEST(LightSampling, PolygonSamplesAreUnbiased) {
    const Light square = test::parse_light_text(R"({"type": "polygon", "luminance_cd_m2": 50,
        "vertices": [[-1, 2, -1], [1, 2, -1], [1, 2, 1], [-1, 2, 1]]})");
    expect_unbiased(square, Vec3(0.2f, 0, 0.1f), Vec3(0, 1, 0), "square overhead");
    expect_unbiased(square, Vec3(0.5f, 0, 0), glm::normalize(Vec3(1, 0.3f, 0)), "horizon cut");
    const Light pentagon = test::parse_light_text(R"({"type": "polygon", "luminance_cd_m2": 5,
        "two_sided": true, "vertices": [[1, 1.98, -1.2], [1.5, 2.15, 0], [0.5, 2.2, 1.5],
        [-1, 2, 1], [-1, 1.8, -1]]})");
    expect_unbiased(pentagon, Vec3(0.2f, 0, 0.3f), glm::normalize(Vec3(-0.4f, 1, 0.2f)),
                    "pentagon front");
    expect_unbiased(pentagon, Vec3(0.2f, 4, 0.3f), glm::normalize(Vec3(0.1f, -1, 0)),
                    "pentagon back");
}

TEST(LightSampling, LineSamplesAreUnbiased) {
    const Light line = test::parse_light_text(
        R"({"type": "line", "from": [-1, 1, -0.5], "to": [2, 2.5, 1], "intensity_cd_per_m": 40})");
    expect_unbiased(line, Vec3(0), glm::normalize(Vec3(0.2f, 1, -0.3f)), "oblique");
    expect_unbiased(line, Vec3(0.3f, 1.2f, 0), glm::normalize(Vec3(1, 0.2f, 0)), "near, cut");
}

TEST(LightSampling, SphereSamplesAreUnbiased) {
    const Light sphere = test::parse_light_text(
        R"({"type": "sphere", "center": [0, 2, 0], "radius": 1, "luminance_cd_m2": 30})");
    for (float theta : {0.0f, 45.0f, 75.0f, 100.0f}) {
        const Vec3 n(std::sin(radians(theta)), std::cos(radians(theta)), 0.0f);
        expect_unbiased(sphere, Vec3(0), n, "sphere");
    }
}

/// Šidák-corrected level for the chi-square tests of this file: 3 tests fail together with
/// probability 1e-4 under a correct sampler.
const double kChiSquareThreshold = 1.0 - std::pow(1.0 - 1e-4, 1.0 / 3.0);

/// Area of a convex 2-D polygon clipped to the box [x0, x1] × [y0, y1] (Sutherland-Hodgman).
double clipped_area(std::vector<Vec2> poly, float x0, float x1, float y0, float y1) {
    const auto clip = [&](int axis, float bound, float sign) {
        std::vector<Vec2> out;
        for (size_t i = 0; i < poly.size(); ++i) {
            const Vec2 a = poly[i], b = poly[(i + 1) % poly.size()];
            const float da = sign * (a[axis] - bound), db = sign * (b[axis] - bound);
            if (da >= 0.0f)
                out.push_back(a);
            if ((da >= 0.0f) != (db >= 0.0f))
                out.push_back(a + (da / (da - db)) * (b - a));
        }
        poly = out;
    };
    clip(0, x0, 1.0f);
    clip(0, x1, -1.0f);
    clip(1, y0, 1.0f);
    clip(1, y1, -1.0f);
    double area = 0.0;
    for (size_t i = 0; i < poly.size(); ++i) {
        const Vec2 a = poly[i], b = poly[(i + 1) % poly.size()];
        area += 0.5 * (static_cast<double>(a.x) * b.y - static_cast<double>(b.x) * a.y);
    }
    return std::abs(area);
}

TEST(LightSampling, PolygonPointsAreUniformInArea) {
    // A pentagon in the plane y = 0 whose fan triangles have unequal areas.
    const std::vector<Vec2> outline = {Vec2(0, 0), Vec2(-3, 0.5f), Vec2(-2.5f, 2), Vec2(0, 2.5f),
                                       Vec2(1, 1)};
    std::string vertices;
    for (const Vec2& v : outline) {
        vertices += (vertices.empty() ? "[" : ", [") + std::to_string(v.x) + ", 0, " +
                    std::to_string(v.y) + "]";
    }
    const Light light = test::parse_light_text(
        R"({"type": "polygon", "luminance_cd_m2": 1, "two_sided": true, "vertices": [)" + vertices +
        "]}");
    const int grid = 12, samples = 400000;
    const float x0 = -3, x1 = 1, y0 = 0, y1 = 2.5f;
    std::vector<double> observed(grid * grid, 0.0), expected(grid * grid);
    Pcg32 rng(3, 5);
    for (int i = 0; i < samples; ++i) {
        const Vec3 x = sample_incident(light, Vec3(0.1f, 1, 0.1f), rng.next_vec2()).light_position;
        const int cx = std::clamp(static_cast<int>((x.x - x0) / (x1 - x0) * grid), 0, grid - 1);
        const int cy = std::clamp(static_cast<int>((x.z - y0) / (y1 - y0) * grid), 0, grid - 1);
        observed[cy * grid + cx] += 1.0;
    }
    const double area = std::get<PolygonLight>(light.emitter).area;
    for (int cy = 0; cy < grid; ++cy) {
        for (int cx = 0; cx < grid; ++cx) {
            const float ax = x0 + (x1 - x0) * cx / grid, bx = x0 + (x1 - x0) * (cx + 1) / grid;
            const float ay = y0 + (y1 - y0) * cy / grid, by = y0 + (y1 - y0) * (cy + 1) / grid;
            expected[cy * grid + cx] = samples * clipped_area(outline, ax, bx, ay, by) / area;
        }
    }
    EXPECT_GT(test::chi_square_p_value(observed, expected), kChiSquareThreshold);
}

TEST(LightSampling, LinePointsFollowTheAnglePdf) {
    // pdf h / (r² Δφ) per metre: the mass of [s_a, s_b] is (atan(s_b/h) − atan(s_a/h)) / Δφ.
    const Light light = test::parse_light_text(
        R"({"type": "line", "from": [-1, 0.5, 0], "to": [3, 0.5, 0], "intensity_cd_per_m": 1})");
    const double h = 0.5;
    const int bins = 40, samples = 200000;
    std::vector<double> observed(bins, 0.0), expected(bins);
    Pcg32 rng(9, 1);
    for (int i = 0; i < samples; ++i) {
        const float s = sample_incident(light, Vec3(0), rng.next_vec2()).light_position.x;
        observed[std::clamp(static_cast<int>((s + 1.0f) / 4.0f * bins), 0, bins - 1)] += 1.0;
    }
    const double dphi = std::atan(3.0 / h) - std::atan(-1.0 / h);
    for (int b = 0; b < bins; ++b) {
        const double sa = -1.0 + 4.0 * b / bins, sb = -1.0 + 4.0 * (b + 1) / bins;
        expected[b] = samples * (std::atan(sb / h) - std::atan(sa / h)) / dphi;
    }
    EXPECT_GT(test::chi_square_p_value(observed, expected), kChiSquareThreshold);
}

TEST(LightSampling, SphereDirectionsAreUniformInTheCone) {
    const Light light = test::parse_light_text(
        R"({"type": "sphere", "center": [0, 0, 2], "radius": 1.2, "luminance_cd_m2": 1})");
    const double cos_sigma = std::sqrt(1.0 - 0.36);
    const int n_cos = 10, n_phi = 8, samples = 200000;
    std::vector<double> observed(n_cos * n_phi, 0.0);
    const std::vector<double> expected(n_cos * n_phi,
                                       static_cast<double>(samples) / (n_cos * n_phi));
    Pcg32 rng(4, 2);
    for (int i = 0; i < samples; ++i) {
        const IncidentLight in = sample_incident(light, Vec3(0), rng.next_vec2());
        // The point lies on the sphere, along wi at the returned distance.
        ASSERT_NEAR(glm::length(in.light_position - Vec3(0, 0, 2)), 1.2f, 1e-4f);
        ASSERT_NEAR(glm::length(in.light_position - in.distance * in.wi), 0.0f, 1e-4f);
        const double c = (in.wi.z - cos_sigma) / (1.0 - cos_sigma);
        double phi = std::atan2(in.wi.y, in.wi.x) / (2.0 * kPiD);
        if (phi < 0.0)
            phi += 1.0;
        const int ci = std::clamp(static_cast<int>(c * n_cos), 0, n_cos - 1);
        const int pi = std::clamp(static_cast<int>(phi * n_phi), 0, n_phi - 1);
        observed[ci * n_phi + pi] += 1.0;
    }
    EXPECT_GT(test::chi_square_p_value(observed, expected), kChiSquareThreshold);
}

}  // namespace
}  // namespace kasumi
