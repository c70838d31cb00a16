// Volume path guiding (volume/guiding/): the directional histogram and the guided mixture are
// normalised densities that their samplers follow (chi-square), the kd-tree finds the leaf of
// a point and is built the same from the same records, and guided paths stay unbiased (white
// furnace with a deliberately wrong guide).
#include "tests/sample_mean.h"
#include "volume/guiding/guided_scattering.h"
#include "volume/guiding/guiding_field.h"
#include "volume/guiding/path_guiding.h"
#include "white_furnace.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

namespace kasumi {
namespace {

/// A point of the unit cube (components drawn in order: argument order is unspecified).
Vec3 uniform3(Pcg32& rng) {
    const float x = rng.next_float();
    const float y = rng.next_float();
    return Vec3(x, y, rng.next_float());
}

/// Cells of equal solid angle for the chi-square tests: kZ bands in z times kPhi sectors.
constexpr int kZ = 20, kPhi = 40;

int cell_of(const Vec3& w) {
    const int band =
        std::min(kZ - 1, static_cast<int>((std::clamp(w.z, -1.0f, 1.0f) + 1.0f) * 0.5f * kZ));
    float phi = std::atan2(w.y, w.x);
    if (phi < 0.0f)
        phi += kTwoPi;
    return band * kPhi + std::min(kPhi - 1, static_cast<int>(phi / kTwoPi * kPhi));
}

/// The integral of `pdf` (per sr) over each cell, by an 8x8 midpoint rule in (z, phi), in which
/// the measure dz dphi is the solid angle.
std::vector<double> cell_masses(const std::function<double(const Vec3&)>& pdf) {
    constexpr int kSub = 8;
    std::vector<double> mass(kZ * kPhi, 0.0);
    const double dz = 2.0 / (kZ * kSub), dphi = 2.0 * kPiD / (kPhi * kSub);
    for (int i = 0; i < kZ * kSub; ++i) {
        const double z = -1.0 + (i + 0.5) * dz, r = std::sqrt(std::max(0.0, 1.0 - z * z));
        for (int j = 0; j < kPhi * kSub; ++j) {
            const double phi = (j + 0.5) * dphi;
            const Vec3 w(static_cast<float>(r * std::cos(phi)),
                         static_cast<float>(r * std::sin(phi)), static_cast<float>(z));
            mass[static_cast<size_t>((i / kSub) * kPhi + j / kSub)] += pdf(w) * dz * dphi;
        }
    }
    return mass;
}

/// Pearson's chi-square of `counts` against n x `masses`, cells with expected < 5 pooled, as
/// a standard normal deviate (Wilson & Hilferty 1931): > 4.26 has probability 1e-5 when the
/// sampler follows the masses.
double chi_square_deviate(const std::vector<int>& counts, const std::vector<double>& masses,
                          int n) {
    double chi2 = 0.0, pooled_observed = 0.0, pooled_expected = 0.0;
    int dof = -1;
    for (size_t i = 0; i < counts.size(); ++i) {
        const double expected = masses[i] * n;
        if (expected < 5.0) {
            pooled_observed += counts[i];
            pooled_expected += expected;
            continue;
        }
        chi2 += (counts[i] - expected) * (counts[i] - expected) / expected;
        ++dof;
    }
    if (pooled_expected > 0.0) {
        chi2 += (pooled_observed - pooled_expected) * (pooled_observed - pooled_expected) /
                pooled_expected;
        ++dof;
    }
    const double k = dof;
    return (std::cbrt(chi2 / k) - (1.0 - 2.0 / (9.0 * k))) / std::sqrt(2.0 / (9.0 * k));
}

/// A lopsided histogram: most of its weight toward (1, 1, 0.5), some toward -z.
DirectionalHistogram lopsided_histogram() {
    DirectionalHistogram h;
    Pcg32 rng(3, 1);
    for (int i = 0; i < 20000; ++i) {
        const Vec3 toward = glm::normalize(Vec3(1.0f, 1.0f, 0.5f) + 0.4f * (uniform3(rng) - 0.5f));
        h.add(toward, 1.0 + rng.next_float());
        h.add(Vec3(0.0f, 0.0f, -1.0f), 0.1);
    }
    EXPECT_TRUE(h.normalise(0.1f));
    return h;
}

TEST(DirectionalHistogram, NormalisedAndFollowedByItsSampler) {
    const DirectionalHistogram h = lopsided_histogram();
    const std::vector<double> masses = cell_masses([&](const Vec3& w) { return h.pdf(w); });
    double total = 0.0;
    for (double m : masses)
        total += m;
    EXPECT_NEAR(total, 1.0, 1e-4);
    constexpr int kSamples = 200000;
    std::vector<int> counts(masses.size(), 0);
    Pcg32 rng(5, 2);
    for (int i = 0; i < kSamples; ++i) {
        float pdf_sr = 0.0f;
        const Vec3 w = h.sample(rng.next_vec2(), pdf_sr);
        ASSERT_NEAR(glm::length(w), 1.0f, 1e-5f);
        ASSERT_FLOAT_EQ(pdf_sr, h.pdf(w));
        ++counts[static_cast<size_t>(cell_of(w))];
    }
    EXPECT_LT(chi_square_deviate(counts, masses, kSamples), 4.26);
    EXPECT_FALSE(DirectionalHistogram().normalise(0.1f));  // no light: no pdf
}

/// A single grid-free medium: a homogeneous box with HG g = 0.8 (the cloud's phase).
MediumSet hg_box() {
    return MediumSet({Medium{"box", HomogeneousMedium{Bounds3{Vec3(-1.0f), Vec3(1.0f)}, Rgb(0.0f),
                                                      Rgb(2.0f), HenyeyGreenstein{0.8f}}}});
}

// The guided mixture: pdf normalised, its sampler follows it (chi-square, false failure 1e-5
// per mix), the weight it returns is sigma_s p(mu) / pdf; a sampler whose stated pdf omits
// the guide's share (the error that would bias guided paths) fails the same test.
TEST(GuidedScattering, MixturePdfIsNormalisedAndMatchesItsSampler) {
    const MediumSet media = hg_box();
    const DirectionalHistogram guide = lopsided_histogram();
    const Vec3 wo = glm::normalize(Vec3(0.3f, -0.2f, 1.0f));
    PointCoefficients k;
    k.sigma_s = Rgb(2.0f);
    k.sigma_t = Rgb(2.0f);
    for (const float mix : {0.2f, 0.5f, 0.9f}) {
        const std::vector<double> masses =
            cell_masses([&](const Vec3& w) { return guided_pdf(media, 0, guide, mix, wo, w); });
        double total = 0.0;
        for (double m : masses)
            total += m;
        EXPECT_NEAR(total, 1.0, 2e-3) << mix;  // HG g = 0.8 peaks within a cell: 2e-3 quadrature
        constexpr int kSamples = 200000;
        std::vector<int> counts(masses.size(), 0);
        Pcg32 rng(7, 3);
        for (int i = 0; i < kSamples; ++i) {
            const float u_choose = rng.next_float();
            const Vec2 u = rng.next_vec2();
            const MixtureSample s =
                sample_guided_scattering(media, 0, guide, mix, k, wo, u_choose, u);
            ASSERT_GT(s.pdf, 0.0f);
            ASSERT_NEAR(s.pdf, guided_pdf(media, 0, guide, mix, wo, s.wi), 1e-4f * s.pdf);
            const float phase = eval(HenyeyGreenstein{0.8f}, scattering_cosine(wo, s.wi));
            ASSERT_NEAR(s.scattering.g, 2.0f * phase, 1e-5f * s.scattering.g);
            ++counts[static_cast<size_t>(cell_of(s.wi))];
        }
        EXPECT_LT(chi_square_deviate(counts, masses, kSamples), 4.26) << "mix " << mix;
        const std::vector<double> phase_only = cell_masses([&](const Vec3& w) {
            return pdf(PhaseFunction{HenyeyGreenstein{0.8f}}, scattering_cosine(wo, w));
        });
        EXPECT_GT(chi_square_deviate(counts, phase_only, kSamples), 4.26)
            << "a pdf without the guide's share went unnoticed at mix " << mix;
    }
}

TEST(GuidingField, FindsTheLeafAndIsDeterministic) {
    std::vector<GuidingRecord> records;
    Pcg32 rng(11, 4);
    for (int i = 0; i < 5000; ++i) {
        const Vec3 p = uniform3(rng) * 10.0f;
        // Light from +x in the half x < 5, from +y in the other.
        records.push_back({p, p.x < 5.0f ? Vec3(1, 0, 0) : Vec3(0, 1, 0), 1.0f});
    }
    const GuidingField field(records, 500, 0.0f);
    EXPECT_GE(field.leaf_count(), 8u);
    const DirectionalHistogram* low = field.find(Vec3(1.0f, 5.0f, 5.0f));
    const DirectionalHistogram* high = field.find(Vec3(9.0f, 5.0f, 5.0f));
    ASSERT_NE(low, nullptr);
    ASSERT_NE(high, nullptr);
    EXPECT_GT(low->pdf(Vec3(1, 0, 0)), 1.0f);
    EXPECT_EQ(low->pdf(Vec3(0, 1, 0)), 0.0f);
    EXPECT_GT(high->pdf(Vec3(0, 1, 0)), 1.0f);
    EXPECT_EQ(field.find(Vec3(20.0f, 5.0f, 5.0f)), nullptr);  // outside the records' box
    const GuidingField again(records, 500, 0.0f);
    for (int i = 0; i < 100; ++i) {
        const Vec3 p = uniform3(rng) * 10.0f, w = glm::normalize(uniform3(rng) - 0.5f);
        const DirectionalHistogram* a = field.find(p);
        const DirectionalHistogram* b = again.find(p);
        ASSERT_EQ(a == nullptr, b == nullptr);
        if (a != nullptr) {
            EXPECT_EQ(a->pdf(w), b->pdf(w));
        }
    }
}

// Energy conservation with guiding on: albedo-1 media in a uniform environment of radiance 1
// return L = 1 in expectation whatever the guide, so a guide that is wrong on purpose (a quarter
// of its weight toward +x, where the furnace has no more light than elsewhere) must still give 1
// within 4 standard errors: the mixture pdf in the weight keeps the paths unbiased.
TEST(GuidedScattering, WhiteFurnaceStaysExact) {
    const test::WhiteFurnace furnace("guided_furnace");
    std::vector<GuidingRecord> records;
    Pcg32 rng(13, 5);
    for (int i = 0; i < 4000; ++i) {
        const Vec3 p = Vec3(-2.0f) + 8.0f * uniform3(rng);
        const Vec3 w = i % 4 == 0 ? Vec3(1, 0, 0) : glm::normalize(uniform3(rng) - 0.5f);
        records.push_back({p, w, 1.0f});
    }
    // Half of each histogram uniform: a guide far from the ideal (the phase function here)
    // multiplies the paths' weights by up to 1 / (1 - mix) per bounce, and albedo-1 paths are
    // long, so the variance grows with the guide's error (the reason guiding is off by default).
    const GuidingField field(records, 400, 0.5f);
    VolumeSettings settings;
    settings.integrator = VolumeIntegrator::Multiple;
    settings.estimator = Estimator::ResidualRatio;
    settings.max_depth = 100000;
    for (const auto& [media, ray] : {std::pair{&furnace.grid, furnace.inside_grid},
                                     std::pair{&furnace.fog, furnace.inside_fog}}) {
        ASSERT_NE(field.find(ray.origin), nullptr);
        for (const float mix : {0.2f}) {
            const PathGuiding guiding{&field, mix, nullptr};
            const MeanAndError l = mean_over_streams(8000, 17, [&](Pcg32& r) {
                const test::UniformBackground background(Rgb(1.0f));
                VolumeCounters counters;
                const VolumeResult v =
                    integrate_media(*media, {}, nullptr, &background, ray, settings, true, r,
                                    counters, false, &guiding);
                return static_cast<double>(v.radiance.g + v.transmittance.g);
            });
            EXPECT_NEAR(l.mean, 1.0, 4.0 * l.stderr_ + 1e-6) << "mix " << mix;
            EXPECT_LT(4.0 * l.stderr_, 0.08);  // the bound has teeth: an 8% loss fails
        }
    }
}

// Paths record their vertices: in the furnace every record's incident radiance is 1 (the
// environment, reached through albedo-1 scattering), so record weight x pdf has mean 1.
TEST(GuidingPathRecorder, RecordsTheIncidentRadiance) {
    const test::WhiteFurnace furnace("recorded_furnace");
    VolumeSettings settings;
    settings.integrator = VolumeIntegrator::Multiple;
    settings.estimator = Estimator::ResidualRatio;
    settings.max_depth = 100000;
    std::vector<GuidingRecord> records;
    const PathGuiding guiding{nullptr, 0.5f, &records};
    const test::UniformBackground background(Rgb(1.0f));
    double sum = 0.0;
    size_t counted = 0;
    for (int i = 0; i < 4000; ++i) {
        Pcg32 rng(static_cast<uint64_t>(i), 9);
        VolumeCounters counters;
        records.clear();
        integrate_media(furnace.fog, {}, nullptr, &background, furnace.inside_fog, settings, true,
                        rng, counters, false, &guiding);
        for (const GuidingRecord& r : records) {
            // Isotropic phase, no guide: the pdf of every direction is 1 / (4 pi).
            sum += r.weight * kInv4Pi;
            ++counted;
        }
    }
    ASSERT_GT(counted, 4000u);
    EXPECT_NEAR(sum / static_cast<double>(counted), 1.0, 0.05);
}

}  // namespace
}  // namespace kasumi
