// The parallel grid construction (volume/grid/density_grid_build.h) against the per-voxel one it
// replaces at load time (DensityGrid::set of every active voxel, then finalize): on random
// sparse blocks at every alignment of the grid's bricks to the blocks, the two grids must be
// identical: the same bricks, the same bounds, bit-identical densities at any point and the same
// brick spans along any ray. Deterministic (fixed seeds), so no false failures.
#include "volume/grid/density_grid_build.h"

#include "core/rng.h"
#include "vdb_test_grids.h"
#include "volume/grid/vdb_io.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <set>
#include <tuple>

namespace kasumi {
namespace {

struct RandomBlocks {
    std::vector<std::vector<float>> values;
    std::vector<VoxelBlock> blocks;
    IVec3 index_min{std::numeric_limits<int>::max()};
    IVec3 index_max{std::numeric_limits<int>::min()};
};

/// `count` blocks at distinct random origins (multiples of 8, as OpenVDB's leaves, shifted by
/// `shift`), about half of the voxels active, a third of those exactly 0; inactive voxels hold
/// junk (negative, NaN) that must be ignored. One block is a full constant block (an active
/// tile cut into blocks).
RandomBlocks random_blocks(uint64_t seed, int count, IVec3 shift) {
    Pcg32 rng(seed, 3);
    RandomBlocks r;
    std::set<std::tuple<int, int, int>> used;
    r.values.reserve(count);
    while (static_cast<int>(r.blocks.size()) < count) {
        const IVec3 cell(static_cast<int>(rng.next_u32() % 9) - 4,
                         static_cast<int>(rng.next_u32() % 9) - 4,
                         static_cast<int>(rng.next_u32() % 9) - 4);
        if (!used.insert({cell.x, cell.y, cell.z}).second)
            continue;
        VoxelBlock block;
        block.origin = cell * VoxelBlock::kEdge + shift;
        std::vector<float> v(VoxelBlock::kVoxels);
        const bool constant = r.blocks.empty();
        for (int n = 0; n < VoxelBlock::kVoxels; ++n) {
            const bool on = constant || rng.next_float() < 0.5f;
            if (on) {
                block.active[n / 64] |= uint64_t(1) << (n % 64);
                v[n] =
                    constant ? 0.75f : (rng.next_float() < 0.33f ? 0.0f : 2.0f * rng.next_float());
                const IVec3 index = block.origin + IVec3(n >> 6, (n >> 3) & 7, n & 7);
                r.index_min = glm::min(r.index_min, index);
                r.index_max = glm::max(r.index_max, index);
            } else {
                v[n] = rng.next_float() < 0.5f ? -1.0f : std::nanf("");
            }
        }
        r.values.push_back(std::move(v));
        block.values = r.values.back().data();
        r.blocks.push_back(block);
    }
    return r;
}

DensityGrid reference_grid(const RandomBlocks& r) {
    DensityGrid grid(r.index_min, r.index_max);
    for (const VoxelBlock& block : r.blocks)
        for (int n = 0; n < VoxelBlock::kVoxels; ++n)
            if (block.active[n / 64] >> (n % 64) & 1)
                grid.set(block.origin + IVec3(n >> 6, (n >> 3) & 7, n & 7), block.values[n]);
    grid.finalize();
    return grid;
}

TEST(DensityGridBuild, EqualsPerVoxelSetAtEveryBrickAlignment) {
    for (int s = 0; s < 8; ++s) {
        // The grid's bricks start one voxel below the active box, so shifting the blocks moves
        // the brick boundaries (and the aprons) through every position inside a block.
        const IVec3 shift(s, (3 * s) % 8, (5 * s + 1) % 8);
        const RandomBlocks r = random_blocks(100 + s, 40, shift);
        const DensityGrid expected = reference_grid(r);
        const DensityGridBuild built =
            DensityGridBuilder::build(r.index_min, r.index_max, r.blocks);
        ASSERT_FALSE(built.has_invalid);
        ASSERT_TRUE(built.grid);
        const DensityGrid& grid = *built.grid;
        ASSERT_GT(expected.allocated_bricks(), 0u);
        EXPECT_EQ(grid.allocated_bricks(), expected.allocated_bricks()) << s;
        EXPECT_EQ(grid.total_bricks(), expected.total_bricks());
        EXPECT_EQ(grid.max_density(), expected.max_density());
        EXPECT_EQ(grid.lower(), expected.lower());
        EXPECT_EQ(grid.upper(), expected.upper());

        Pcg32 rng(7 + s, 1);
        const Vec3 lo = grid.lower() - Vec3(2.0f), extent = grid.upper() - grid.lower() + 4.0f;
        int nonzero = 0;
        for (int i = 0; i < 200000; ++i) {
            const Vec3 p = lo + extent * Vec3(rng.next_float(), rng.next_float(), rng.next_float());
            const float d = grid.density(p);
            ASSERT_EQ(d, expected.density(p)) << s << " at " << p.x << ", " << p.y << ", " << p.z;
            nonzero += d > 0.0f;
        }
        EXPECT_GT(nonzero, 1000);  // the points did reach the blocks
        // Integer points: the voxels themselves, aprons included.
        for (int z = r.index_min.z - 1; z <= r.index_max.z + 1; ++z)
            for (int y = r.index_min.y - 1; y <= r.index_max.y + 1; ++y)
                for (int x = r.index_min.x - 1; x <= r.index_max.x + 1; ++x) {
                    const Vec3 p(x, y, z);
                    ASSERT_EQ(grid.density(p), expected.density(p)) << x << " " << y << " " << z;
                }
        // The brick DDA sees the same bricks with the same bounds.
        std::vector<BrickSpan> a, b;
        for (int i = 0; i < 2000; ++i) {
            const Vec3 o = lo + extent * Vec3(rng.next_float(), rng.next_float(), rng.next_float());
            const Vec3 d = glm::normalize(
                Vec3(rng.next_float(), rng.next_float(), rng.next_float()) - Vec3(0.5f));
            a.clear();
            b.clear();
            grid.bricks_along(o, d, 0.0f, 200.0f, a);
            expected.bricks_along(o, d, 0.0f, 200.0f, b);
            ASSERT_EQ(a.size(), b.size());
            for (size_t k = 0; k < a.size(); ++k) {
                EXPECT_EQ(a[k].t0, b[k].t0);
                EXPECT_EQ(a[k].t1, b[k].t1);
                EXPECT_EQ(a[k].density_max, b[k].density_max);
                EXPECT_EQ(a[k].density_min, b[k].density_min);
            }
        }
    }
}

// DensityGrid::axis_split + density_split (the light cache's per-axis lookups) against
// density() at the same point: bit-identical, at random points and, with the interpolation
// skipped along axes whose fraction is 0 (density_split<Flat>), at points on voxels along those
// axes (integer coordinates there), inside, on the aprons and outside the stored region.
TEST(DensityGridBuild, SplitLookupsEqualDensityBitForBit) {
    const RandomBlocks r = random_blocks(31, 40, IVec3(3, 5, 1));
    const DensityGridBuild built = DensityGridBuilder::build(r.index_min, r.index_max, r.blocks);
    ASSERT_TRUE(built.grid);
    const DensityGrid& grid = *built.grid;
    const auto split = [&](const Vec3& p) {
        return std::array<DensityGrid::AxisSplit, 3>{
            grid.axis_split(0, p.x), grid.axis_split(1, p.y), grid.axis_split(2, p.z)};
    };
    Pcg32 rng(41, 2);
    const Vec3 lo = grid.lower() - Vec3(3.0f), extent = grid.upper() - grid.lower() + 6.0f;
    int nonzero = 0;
    for (int i = 0; i < 100000; ++i) {
        Vec3 p = lo + extent * Vec3(rng.next_float(), rng.next_float(), rng.next_float());
        const auto s = split(p);
        ASSERT_EQ(grid.density_split(s[0], s[1], s[2]), grid.density(p));
        // The same point moved onto voxels along a (fraction 0 there), then along all axes.
        for (int a = 0; a < 3; ++a) {
            Vec3 q = p;
            q[a] = std::floor(q[a]);
            const auto t = split(q);
            const float expected = grid.density(q);
            nonzero += expected > 0.0f;
            if (a == 0)
                ASSERT_EQ(grid.density_split<1>(t[0], t[1], t[2]), expected);
            else if (a == 1)
                ASSERT_EQ(grid.density_split<2>(t[0], t[1], t[2]), expected);
            else
                ASSERT_EQ(grid.density_split<4>(t[0], t[1], t[2]), expected);
        }
        p = glm::floor(p);
        const auto v = split(p);
        ASSERT_EQ(grid.density_split<7>(v[0], v[1], v[2]), grid.density(p));
    }
    EXPECT_GT(nonzero, 3000);  // the points did reach the blocks
}

TEST(DensityGridBuild, FirstInvalidActiveVoxelIsReported) {
    RandomBlocks r = random_blocks(5, 6, IVec3(1, 2, 3));
    // Make an active voxel of block 3 negative and later ones (block 4, and block 3 at a higher
    // offset) NaN: block order, then offset order, decides which is reported.
    auto activate = [&](int b, int n, float value) {
        r.blocks[b].active[n / 64] |= uint64_t(1) << (n % 64);
        r.values[b][n] = value;
    };
    activate(4, 10, std::nanf(""));
    activate(3, 300, std::nanf(""));
    activate(3, 77, -0.5f);
    const DensityGridBuild built = DensityGridBuilder::build(
        r.index_min - IVec3(8), r.index_max + IVec3(8), r.blocks);  // the box is a bound only
    ASSERT_TRUE(built.has_invalid);
    EXPECT_FALSE(built.grid);
    EXPECT_EQ(built.invalid.index, r.blocks[3].origin + IVec3(77 >> 6, (77 >> 3) & 7, 77 & 7));
    EXPECT_EQ(built.invalid.value, -0.5f);

    RandomBlocks inf = random_blocks(6, 3, IVec3(0));
    inf.blocks[1].active[0] |= 1;
    inf.values[1][0] = std::numeric_limits<float>::infinity();
    const DensityGridBuild built_inf =
        DensityGridBuilder::build(inf.index_min - IVec3(8), inf.index_max, inf.blocks);
    ASSERT_TRUE(built_inf.has_invalid);
    EXPECT_EQ(built_inf.invalid.index, inf.blocks[1].origin);
}

TEST(DensityGridBuild, ActiveZerosAllocateNothing) {
    std::vector<float> zeros(VoxelBlock::kVoxels, 0.0f);
    VoxelBlock block;
    block.origin = IVec3(16, -8, 0);
    block.values = zeros.data();
    block.active.fill(~uint64_t(0));
    const DensityGridBuild built =
        DensityGridBuilder::build(block.origin, block.origin + IVec3(7), {block});
    ASSERT_FALSE(built.has_invalid);
    EXPECT_TRUE(built.grid->empty());
    EXPECT_EQ(built.grid->density(Vec3(20.0f, -4.0f, 4.0f)), 0.0f);
    std::vector<BrickSpan> spans;
    built.grid->bricks_along(Vec3(0.0f, -4.0f, 4.0f), Vec3(1, 0, 0), 0.0f, 100.0f, spans);
    EXPECT_TRUE(spans.empty());
}

TEST(DensityGridBuild, ActiveTilesLoadLikeTheirVoxels) {
    // A 160³ block whose lower 128³ octant is one value: pruned, OpenVDB stores that octant as a
    // single active tile of an internal node (and the rest as leaves); the reader cuts tiles into
    // 8³ blocks. The pruned file must load exactly like the same voxels stored as leaves.
    DenseVoxels v;
    v.origin = IVec3(-128, 0, -128);  // node-aligned, so the constant octant fills whole nodes
    v.dims = IVec3(160);
    v.values.resize(static_cast<size_t>(160) * 160 * 160);
    Pcg32 rng(11, 2);
    size_t i = 0;
    for (int z = 0; z < 160; ++z)
        for (int y = 0; y < 160; ++y)
            for (int x = 0; x < 160; ++x, ++i)
                v.values[i] = (x < 128 && y < 128 && z < 128) ? 0.5f : rng.next_float();
    const std::string leaves = test::temp_grid_path("tile_leaves");
    const std::string tiles = test::temp_grid_path("tile_pruned");
    write_fog_volume(leaves, "density", v, 1.0, Vec3(0.0f), false);
    write_fog_volume(tiles, "density", v, 1.0, Vec3(0.0f), true);
    const LoadedGrid a = load_density_grid(leaves, "", "leaves");
    const LoadedGrid b = load_density_grid(tiles, "", "tiles");
    EXPECT_EQ(a.active_voxels, b.active_voxels);
    EXPECT_EQ(a.active_tiles, 0u);
    EXPECT_GT(b.active_tiles, 0u);  // the tile path was taken
    ASSERT_EQ(a.grid->allocated_bricks(), b.grid->allocated_bricks());
    EXPECT_EQ(a.grid->max_density(), b.grid->max_density());
    EXPECT_EQ(a.grid->lower(), b.grid->lower());
    for (int k = 0; k < 200000; ++k) {
        const Vec3 p = Vec3(v.origin) - Vec3(2.0f) +
                       164.0f * Vec3(rng.next_float(), rng.next_float(), rng.next_float());
        ASSERT_EQ(a.grid->density(p), b.grid->density(p)) << p.x << " " << p.y << " " << p.z;
    }
    EXPECT_EQ(b.grid->density(Vec3(-60.0f, 60.0f, -60.0f)), 0.5f);
}

}  // namespace
}  // namespace kasumi
