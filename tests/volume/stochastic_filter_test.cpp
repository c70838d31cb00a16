// Stochastic (one-voxel) trilinear filtering, render.volume.density_filter "stochastic"
// (DensityGrid::density_in_stochastic; Pharr, Wronski, Salvi & Fajardo 2024): a lookup picks one
// of the cell's 8 voxels with probability equal to its trilinear weight. Checked: the picks'
// frequencies (chi-square) and the lookups' mean equal the trilinear weights and value (a
// planted 2% error fails both); the trackers' transmittance with it on equals a fine trilinear
// march within 4 standard errors; a render with it on is the same for 1 and 2 threads and
// differs from the trilinear render (the option reaches the trackers).
#include "render/renderer.h"
#include "scene/scene_loader.h"
#include "tests/render/quiet_render_options.h"
#include "tests/sample_mean.h"
#include "volume/grid/density_grid.h"
#include "volume/medium_set.h"
#include "volume/transmittance.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <memory>

namespace kasumi {
namespace {

constexpr int kEdge = 32;  ///< voxels per grid edge: 4 bricks of 8 cells per axis

/// Densities in [0, 2) from a hash of each voxel's index, on the bricks whose coordinates sum
/// to an even number (the others empty).
std::shared_ptr<DensityGrid> random_grid(uint64_t seed) {
    auto grid = std::make_shared<DensityGrid>(IVec3(0), IVec3(kEdge - 1));
    for (int i = 0; i < kEdge * kEdge * kEdge; ++i) {
        const IVec3 v(i % kEdge, (i / kEdge) % kEdge, i / (kEdge * kEdge));
        if (((v.x / 8 + v.y / 8 + v.z / 8) & 1) == 0)
            grid->set(v, static_cast<float>(mix64(seed ^ mix64(static_cast<uint64_t>(i))) >> 40) *
                             0x1p-23f);
    }
    grid->finalize();
    return grid;
}

uint64_t bits64(Pcg32& rng) {
    const uint64_t hi = rng.next_u32();
    return (hi << 32) | rng.next_u32();
}

TEST(StochasticFilter, PicksEachVoxelWithItsTrilinearWeight) {
    // One cell whose 8 voxels hold 1, 2, 4, ..., 128: the value names the voxel picked.
    DensityGrid grid(IVec3(0), IVec3(7));
    for (int c = 0; c < 8; ++c)
        grid.set(IVec3(2 + (c & 1), 3 + ((c >> 1) & 1), 4 + ((c >> 2) & 1)),
                 static_cast<float>(1 << c));
    grid.finalize();
    const Vec3 f(0.3f, 0.85f, 0.05f);
    const Vec3 p = Vec3(2.0f, 3.0f, 4.0f) + f;
    constexpr int n = 400000;
    std::array<int, 8> count{};
    Pcg32 rng(11, 1);
    for (int i = 0; i < n; ++i) {
        const float v = grid.density_stochastic(p, bits64(rng));
        const int c = static_cast<int>(std::lround(std::log2(v)));
        ASSERT_EQ(static_cast<float>(1 << c), v);
        ++count[c];
    }
    const auto chi_square = [&](double planted) {
        double chi2 = 0.0;
        for (int c = 0; c < 8; ++c) {
            double w =
                (c & 1 ? f.x : 1.0 - f.x) * (c & 2 ? f.y : 1.0 - f.y) * (c & 4 ? f.z : 1.0 - f.z);
            if (c == 0)
                w *= 1.0 + planted;
            if (c == 1)
                w -= planted * (1.0 - f.x) * (1.0 - f.y) * (1.0 - f.z);  // the weights sum to 1
            const double expected = n * w;
            chi2 += (count[c] - expected) * (count[c] - expected) / expected;
        }
        return chi2;
    };
    // 7 degrees of freedom: P(chi2 > 29.9) = 1e-4.
    EXPECT_LT(chi_square(0.0), 29.9);
    // Teeth: weights off by 2% (relative, on the heaviest voxel) are rejected.
    EXPECT_GT(chi_square(0.02), 29.9);
    // A point on a cell face (f.x = 0) never picks a voxel beyond it (odd voxels: 2, 8, 32,
    // 128).
    for (int i = 0; i < 1000; ++i) {
        const float v = grid.density_stochastic(Vec3(2.0f, 3.5f, 4.5f), bits64(rng));
        EXPECT_TRUE(v == 1.0f || v == 4.0f || v == 16.0f || v == 64.0f) << v;
    }
}

TEST(StochasticFilter, MeanOfLookupsIsTheTrilinearDensity) {
    const auto grid = random_grid(3);
    Pcg32 points(7, 2);
    int checked = 0;
    for (int k = 0; k < 40; ++k) {
        const Vec3 p(points.next_float() * (kEdge - 1), points.next_float() * (kEdge - 1),
                     points.next_float() * (kEdge - 1));
        const double trilinear = grid->density(p);
        if (!(trilinear > 0.2))
            continue;
        ++checked;
        const MeanAndError m = mean_over_streams(200000, 100 + k, [&](Pcg32& rng) {
            return static_cast<double>(grid->density_stochastic(p, bits64(rng)));
        });
        // 4 standard errors: a false failure about once in 16000 per point.
        EXPECT_NEAR(m.mean, trilinear, 4.0 * m.stderr_) << "point " << k;
        // Teeth: a planted 2% error would fail.
        EXPECT_GT(std::abs(m.mean - 1.02 * trilinear), 4.0 * m.stderr_) << "point " << k;
    }
    EXPECT_GE(checked, 10);
}

TEST(StochasticFilter, TrackersTransmittanceMatchesTheTrilinearMarch) {
    const auto grid = random_grid(9);
    // sigma_s 0.08, sigma_a 0.02 per unit density, index space = world space.
    VdbMedium v;
    v.grid = grid;
    v.bounds_world = Bounds3{grid->lower(), grid->upper()};
    v.sigma_s_per_density = Rgb(0.08f);
    v.sigma_a_per_density = v.sigma_s_per_density * 0.25f;
    const MediumSet trilinear({Medium{"blocks", v}});
    MediumSet stochastic({Medium{"blocks", v}});
    stochastic.set_stochastic_filter(true);
    ASSERT_NE(stochastic.single_grid(), nullptr);
    const Ray rays[] = {
        {Vec3(-3.0f, 10.3f, 17.9f), glm::normalize(Vec3(1.0f, 0.31f, -0.17f)), 0.0f, 60.0f},
        {Vec3(35.0f, 2.5f, 30.1f), glm::normalize(Vec3(-1.0f, 0.8f, -0.9f)), 0.0f, 70.0f},
        {Vec3(12.2f, 13.3f, 6.1f), Vec3(0.0f, 0.0f, 1.0f), 3.0f, 30.0f},  // starts inside
    };
    // The option reaches the trackers' lookups: mid-cell, the value is one voxel, not the
    // trilinear blend.
    {
        const RayMediaQuery q(stochastic, rays[2]);
        const Vec3 p = rays[2].at(9.37f);
        const double exact = grid->density(p);
        bool differs = false;
        grid->walk(rays[2].origin, rays[2].direction, 9.0f, 9.5f,
                   [&](const BrickSpan&, const BrickRef& b) {
                       for (int i = 0; i < 8; ++i)
                           differs = differs || std::abs(q.density_in(0, b, 9.37f) - exact) > 1e-4;
                       return false;
                   });
        EXPECT_TRUE(differs);
    }
    int rays_checked = 0;
    for (const Ray& ray : rays) {
        VolumeCounters counters;
        Pcg32 rng(1, 1);
        const double reference =
            estimate_transmittance(trilinear, ray, Estimator::March, 1.0f / 64.0f, rng, counters).r;
        if (!(reference > 0.02 && reference < 0.95))
            continue;
        ++rays_checked;
        for (Estimator e : {Estimator::Delta, Estimator::Ratio, Estimator::ResidualRatio,
                            Estimator::UnbiasedMarch}) {
            const MeanAndError m = mean_over_streams(100000, 17, [&](Pcg32& r) {
                VolumeCounters c;
                return static_cast<double>(
                    estimate_transmittance(stochastic, ray, e, 0.25f, r, c).r);
            });
            // 4 standard errors: a false failure about once in 16000 per check.
            EXPECT_NEAR(m.mean, reference, 4.0 * m.stderr_ + 1e-4) << estimator_name(e);
            // Teeth: a 5% bias would fail.
            EXPECT_LT(4.0 * m.stderr_ + 1e-4, 0.05 * reference) << estimator_name(e);
        }
    }
    EXPECT_GE(rays_checked, 2);
}

Image render_cloud(const std::string& filter, int threads) {
    SceneDesc desc = load_scene(KASUMI_SOURCE_DIR "/data/scenes/cloud.json",
                                {{"/film/width", "48"},
                                 {"/film/height", "27"},
                                 {"/film/spp", "2"},
                                 {"/render/volume/density_filter", "\"" + filter + "\""}});
    const SceneRuntime runtime(std::move(desc));
    return render_image(runtime, quiet(threads)).film.to_image();
}

TEST(StochasticFilter, RenderIsTheSameForOneAndTwoThreads) {
    const Image one = render_cloud("stochastic", 1);
    const Image two = render_cloud("stochastic", 2);
    const Image tri = render_cloud("trilinear", 2);
    ASSERT_EQ(one.channels.size(), two.channels.size());
    bool differs_from_trilinear = false;
    for (size_t c = 0; c < one.channels.size(); ++c) {
        ASSERT_EQ(one.channels[c].name, two.channels[c].name);
        EXPECT_EQ(one.channels[c].data, two.channels[c].data) << one.channels[c].name;
        if (const ImageChannel* t = tri.find(one.channels[c].name))
            differs_from_trilinear = differs_from_trilinear || t->data != one.channels[c].data;
    }
    EXPECT_TRUE(differs_from_trilinear);
}

}  // namespace
}  // namespace kasumi
