// Transmittance through VDB grids against exact answers, for every estimator.
#include "core/error.h"
#include "vdb_test_grids.h"
#include "volume/transmittance.h"

#include <gtest/gtest.h>

#include <cmath>

namespace kasumi {
namespace {

using test::vdb_medium;
using test::write_box;

struct Estimate {
    Rgb mean{0.0f};
    double stderr_ = 0.0;  ///< of the red channel
};

Estimate average(const MediumSet& media, const Ray& ray, Estimator estimator, int n,
                 float step_m = 0.05f, uint64_t seed = 1) {
    VolumeCounters counters;
    glm::dvec3 sum(0.0);
    double sum_sq = 0.0;
    for (int i = 0; i < n; ++i) {
        Pcg32 rng(seed, static_cast<uint64_t>(i));
        const Rgb t = estimate_transmittance(media, ray, estimator, step_m, rng, counters);
        sum += glm::dvec3(t);
        sum_sq += static_cast<double>(t.r) * t.r;
    }
    Estimate e;
    const glm::dvec3 mean = sum / static_cast<double>(n);
    e.mean = Rgb(mean);
    e.stderr_ = std::sqrt(std::max(0.0, sum_sq / n - mean.x * mean.x) / (n - 1));
    return e;
}

const Estimator kUnbiased[] = {Estimator::Delta, Estimator::Ratio, Estimator::ResidualRatio};

/// 16³ voxels of 0.5 m from the origin: the effective box is [-0.25, 7.75] m per axis.
class ConstantBox : public ::testing::Test {
  protected:
    static void SetUpTestSuite() { s_path = write_box("box16", 16, 1.0f, 0.5); }
    static MediumSet media(float density_scale) {
        return MediumSet({vdb_medium(s_path, {{"density_scale", density_scale}, {"albedo", 0.8}})});
    }
    static inline std::string s_path;
};

TEST_F(ConstantBox, EveryUnbiasedEstimatorMatchesBeerLambert) {
    // Through two faces along x, 8 m of effective path: tau = 8 * density_scale = 0.5.
    const MediumSet m = media(0.0625f);
    const Ray ray{Vec3(-3.0f, 3.6f, 4.1f), Vec3(1, 0, 0), 0.0f, 14.0f};
    const double exact = std::exp(-0.5);
    for (Estimator e : kUnbiased) {
        const Estimate t = average(m, ray, e, 10000);
        // 4 standard errors: a false failure about once in 16000 runs per estimator.
        EXPECT_NEAR(t.mean.r, exact, 4.0 * t.stderr_) << estimator_name(e);
        // The comparison has teeth: a 5% bias would fail.
        EXPECT_LT(4.0 * t.stderr_, 0.05 * exact) << estimator_name(e);
        EXPECT_EQ(t.mean.r, t.mean.g);  // grey medium
    }
}

TEST_F(ConstantBox, MarchConvergesAtSecondOrder) {
    // From inside the plateau out through the +x face's one-voxel ramp: the density along the
    // ray has one kink not on a brick boundary (where the ramp ends, index 16), where the
    // trapezoid rule's error is (slope jump) h^2 a(1 - a) / 2 for the kink's relative position
    // a in its step, uniform under the jitter: the RMS error scales exactly as h^2.
    const MediumSet m = media(0.25f);
    const Vec3 dir = glm::normalize(Vec3(1.0f, 0.35f, 0.1f));
    const Ray ray{Vec3(3.0f, 3.6f, 4.1f), dir, 0.0f, 15.0f};
    const double exact = std::exp(-0.25 * (7.75 - 3.0) / dir.x);
    double previous = 0.0;
    for (float step : {0.4f, 0.2f, 0.1f, 0.05f}) {
        double sq = 0.0;
        const int n = 400;
        for (int i = 0; i < n; ++i) {
            const Estimate t = average(m, ray, Estimator::March, 1, step, 100 + i);
            sq += (t.mean.r - exact) * (t.mean.r - exact);
        }
        const double rms = std::sqrt(sq / n);
        if (previous > 0.0) {
            const double order = std::log2(previous / rms);
            EXPECT_GT(order, 1.8) << "step " << step << " rms " << rms;
            EXPECT_LT(order, 2.2) << "step " << step << " rms " << rms;
        }
        previous = rms;
    }
    EXPECT_LT(previous, 1e-4);
}

TEST(VdbTransform, VoxelSizeTranslateRotateScaleAgree) {
    // The same 16 m cube three ways (32 voxels of 0.5 m, 16 of 1 m, 8 of 2 m), each placed by
    // the medium's transform (scale 0.5 then rotate and translate); a ray crossing two faces
    // through the middle sees tau = sigma * 16 m * 0.5 (scale) = 0.8 for sigma = 0.1.
    const Json transform = {
        {"translate", {10.0, -3.0, 2.0}}, {"rotate", {30.0, 45.0, 60.0}}, {"scale", 0.5}};
    struct Case {
        int n;
        double voxel;
    };
    for (const Case c : {Case{32, 0.5}, Case{16, 1.0}, Case{8, 2.0}}) {
        const std::string path = write_box("cube" + std::to_string(c.n), c.n, 1.0f, c.voxel,
                                           Vec3(static_cast<float>(-0.5 * 16.0 + 0.5 * c.voxel)));
        const MediumSet media({vdb_medium(
            path, {{"density_scale", 0.1}, {"albedo", 1.0}, {"transform", transform}})});
        // The cube's centre is the local origin; a local ray along a slanted direction through
        // it crosses two opposite faces (|x| reaches 8 first), mapped to world by the transform.
        const auto& v = std::get<VdbMedium>(media.media()[0].model);
        const Mat4 index_to_world = glm::inverse(v.world_to_index);
        const Vec3 centre_index = Vec3(static_cast<float>((16.0 / c.voxel - 1.0) * 0.5));
        const Vec3 dir_local = glm::normalize(Vec3(1.0f, 0.2f, -0.1f));
        const Vec3 o_world(index_to_world *
                           Vec4(centre_index - dir_local * (20.0f / float(c.voxel)), 1.0f));
        const Vec3 p_world(index_to_world * Vec4(centre_index, 1.0f));
        const Vec3 dir_world = glm::normalize(p_world - o_world);
        const Ray ray{o_world, dir_world, 0.0f, 2.0f * glm::length(p_world - o_world)};
        // World path length inside the cube: 16 m / |dir_local.x| scaled by 0.5.
        const double tau = 0.1 * 0.5 * 16.0 / dir_local.x;
        const Estimate t = average(media, ray, Estimator::ResidualRatio, 4000);
        EXPECT_NEAR(t.mean.r, std::exp(-tau), 4.0 * t.stderr_ + 1e-5) << "voxel " << c.voxel;
        const Estimate m = average(media, ray, Estimator::March, 64, 0.01f);
        EXPECT_NEAR(m.mean.r, std::exp(-tau), 2e-4) << "voxel " << c.voxel;
    }
}

TEST(VdbEdgeCases, EmptyGridAndZeroDensityAreClear) {
    const std::string empty = write_box("empty", 8, 0.0f, 1.0);
    const std::string box = write_box("box8", 8, 1.0f, 1.0);
    const Ray ray{Vec3(-5.0f, 3.5f, 3.5f), Vec3(1, 0, 0), 0.0f, kInfinity};
    for (const MediumSet& media : {MediumSet({vdb_medium(empty, {{"density_scale", 5.0}})}),
                                   MediumSet({vdb_medium(box, {{"density_scale", 0.0}})})}) {
        for (Estimator e :
             {Estimator::March, Estimator::Delta, Estimator::Ratio, Estimator::ResidualRatio}) {
            EXPECT_EQ(average(media, ray, e, 16).mean, Rgb(1.0f)) << estimator_name(e);
        }
    }
}

TEST(VdbEdgeCases, InsideGrazingAndBoundaryRays) {
    // 8³ voxels of 1 m at the origin, sigma = 0.5: effective box [-0.5, 7.5] m.
    const std::string box = write_box("box8", 8, 1.0f, 1.0);
    const MediumSet media({vdb_medium(box, {{"density_scale", 0.5}})});
    struct Case {
        const char* what;
        Ray ray;
        double tau;
    };
    const Case cases[] = {
        // Camera inside the plateau, looking out through +x: 7.5 - 3 = 4.5 m of path.
        {"inside", Ray{Vec3(3.0f, 3.5f, 3.5f), Vec3(1, 0, 0), 0.0f, kInfinity}, 0.5 * 4.5},
        // Along the face's mid-ramp plane y = -0.5: density 1/2 all the way across.
        {"grazing", Ray{Vec3(-5.0f, -0.5f, 3.5f), Vec3(1, 0, 0), 0.0f, kInfinity}, 0.25 * 8.0},
        // Along y = -1, the outer edge of the stored region: density 0.
        {"outside edge", Ray{Vec3(-5.0f, -1.0f, 3.5f), Vec3(1, 0, 0), 0.0f, kInfinity}, 0.0},
        // Starting exactly on the stored region's boundary x = -1.
        {"on boundary", Ray{Vec3(-1.0f, 3.5f, 3.5f), Vec3(1, 0, 0), 0.0f, kInfinity}, 0.5 * 8.0},
    };
    for (const Case& c : cases) {
        for (Estimator e : kUnbiased) {
            const Estimate t = average(media, c.ray, e, 4000);
            EXPECT_TRUE(std::isfinite(t.mean.r));
            EXPECT_NEAR(t.mean.r, std::exp(-c.tau), 4.0 * t.stderr_ + 1e-6)
                << c.what << " " << estimator_name(e);
        }
        const Estimate m = average(media, c.ray, Estimator::March, 8, 0.01f);
        EXPECT_NEAR(m.mean.r, std::exp(-c.tau), 1e-4) << c.what << " march";
    }
}

TEST(VdbEdgeCases, OpticalDepthFromTinyToHugeIsStable) {
    const std::string box = write_box("box8", 8, 1.0f, 1.0);
    const Ray ray{Vec3(-5.0f, 3.5f, 3.5f), Vec3(1, 0, 0), 0.0f, kInfinity};
    for (Estimator e :
         {Estimator::March, Estimator::Delta, Estimator::Ratio, Estimator::ResidualRatio}) {
        double previous = 1.0;
        for (double tau = 1e-8; tau <= 1.0001e4; tau *= 10.0) {
            const MediumSet media({vdb_medium(box, {{"density_scale", tau / 8.0}})});
            const Estimate t = average(media, ray, e, 2000, 0.02f);
            ASSERT_TRUE(std::isfinite(t.mean.r)) << estimator_name(e) << " tau " << tau;
            EXPECT_GE(t.mean.r, 0.0f);
            EXPECT_LE(t.mean.r, 1.0f);
            // Every estimate lies in [0, 1] with mean T, so its variance is at most T (1 - T):
            // a bound that holds even when a run of 2000 samples sees no collision at all.
            const double exact = std::exp(-tau);
            const double sigma = std::sqrt(exact * (1.0 - exact) / 2000.0);
            EXPECT_NEAR(t.mean.r, exact, 5.0 * std::max(sigma, t.stderr_) + 1e-6)
                << estimator_name(e) << " tau " << tau;
            // Monotone up to the noise of the two estimates.
            EXPECT_LE(t.mean.r, previous + 5.0 * t.stderr_ + 1e-6) << estimator_name(e);
            previous = t.mean.r;
        }
    }
}

TEST(VdbEdgeCases, DensityScaleOfAMillionIsOpaqueAndQuick) {
    const std::string box = write_box("box8", 8, 1.0f, 1.0);
    const MediumSet media({vdb_medium(box, {{"density_scale", 1e6}})});
    const Ray ray{Vec3(-5.0f, 3.5f, 3.5f), Vec3(1, 0, 0), 0.0f, kInfinity};
    for (Estimator e : kUnbiased) {
        VolumeCounters counters;
        Pcg32 rng(1, 2);
        for (int i = 0; i < 100; ++i) {
            const Rgb t = estimate_transmittance(media, ray, e, 0.1f, rng, counters);
            EXPECT_EQ(t, Rgb(0.0f)) << estimator_name(e);
        }
        // The walks end within the one-voxel entry ramp: about sqrt(2 mu) ~ 1400 null
        // collisions there for the majorant mu = 1e6 of the boundary bricks, then a real one
        // (delta) or roulette (ratio trackers). Bounded, not proportional to tau = 8e6.
        EXPECT_LT(counters.density_lookups, 100u * 5000u) << estimator_name(e);
    }
}

TEST(VdbLoad, BadVoxelsAndMissingFilesAreInputErrors) {
    DenseVoxels v;
    v.dims = IVec3(4);
    v.values.assign(64, 0.5f);
    v.values[21] = std::nanf("");
    const std::string nan_path = test::temp_grid_path("nan");
    write_fog_volume(nan_path, "density", v, 1.0, Vec3(0.0f));
    v.values[21] = -0.25f;
    const std::string negative_path = test::temp_grid_path("negative");
    write_fog_volume(negative_path, "density", v, 1.0, Vec3(0.0f));

    const auto message = [](const std::string& path, Json keys) -> std::string {
        try {
            vdb_medium(path, std::move(keys));
        } catch (const Error& e) {
            EXPECT_EQ(e.kind(), ErrorKind::Input);
            return e.what();
        }
        return "no error";
    };
    for (const std::string& path : {nan_path, negative_path}) {
        const std::string m = message(path, Json::object());
        EXPECT_NE(m.find("test.json: /media/0/file"), std::string::npos) << m;
        EXPECT_NE(m.find(path), std::string::npos) << m;
        EXPECT_NE(m.find("voxel (1, 1, 1)"), std::string::npos) << m;
    }
    const std::string missing = message(test::temp_grid_path("does_not_exist"), Json::object());
    EXPECT_NE(missing.find("no such file"), std::string::npos) << missing;
    const std::string no_grid =
        message(write_box("box4", 4, 1.0f, 1.0), Json{{"grid", "temperature"}});
    EXPECT_NE(no_grid.find("no grid \"temperature\""), std::string::npos) << no_grid;
}

}  // namespace
}  // namespace kasumi
