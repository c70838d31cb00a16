// Blackbody emission of VDB media with a temperature grid (volume/blackbody.h, docs/volumes.md).
//
// 1. Photometry of Planck's law: the 1948-1979 definition of the candela made the luminance of a
//    black body at the freezing point of platinum 60 cd/cm² = 6.0e5 cd/m² (9th CGPM, 1948); that
//    point is 2041.3 K on ITS-90 (1768.2 °C, Preston-Thomas 1990). With today's 683 lm/W and the
//    CIE 1931 V(lambda) the same luminance follows to within a few per cent (the old definition
//    rested on the 1948 temperature scale and V(lambda)); the test allows 5%.
// 2. Closed form along a ray: a non-scattering medium of constant absorption sigma_a and
//    constant temperature T emits L = B(T) (1 - exp(-sigma_a d)) toward the start of a segment
//    of length d inside it (the emission term of the radiative transfer equation integrated with
//    its own attenuation). Every estimator must give it: the trackers' null-collision emission is
//    unbiased (Bernoulli-like, variance B² p (1 - p)), the march integrates T exactly here.
//    4 standard errors: false-failure rate about 6e-5 per comparison (normal approximation).
#include "tests/volume/vdb_test_grids.h"
#include "volume/blackbody.h"
#include "volume/medium_set.h"
#include "volume/volume_path.h"

#include <gtest/gtest.h>

#include <cmath>

namespace kasumi {
namespace {

TEST(Blackbody, PlatinumPointLuminanceMatchesTheOldCandela) {
    const Rgb b = blackbody_rec709(2041.3);
    EXPECT_NEAR(luminance(b), 6.0e5, 0.05 * 6.0e5);
}

TEST(Blackbody, HotterIsBrighterAndBluer) {
    const Rgb warm = blackbody_rec709(1500.0), hot = blackbody_rec709(6500.0);
    EXPECT_GT(luminance(hot), luminance(warm));
    EXPECT_GT(warm.r, warm.b);
    // Near 6500 K the Planckian locus passes close to D65: nearly grey.
    EXPECT_NEAR(hot.b / hot.r, 1.0, 0.15);
    EXPECT_EQ(luminance(blackbody_rec709(0.0)), 0.0f);
}

TEST(Blackbody, TableMatchesDirectIntegration) {
    const BlackbodyTable table;
    for (double t : {800.0, 1234.5, 3000.0, 9999.0}) {
        const Rgb direct = blackbody_rec709(t), tabulated = table(static_cast<float>(t));
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(tabulated[c], direct[c], 2e-3 * luminance(direct) + 1e-6) << t;
    }
}

TEST(Blackbody, TableAboveItsLastEntryFollowsPlanckNotStefanBoltzmann) {
    // Above 40000 K the visible radiance grows like T (Rayleigh-Jeans: B -> 2 c k T / lambda⁴),
    // not like the T⁴ of the total exitance: at 80000 K the luminance is ~2.3x that at 40000 K,
    // not 16x. The table must follow Planck's law (direct 1 nm integration) there too.
    const BlackbodyTable table;
    for (double t : {40000.0, 40005.0, 45000.0, 80000.0, 2.5e5, 1e7}) {
        const Rgb direct = blackbody_rec709(t), tabulated = table(static_cast<float>(t));
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(tabulated[c], direct[c], 1e-4 * luminance(direct)) << t;
    }
    const double ratio =
        luminance(blackbody_rec709(80000.0)) / luminance(blackbody_rec709(40000.0));
    EXPECT_GT(ratio, 2.0);
    EXPECT_LT(ratio, 2.5);
}

/// A 24³ block of density 1 with a constant temperature grid in a second file.
MediumSet emitting_block(float sigma_a, float temperature_k) {
    const std::string density = test::write_box("emission_density", 24, 1.0f, 1.0);
    DenseVoxels t;
    t.dims = IVec3(24);
    t.values.assign(24 * 24 * 24, temperature_k);
    const std::string temperature = test::temp_grid_path("emission_temperature");
    write_fog_volume(temperature, "temperature", t, 1.0, Vec3(0.0f));
    Json keys = {{"sigma_a", sigma_a},
                 {"sigma_s", 0.0},
                 {"temperature", {{"file", temperature}, {"grid", "temperature"}}}};
    std::vector<Medium> media;
    media.push_back(test::vdb_medium(density, keys));
    return MediumSet(std::move(media));
}

TEST(Emission, ConstantHotAbsorberMatchesClosedFormForEveryEstimator) {
    const float sigma_a = 0.15f, temperature = 1800.0f, d = 12.0f;
    const MediumSet media = emitting_block(sigma_a, temperature);
    ASSERT_TRUE(media.emits());
    const Rgb b = blackbody_rec709(temperature);
    const double expected = luminance(b) * (1.0 - std::exp(-sigma_a * d));
    // The segment lies where the trilinear density and temperature are constant (indices 5..17).
    const Ray ray{Vec3(5.0f, 11.3f, 12.1f), Vec3(1.0f, 0.0f, 0.0f), 0.0f, d};
    for (Estimator e :
         {Estimator::Delta, Estimator::Ratio, Estimator::ResidualRatio, Estimator::March}) {
        VolumeSettings settings;
        settings.estimator = e;
        settings.integrator = VolumeIntegrator::Single;
        settings.step_voxels = 0.5f;
        const int n = 40000;
        double sum = 0.0, sum2 = 0.0;
        VolumeCounters counters;
        for (int i = 0; i < n; ++i) {
            Pcg32 rng(static_cast<uint64_t>(i), 11u);
            const VolumeResult r =
                integrate_media(media, {}, nullptr, nullptr, ray, settings, false, rng, counters);
            const double y = luminance(r.radiance);
            sum += y;
            sum2 += y * y;
        }
        const double mean = sum / n;
        const double stderr_mean = std::sqrt(std::max(sum2 / n - mean * mean, 0.0) / n);
        EXPECT_NEAR(mean, expected, 4.0 * stderr_mean + 1e-4 * expected)
            << "estimator " << static_cast<int>(e);
        // A 2% bias fails: the tolerance stays well below it.
        EXPECT_LT(4.0 * stderr_mean, 0.01 * expected);
    }
}

TEST(Emission, ColdOrTransparentMediaEmitNothing) {
    EXPECT_FALSE(emitting_block(0.0f, 1800.0f).emits());
    const MediumSet cold = emitting_block(0.2f, 0.0f);
    VolumeSettings settings;
    settings.estimator = Estimator::ResidualRatio;
    VolumeCounters counters;
    Pcg32 rng(1u, 2u);
    const Ray ray{Vec3(5.0f, 11.3f, 12.1f), Vec3(1.0f, 0.0f, 0.0f), 0.0f, 12.0f};
    const VolumeResult r =
        integrate_media(cold, {}, nullptr, nullptr, ray, settings, false, rng, counters);
    EXPECT_EQ(luminance(r.radiance), 0.0f);
}

}  // namespace
}  // namespace kasumi
