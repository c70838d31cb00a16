// The direct .vdb reader (volume/grid/vdb_direct.h) against OpenVDB's own reading of the same files
// (load_density_grid_openvdb: OpenVDB's tree, then DensityGridBuilder), and both against the
// trilinear interpolation of the voxels as written (what OpenVDB's BoxSampler returns on a fog
// volume: inactive voxels and everything outside read 0). Files are written by OpenVDB with
// every compression it offers, inactive voxels holding one, two or many distinct junk values
// (the mask-compression cases 0, 2, 4, 5 and 6 of io/Compression.h; 1 and 3 need a background
// whose negative differs from it, never 0), negative coordinates, and active tiles.
// Deterministic (fixed seeds), so no false failures.
#include "volume/grid/vdb_direct.h"

#include "core/error.h"
#include "core/rng.h"
#include "vdb_test_grids.h"
#include "volume/grid/vdb_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace kasumi {
namespace {

/// Voxels in OpenVDB's leaves (8³ cells aligned to index 0) of five kinds, so that leaves
/// inside the box take every mask-compression case: empty; dense and active; sparse with the
/// inactive voxels all 3.0 (one inactive value); sparse with inactive -1 or 3 (two values, a
/// selection mask); sparse with inactive -1, 3, 7 or NaN (all values stored). Leaves cut by the
/// box also hold inactive background voxels (a background and one or two other values).
DenseVoxels random_voxels(uint64_t seed, IVec3 origin, IVec3 dims) {
    Pcg32 rng(seed, 5);
    DenseVoxels v;
    v.origin = origin;
    v.dims = dims;
    const size_t n = static_cast<size_t>(dims.x) * dims.y * dims.z;
    v.values.assign(n, 0.0f);
    v.inactive.assign(n, 0);
    size_t i = 0;
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x, ++i) {
                const IVec3 leaf = (origin + IVec3(x, y, z)) >> 3;  // floor division by 8
                const uint32_t hash = static_cast<uint32_t>(leaf.x * 73856093 ^ leaf.y * 19349663 ^
                                                            leaf.z * 83492791) +
                                      static_cast<uint32_t>(seed);
                const uint32_t kind = (hash >> 3) % 5;
                const float u = rng.next_float(), value = 0.05f + 2.0f * rng.next_float();
                if (kind == 0)
                    continue;
                if (kind == 1 || u < 0.5f) {
                    // Zeros (written as inactive background) only in the dense leaves, so the
                    // sparse ones hold no background.
                    v.values[i] = kind == 1 && u < 0.1f ? 0.0f : value;
                    continue;
                }
                v.inactive[i] = 1;
                const float junk[4] = {-1.0f, 3.0f, 7.0f, std::nanf("")};
                v.values[i] = kind == 2 ? 3.0f : junk[rng.next_u32() % (kind == 3 ? 2 : 4)];
            }
    return v;
}

float voxel(const DenseVoxels& v, IVec3 c) {
    const IVec3 l = c - v.origin;
    if (glm::any(glm::lessThan(l, IVec3(0))) || glm::any(glm::greaterThanEqual(l, v.dims)))
        return 0.0f;
    const size_t i =
        static_cast<size_t>(l.x) + static_cast<size_t>(v.dims.x) * (l.y + size_t(v.dims.y) * l.z);
    return !v.inactive.empty() && v.inactive[i] ? 0.0f : v.values[i];
}

/// Trilinear interpolation between voxel centres at integer index points.
double trilinear(const DenseVoxels& v, Vec3 p) {
    const Vec3 f = glm::floor(p);
    const IVec3 c(f);
    const glm::dvec3 t = glm::dvec3(p) - glm::dvec3(f);
    double sum = 0.0;
    for (int k = 0; k < 8; ++k) {
        const IVec3 o(k & 1, (k >> 1) & 1, k >> 2);
        const double w =
            (o.x ? t.x : 1.0 - t.x) * (o.y ? t.y : 1.0 - t.y) * (o.z ? t.z : 1.0 - t.z);
        sum += w * voxel(v, c + o);
    }
    return sum;
}

/// The two readings agree bit for bit: counts, transform, bricks, bounds, every density and
/// the brick DDA along random rays.
void expect_same(const LoadedGrid& a, const LoadedGrid& b, const DenseVoxels* written) {
    EXPECT_EQ(a.grid_name, b.grid_name);
    EXPECT_EQ(a.active_voxels, b.active_voxels);
    EXPECT_EQ(a.active_tiles, b.active_tiles);
    EXPECT_EQ(a.index_to_world, b.index_to_world);
    ASSERT_TRUE(a.grid && b.grid);
    const DensityGrid& g = *a.grid;
    const DensityGrid& h = *b.grid;
    ASSERT_EQ(g.allocated_bricks(), h.allocated_bricks());
    ASSERT_EQ(g.total_bricks(), h.total_bricks());
    EXPECT_EQ(g.max_density(), h.max_density());
    EXPECT_EQ(g.lower(), h.lower());
    EXPECT_EQ(g.upper(), h.upper());
    if (g.empty())
        return;
    Pcg32 rng(17, 3);
    const Vec3 lo = g.lower() - Vec3(2.0f), extent = g.upper() - g.lower() + Vec3(4.0f);
    int nonzero = 0;
    for (int i = 0; i < 100000; ++i) {
        const Vec3 p = lo + extent * Vec3(rng.next_float(), rng.next_float(), rng.next_float());
        const float d = g.density(p);
        ASSERT_EQ(d, h.density(p)) << p.x << " " << p.y << " " << p.z;
        if (written) {  // against the voxels as written, in double: float rounding only
            ASSERT_NEAR(d, trilinear(*written, p), 1e-6 * g.max_density())
                << p.x << " " << p.y << " " << p.z;
        }
        nonzero += d > 0.0f;
    }
    EXPECT_GT(nonzero, 1000);
    std::vector<BrickSpan> sa, sb;
    for (int i = 0; i < 1000; ++i) {
        const Vec3 o = lo + extent * Vec3(rng.next_float(), rng.next_float(), rng.next_float());
        const Vec3 d =
            glm::normalize(Vec3(rng.next_float(), rng.next_float(), rng.next_float()) - Vec3(0.5f));
        sa.clear();
        sb.clear();
        g.bricks_along(o, d, 0.0f, 300.0f, sa);
        h.bricks_along(o, d, 0.0f, 300.0f, sb);
        ASSERT_EQ(sa.size(), sb.size());
        for (size_t k = 0; k < sa.size(); ++k) {
            EXPECT_EQ(sa[k].t0, sb[k].t0);
            EXPECT_EQ(sa[k].t1, sb[k].t1);
            EXPECT_EQ(sa[k].density_max, sb[k].density_max);
            EXPECT_EQ(sa[k].density_min, sb[k].density_min);
        }
    }
}

TEST(VdbDirectRead, EqualsOpenVdbForEveryCompression) {
    // -1: OpenVDB's default (blosc + active mask); 0 none; 1 zip; 2 active mask only; 3 zip +
    // mask; 4 blosc; 6 blosc + mask.
    for (int compression : {-1, 0, 1, 2, 3, 4, 6}) {
        DenseVoxels v = random_voxels(40 + compression, IVec3(-37, -90, 5), IVec3(45, 30, 52));
        v.compression = compression;
        const std::string path = test::temp_grid_path("direct_" + std::to_string(compression + 1));
        write_fog_volume(path, "density", v, 0.5, Vec3(-3.0f, 1.0f, 2.5f));
        std::string why;
        const std::optional<LoadedGrid> direct = read_density_grid_direct(path, "", &why);
        ASSERT_TRUE(direct) << "compression " << compression << ": declined: " << why;
        const LoadedGrid openvdb = load_density_grid_openvdb(path, "", "test");
        SCOPED_TRACE("compression " + std::to_string(compression));
        EXPECT_GT(direct->active_voxels, 10000u);
        expect_same(*direct, openvdb, &v);
        EXPECT_EQ(direct->index_to_world[0][0], 0.5);
        EXPECT_EQ(direct->index_to_world[3][0], -3.0);
    }
}

TEST(VdbDirectRead, ActiveTilesAndNegativeCoordinates) {
    // A 160³ block whose lower 128³ octant is one value, pruned into an active tile of an
    // internal node (the rest leaves), below index 0 in x and z.
    DenseVoxels v;
    v.origin = IVec3(-128, 0, -128);
    v.dims = IVec3(160);
    v.values.resize(static_cast<size_t>(160) * 160 * 160);
    Pcg32 rng(12, 2);
    size_t i = 0;
    for (int z = 0; z < 160; ++z)
        for (int y = 0; y < 160; ++y)
            for (int x = 0; x < 160; ++x, ++i)
                v.values[i] = (x < 128 && y < 128 && z < 128) ? 0.5f : rng.next_float();
    const std::string path = test::temp_grid_path("direct_tiles");
    write_fog_volume(path, "density", v, 1.0, Vec3(0.0f), true);
    const std::optional<LoadedGrid> direct = read_density_grid_direct(path, "");
    ASSERT_TRUE(direct);
    EXPECT_GT(direct->active_tiles, 0u);
    expect_same(*direct, load_density_grid_openvdb(path, "", "test"), &v);
    EXPECT_EQ(direct->grid->density(Vec3(-60.0f, 60.0f, -60.0f)), 0.5f);
}

TEST(VdbDirectRead, EmptyGridAndNamedGrid) {
    const std::string path = test::write_box("direct_empty", 4, 0.0f, 1.0, Vec3(0.0f), "smoke");
    const std::optional<LoadedGrid> direct = read_density_grid_direct(path, "");
    ASSERT_TRUE(direct);  // no "density": the first float grid, as OpenVDB's path picks
    EXPECT_EQ(direct->grid_name, "smoke");
    EXPECT_EQ(direct->active_voxels, 0u);
    EXPECT_TRUE(direct->grid->empty());
    expect_same(*direct, load_density_grid_openvdb(path, "", "test"), nullptr);
    ASSERT_TRUE(read_density_grid_direct(path, "smoke"));
    EXPECT_FALSE(read_density_grid_direct(path, "density"));
}

TEST(VdbDirectRead, DeclinesBrokenFilesAndLeavesTheErrorToOpenVdb) {
    const DenseVoxels v = random_voxels(7, IVec3(-20), IVec3(40));
    const std::string path = test::temp_grid_path("direct_whole");
    write_fog_volume(path, "density", v, 1.0, Vec3(0.0f));
    std::ifstream in(path, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_GT(bytes.size(), 2000u);
    const std::string cut = test::temp_grid_path("direct_cut");
    // Cut inside the header, the grid's metadata, the topology and the last leaf's values.
    for (size_t at : {size_t(20), size_t(300), bytes.size() / 3, bytes.size() - 5}) {
        std::ofstream(cut, std::ios::binary | std::ios::trunc).write(bytes.data(), at);
        std::string why;
        EXPECT_FALSE(read_density_grid_direct(cut, "", &why)) << at;
        EXPECT_FALSE(why.empty());
        // load_density_grid falls back to OpenVDB, which reports the file (exit code 3).
        try {
            load_density_grid(cut, "", "scene.json: /media/0/file");
            ADD_FAILURE() << "a file cut at byte " << at << " loaded";
        } catch (const Error& e) {
            EXPECT_EQ(e.kind(), ErrorKind::Input) << e.what();
            EXPECT_NE(std::string(e.what()).find("scene.json: /media/0/file"), std::string::npos);
        }
    }
    // A leaf's blosc chunk with a byte flipped inside its compressed data is declined or read
    // exactly as OpenVDB reads it, never something else.
    std::string flipped = bytes;
    flipped[bytes.size() - 40] = static_cast<char>(flipped[bytes.size() - 40] ^ 0x5A);
    std::ofstream(cut, std::ios::binary | std::ios::trunc).write(flipped.data(), flipped.size());
    if (const std::optional<LoadedGrid> g = read_density_grid_direct(cut, "")) {
        try {
            expect_same(*g, load_density_grid_openvdb(cut, "", "test"), nullptr);
        } catch (const Error&) {
            ADD_FAILURE() << "OpenVDB refused a file the direct reader read";
        }
    }
    EXPECT_FALSE(read_density_grid_direct(test::temp_grid_path("no_such_file"), ""));
}

TEST(VdbDirectRead, AFileCutWhileItIsReadIsAnInputError) {
    // Another process rewriting the .vdb cuts it while it is mapped: the pages past its new end
    // raise SIGBUS, which killed the renderer. The read hook cuts the file to nothing after the
    // topology is read (the sequential leaf walk faults next) and before the leaves' values are
    // decompressed (the parallel workers fault), for each compression.
    for (int compression : {0, 2, -1}) {
        for (const char* stage : {"topology", "values"}) {
            DenseVoxels v = random_voxels(3, IVec3(-20), IVec3(40));
            v.compression = compression;
            const std::string path = test::temp_grid_path("direct_cut_while_read");
            write_fog_volume(path, "density", v, 1.0, Vec3(0.0f));
            ASSERT_TRUE(read_density_grid_direct(path, ""));
            int cuts = 0;
            set_direct_read_hook([&](const std::string& read, const char* at) {
                if (read == path && std::string(at) == stage) {
                    std::filesystem::resize_file(path, 0);
                    ++cuts;
                }
            });
            const uintmax_t size = std::filesystem::file_size(path);
            try {
                read_density_grid_direct(path, "", nullptr, "scene.json: /media/0/file");
                ADD_FAILURE() << stage << ": a file cut while it was read loaded";
            } catch (const Error& e) {
                EXPECT_EQ(e.kind(), ErrorKind::Input);
                EXPECT_EQ(std::string(e.what()),
                          "scene.json: /media/0/file: " + path + ": the file was cut from " +
                              std::to_string(size) +
                              " to 0 bytes while it was read (is another process writing it?)")
                    << stage << ", compression " << compression;
            }
            set_direct_read_hook(nullptr);
            EXPECT_EQ(cuts, 1) << stage;
        }
    }
}

}  // namespace
}  // namespace kasumi
