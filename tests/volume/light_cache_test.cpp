// The cached directional-light transmittance (volume/light_cache.h) against Beer-Lambert.
//
// A constant block of n³ voxels ramps to 0 over one voxel at each face and integrates like a
// sharp box from index -0.5 to n - 0.5 (tests/volume/vdb_test_grids.h). Far from the box's edges
// the density along an oblique light ray depends only on the coordinate along the exit face's
// normal, linearly inside each voxel, so Simpson's rule per lattice step is exact and the
// density integral is linear across each slice, where the bilinear transport is exact too:
// the cache must reproduce exp(-sigma_t d) to rounding (1e-4 relative), for lights along every
// major axis and both signs. Deterministic: no false failures.
#include "volume/light_cache.h"
#include "core/rng.h"
#include "tests/volume/vdb_test_grids.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace kasumi {
namespace {

TEST(LightCache, ConstantBlockMatchesBeerLambertAlongEveryAxis) {
    const int n = 40;
    const float sigma_t = 0.05f;
    const std::string path = test::write_box("light_cache_block", n, 1.0f, 1.0);
    const Medium medium = test::vdb_medium(path, {{"density_scale", sigma_t}, {"albedo", 0.9}});
    const VdbMedium& grid = std::get<VdbMedium>(medium.model);
    const Vec3 p(18.3f, 19.6f, 20.2f);
    for (int axis = 0; axis < 3; ++axis) {
        for (float sign : {1.0f, -1.0f}) {
            Vec3 toward(0.23f, -0.17f, 0.31f);
            toward[axis] = sign;
            toward = glm::normalize(toward);
            const LightTransmittanceCache cache(grid, toward);
            // Distance to the exit face along `axis` (sharp-box equivalent at -0.5 or n - 0.5).
            const float face = sign > 0.0f ? n - 0.5f : -0.5f;
            const float d = (face - p[axis]) / toward[axis];
            const auto t = cache.transmittance(p);
            ASSERT_TRUE(t.has_value());
            const float expected = std::exp(-sigma_t * d);
            EXPECT_NEAR(t->r, expected, 1e-4f * expected) << "axis " << axis << " sign " << sign;
            EXPECT_EQ(t->r, t->b);
        }
    }
}

/// The sweep of light_cache.h written point by point, as the cache was first built: D(p) =
/// D bilinear on the upstream slice at p + step + Simpson's rule on grid.density() at p, the
/// midpoint and p + step.
std::vector<float> per_point_sweep(const DensityGrid& grid, const Mat4& world_to_index,
                                   const Vec3& toward_light, float cell, IVec3 dims) {
    std::vector<float> d(static_cast<size_t>(dims.x) * dims.y * dims.z, 0.0f);
    const auto at = [&](IVec3 p) -> float& {
        return d[static_cast<size_t>(p.x) + static_cast<size_t>(dims.x) * (p.y + dims.y * p.z)];
    };
    const Vec3 d_index(world_to_index * Vec4(toward_light, 0.0f));
    int a = 0;
    for (int c = 1; c < 3; ++c)
        if (std::abs(d_index[c]) > std::abs(d_index[a]))
            a = c;
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    const Vec3 step = d_index * (cell / std::abs(d_index[a]));
    const float length_m = cell / std::abs(d_index[a]);
    const int toward = step[a] > 0.0f ? 1 : -1;
    for (int slice = toward > 0 ? dims[a] - 1 : 0; slice >= 0 && slice < dims[a]; slice -= toward) {
        IVec3 p;
        p[a] = slice;
        for (p[c] = 0; p[c] < dims[c]; ++p[c])
            for (p[b] = 0; p[b] < dims[b]; ++p[b]) {
                const Vec3 x = grid.lower() + cell * Vec3(p);
                float upstream = 0.0f;
                if (slice + toward >= 0 && slice + toward < dims[a]) {
                    const float u = static_cast<float>(p[b]) + step[b] / cell;
                    const float v = static_cast<float>(p[c]) + step[c] / cell;
                    const int iu = static_cast<int>(std::floor(u));
                    const int iv = static_cast<int>(std::floor(v));
                    const float wu[2] = {1.0f - (u - std::floor(u)), u - std::floor(u)};
                    const float wv[2] = {1.0f - (v - std::floor(v)), v - std::floor(v)};
                    for (int dv = 0; dv < 2; ++dv)
                        for (int du = 0; du < 2; ++du) {
                            IVec3 q;
                            q[a] = slice + toward;
                            q[b] = iu + du;
                            q[c] = iv + dv;
                            if (q[b] < 0 || q[b] >= dims[b] || q[c] < 0 || q[c] >= dims[c])
                                continue;
                            upstream += wu[du] * wv[dv] * at(q);
                        }
                }
                at(p) = upstream + length_m *
                                       (grid.density(x) + 4.0f * grid.density(x + 0.5f * step) +
                                        grid.density(x + step)) *
                                       (1.0f / 6.0f);
            }
    }
    return d;
}

// The sweep's per-axis lookups (DensityGrid::axis_split, interpolation skipped where a
// lookup lies on voxels) must give the per-point form's cache bit for bit, on a grid of random
// densities, for lights along each major axis in both directions, at lattice spacing 1 (the
// midpoint between voxels: the general lookup) and 2 (every lookup on voxels along the
// slices' axis). Deterministic.
TEST(LightCache, SweepEqualsThePerPointFormBitForBit) {
    for (const int n : {24, 96}) {  // lattice spacing 1 and 2 voxels (at most 2^19 points)
        DenseVoxels v;
        v.dims = IVec3(n);
        v.values.resize(static_cast<size_t>(n) * n * n);
        Pcg32 rng(17, 5);
        for (float& x : v.values)
            x = rng.next_float() < 0.3f ? 0.0f : 3.0f * rng.next_float();
        const std::string path = test::temp_grid_path("light_cache_random_" + std::to_string(n));
        write_fog_volume(path, "density", v, 2.0, Vec3(-5.0f, 3.0f, 1.0f));
        const Medium medium = test::vdb_medium(path, {{"density_scale", 0.02}});
        const VdbMedium& grid = std::get<VdbMedium>(medium.model);
        for (int axis = 0; axis < 3; ++axis)
            for (float sign : {1.0f, -1.0f}) {
                Vec3 toward(0.37f, -0.29f, 0.21f);
                toward[axis] = sign;
                toward = glm::normalize(toward);
                const LightTransmittanceCache cache(grid, toward);
                ASSERT_EQ(cache.cell(), n == 24 ? 1.0f : 2.0f);
                const std::vector<float> expected = per_point_sweep(
                    *grid.grid, grid.world_to_index, toward, cache.cell(), cache.dims());
                const IVec3 dims = cache.dims();
                size_t i = 0, positive = 0;
                for (int z = 0; z < dims.z; ++z)
                    for (int y = 0; y < dims.y; ++y)
                        for (int x = 0; x < dims.x; ++x, ++i) {
                            ASSERT_EQ(cache.density_integral(x, y, z), expected[i])
                                << "n " << n << " axis " << axis << " sign " << sign << " at " << x
                                << " " << y << " " << z;
                            positive += expected[i] > 0.0f;
                        }
                EXPECT_GT(positive, i / 4);  // the lookups did reach the density
            }
    }
}

TEST(LightCache, OutsideTheLatticeAsksTheCallerToWalk) {
    const std::string path = test::write_box("light_cache_small", 8, 1.0f, 1.0);
    const Medium medium = test::vdb_medium(path, {{"density_scale", 0.1}});
    const LightTransmittanceCache cache(std::get<VdbMedium>(medium.model), Vec3(0, 1, 0));
    EXPECT_FALSE(cache.transmittance(Vec3(100.0f, 0.0f, 0.0f)).has_value());
}

}  // namespace
}  // namespace kasumi
