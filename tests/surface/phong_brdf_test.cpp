/// The property suite of the Phong BRDF (surface/phong_brdf.h), in the manner of the phase
/// suite: reciprocity, energy conservation and the exact albedo at normal incidence by
/// quadrature, the pdf normalised over the hemisphere, samples carrying their own pdf and value,
/// and a chi-square goodness-of-fit test of the sampler (phase/phase_validation.h's statistic).
///
/// Quadrature: integrals over the sphere are taken in the frame of the mirror direction with
/// s = ln(1 − cos α) uniform, so that the lobe of exponents up to 1000 (width 1 − cos α ~ 1/n)
/// gets as many nodes as the diffuse part; the midpoint rule has no random error.
///
/// False-failure rate: the chi-square tests share an overall significance of 1 % through the
/// Šidák correction (each compares its p-value with 1 − 0.99^{1/N}, N = the number of cases);
/// seeds are fixed, so a given build passes or fails deterministically.
#include "surface/phong_brdf.h"

#include "core/rng.h"
#include "core/sampling.h"
#include "phase/phase_validation.h"
#include "surface/fresnel.h"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

namespace kasumi {
namespace {

constexpr double kLowestGap = 1e-12;  ///< 1 − cos α below this is left out (mass < n · 1e-12)

/// ∫ g(w) dω over the unit sphere by the midpoint rule in (s, φ) about `axis`, s = ln(1 − cos α)
/// in [ln kLowestGap, ln 2]: dω = e^s ds dφ. s = 0 (α = 90°) is a node boundary, so the jump
/// of a lobe of exponent 0 at the horizon of a normal view is integrated exactly.
template <class G>
double integrate_about(const Vec3& axis, G&& g, int n_s = 600, int n_phi = 600) {
    const double dphi = 2.0 * kPiD / n_phi;
    double sum = 0.0;
    for (const auto& [s_lo, s_hi] : {std::pair{std::log(kLowestGap), 0.0}, {0.0, std::log(2.0)}}) {
        const double ds = (s_hi - s_lo) / n_s;
        for (int i = 0; i < n_s; ++i) {
            const double gap = std::exp(s_lo + (i + 0.5) * ds);
            const float cos_alpha = static_cast<float>(1.0 - gap);
            double ring = 0.0;
            for (int j = 0; j < n_phi; ++j)
                ring += g(direction_about(axis, cos_alpha, static_cast<float>((j + 0.5) * dphi)));
            sum += ring * gap * ds;
        }
    }
    return sum * dphi;
}

Vec3 view_at(float cos_theta) {
    return Vec3(std::sqrt(1.0f - cos_theta * cos_theta), 0.0f, cos_theta);
}

const Vec3 kNormal(0.0f, 0.0f, 1.0f);

PhongMaterial material(float kd, float ks, float exponent) {
    PhongMaterial m;
    m.kd = Rgb(kd);
    m.ks = Rgb(ks);
    m.n = exponent;
    return m;
}

/// Directional albedo ∫ f(wo, wi) cos θi dωi (green channel).
double albedo(const PhongMaterial& m, const Vec3& wo) {
    return integrate_about(reflect(wo, kNormal), [&](const Vec3& wi) {
        return static_cast<double>(eval(m, kNormal, wo, wi).g) *
               std::max(0.0f, glm::dot(kNormal, wi));
    });
}

double pdf_integral(const PhongMaterial& m, const Vec3& wo) {
    return integrate_about(reflect(wo, kNormal),
                           [&](const Vec3& wi) { return double(pdf(m, kNormal, wo, wi)); });
}

const float kExponents[] = {0.0f, 1.0f, 10.0f, 100.0f, 1000.0f};
const float kViewCosines[] = {1.0f, 0.7f, 0.3f, 0.05f, 0.01f};

TEST(PhongBrdf, ReciprocalWithConstantSpecularReflectance) {
    Pcg32 rng(17, 3);
    for (const float exponent : kExponents) {
        const PhongMaterial m = material(0.4f, 0.5f, exponent);
        for (int k = 0; k < 2000; ++k) {
            const Vec3 wo = sample_uniform_sphere(rng.next_vec2());
            const Vec3 wi = sample_uniform_sphere(rng.next_vec2());
            const Rgb a = eval(m, kNormal, wo, wi), b = eval(m, kNormal, wi, wo);
            ASSERT_NEAR(a.g, b.g, 1e-5f * std::max(1.0f, a.g)) << exponent;
        }
    }
}

TEST(PhongBrdf, ZeroUnlessBothDirectionsAreAboveTheShadingNormal) {
    const PhongMaterial m = material(0.5f, 0.5f, 10.0f);
    const Vec3 above = glm::normalize(Vec3(0.3f, 0.0f, 1.0f));
    const Vec3 below = glm::normalize(Vec3(-0.3f, 0.0f, -0.01f));
    EXPECT_GT(eval(m, kNormal, above, above).g, 0.0f);
    EXPECT_EQ(eval(m, kNormal, above, below).g, 0.0f);
    EXPECT_EQ(eval(m, kNormal, below, above).g, 0.0f);
    EXPECT_EQ(pdf(m, kNormal, above, below), 0.0f);
    EXPECT_EQ(pdf(m, kNormal, below, above), 0.0f);
    EXPECT_FALSE(sample(m, kNormal, below, 0.5f, Vec2(0.5f)).has_value());
}

TEST(PhongBrdf, AlbedoIsKdPlusKsAtNormalIncidenceAndAtMostThatElsewhere) {
    // At normal incidence the lobe's (n + 2)/(2π) cos^n α cos θ integrates to exactly 1, so
    // the albedo is kd + ks; tilted, part of the lobe falls below the horizon: less.
    for (const float exponent : kExponents) {
        for (const auto& [kd, ks] : {std::pair{0.0f, 1.0f}, {0.5f, 0.5f}, {1.0f, 0.0f}}) {
            const PhongMaterial m = material(kd, ks, exponent);
            for (const float cos_view : kViewCosines) {
                const double a = albedo(m, view_at(cos_view));
                if (cos_view == 1.0f) {
                    EXPECT_NEAR(a, 1.0, 2e-3) << exponent << " kd " << kd;
                }
                EXPECT_LE(a, 1.0 + 2e-3) << exponent << " kd " << kd << " cos " << cos_view;
            }
        }
    }
}

TEST(PhongBrdf, FresnelSpecularAloneConservesEnergy) {
    for (const SpecularFresnel mode : {SpecularFresnel::Schlick, SpecularFresnel::Exact}) {
        PhongMaterial m = material(0.0f, 0.04f, 50.0f);
        m.ks_fresnel = mode;
        for (const float cos_view : kViewCosines)
            EXPECT_LE(albedo(m, view_at(cos_view)), 1.0 + 2e-3);
    }
}

TEST(PhongBrdf, PdfIsNormalisedOverTheHemisphere) {
    for (const float exponent : kExponents) {
        for (const float kd : {0.0f, 0.5f, 1.0f}) {
            const PhongMaterial m = material(kd, 1.0f - kd, exponent);
            // At normal view the lobe lies inside the hemisphere: the mixture integrates to 1.
            EXPECT_NEAR(pdf_integral(m, kNormal), 1.0, 2e-3) << exponent << " kd " << kd;
            // Tilted, the lobe's part below the surface is lost (sample() returns nothing).
            for (const float cos_view : kViewCosines)
                EXPECT_LE(pdf_integral(m, view_at(cos_view)), 1.0 + 2e-3) << exponent;
        }
    }
}

TEST(PhongBrdf, SamplesCarryTheirPdfAndValue) {
    const Vec3 wo = glm::normalize(Vec3(0.4f, 0.1f, 1.0f));
    PhongMaterial m = material(0.5f, 0.3f, 30.0f);
    m.kd = Rgb(0.4f, 0.5f, 0.6f);
    Pcg32 rng(7, 11);
    for (int k = 0; k < 1000; ++k) {
        const float u_lobe = rng.next_float();
        const auto s = sample(m, kNormal, wo, u_lobe, rng.next_vec2());
        if (!s)
            continue;
        EXPECT_NEAR(s->pdf, pdf(m, kNormal, wo, s->wi), 1e-4f * s->pdf);
        EXPECT_NEAR(s->f.g, eval(m, kNormal, wo, s->wi).g, 1e-6f);
        EXPECT_GT(glm::dot(kNormal, s->wi), 0.0f);
    }
}

struct ChiCase {
    float kd, ks, exponent, cos_view;
};

const std::vector<ChiCase>& chi_cases() {
    static const std::vector<ChiCase> c = {
        {1.0f, 0.0f, 1.0f, 0.7f},    {0.5f, 0.5f, 1.0f, 1.0f},    {0.5f, 0.5f, 10.0f, 0.7f},
        {0.3f, 0.7f, 10.0f, 0.05f},  {0.5f, 0.5f, 100.0f, 1.0f},  {0.2f, 0.8f, 100.0f, 0.3f},
        {0.5f, 0.5f, 1000.0f, 0.7f}, {0.0f, 1.0f, 1000.0f, 0.01f}};
    return c;
}

class PhongChiSquare : public ::testing::TestWithParam<ChiCase> {};

/// Samples binned in (s = ln(1 − cos α), φ) about the mirror direction, s from ln 1e-5 to ln 2
/// in 40 cells (everything closer to the mirror direction in the first: float cos α near 1 is
/// quantised in steps of 6e-8, too coarse for narrower cells), φ in 12; expected
/// counts from the pdf integrated over each cell (32 × 32 midpoint nodes).
TEST_P(PhongChiSquare, SamplerMatchesPdf) {
    const ChiCase c = GetParam();
    const PhongMaterial m = material(c.kd, c.ks, c.exponent);
    const Vec3 wo = view_at(c.cos_view);
    const Vec3 mirror = reflect(wo, kNormal);
    const Frame frame(mirror);
    const int n_s = 40, n_phi = 12, samples = 1000000, sub = 32;
    const double s_lo = std::log(1e-5), s_hi = std::log(2.0);
    const double ds = (s_hi - s_lo) / n_s, dphi = 2.0 * kPiD / n_phi;
    std::vector<double> observed(n_s * n_phi, 0.0), expected(n_s * n_phi, 0.0);
    Pcg32 rng(2024, 7);
    for (int k = 0; k < samples; ++k) {
        const float u_lobe = rng.next_float();
        const auto s = sample(m, kNormal, wo, u_lobe, rng.next_vec2());
        if (!s)
            continue;
        // 1 − cos α = |wi − mirror|² / 2, without the cancellation of 1 − dot near the axis.
        const DVec3 gap_vector = DVec3(s->wi) - DVec3(mirror);
        const double gap = 0.5 * glm::dot(gap_vector, gap_vector);
        const Vec3 local = frame.to_local(s->wi);
        double phi = std::atan2(double(local.y), double(local.x));
        if (phi < 0.0)
            phi += 2.0 * kPiD;
        const int i = std::clamp(static_cast<int>((std::log(gap) - s_lo) / ds), 0, n_s - 1);
        const int j = std::clamp(static_cast<int>(phi / dphi), 0, n_phi - 1);
        observed[i * n_phi + j] += 1.0;
    }
    for (int i = 0; i < n_s; ++i) {
        for (int j = 0; j < n_phi; ++j) {
            // Cell 0 (everything nearer the axis than its upper edge, where the pdf is nearly
            // constant) uniform in 1 − cos α; the others uniform in s. Fine nodes: the horizon
            // cuts some cells with a jump.
            const double first_edge = std::exp(s_lo + ds);
            double mass = 0.0;
            for (int a = 0; a < sub; ++a) {
                const double gap = i == 0 ? first_edge * (a + 0.5) / sub
                                          : std::exp(s_lo + (i + (a + 0.5) / sub) * ds);
                const double weight = i == 0 ? first_edge / sub : gap * ds / sub;
                for (int b = 0; b < sub; ++b) {
                    const double phi = (j + (b + 0.5) / sub) * dphi;
                    const Vec3 wi = direction_about(mirror, static_cast<float>(1.0 - gap),
                                                    static_cast<float>(phi));
                    mass += pdf(m, kNormal, wo, wi) * weight;
                }
            }
            expected[i * n_phi + j] = samples * mass * (dphi / sub);
        }
    }
    ValidationOptions run;
    run.significance = 0.01;
    run.n_tests = static_cast<int>(chi_cases().size());
    const ChiSquareResult r = chi_square_statistic(observed, expected, per_check_alpha(run));
    std::ostringstream worst;
    for (size_t k = 0; k < observed.size(); ++k)
        if (expected[k] >= 5.0 &&
            (observed[k] - expected[k]) * (observed[k] - expected[k]) > 9.0 * expected[k])
            worst << "cell s " << k / n_phi << " phi " << k % n_phi << ": observed " << observed[k]
                  << " expected " << expected[k] << "\n";
    EXPECT_TRUE(r.passed) << worst.str() << "chi² " << r.statistic << " dof " << r.dof << " p "
                          << r.p_value << " threshold " << r.threshold;
}

INSTANTIATE_TEST_SUITE_P(Lobes, PhongChiSquare, ::testing::ValuesIn(chi_cases()),
                         [](const auto& param_info) {
                             const ChiCase& c = param_info.param;
                             return "kd" + std::to_string(static_cast<int>(c.kd * 10)) + "_n" +
                                    std::to_string(static_cast<int>(c.exponent)) + "_cos" +
                                    std::to_string(static_cast<int>(c.cos_view * 100));
                         });

}  // namespace
}  // namespace kasumi
