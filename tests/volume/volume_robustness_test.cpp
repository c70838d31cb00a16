// Hostile settings the volume stage must survive with finite work and correct answers: a march
// step of 1e-30 m, a grid whose density scale makes one brick's majorant depth astronomically
// large, and .vdb files whose header is cut short or lies about its lengths.
#include "core/error.h"
#include "vdb_test_grids.h"
#include "volume/grid/vdb_header.h"
#include "volume/in_scattering.h"
#include "volume/march_walk.h"
#include "volume/transmittance.h"
#include "volume/volume_path.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>

namespace kasumi {
namespace {

using test::vdb_medium;

// The half-space of in_scattering_test.cpp: a directional light straight down onto a
// homogeneous half-space y < 0, seen from depth d along a horizontal ray:
//   L = sigma_s p(mu) E exp(-sigma_t d) / sigma_t,  mu = 0.
// The march is unbiased for homogeneous media at any step, so lengthening a 1e-30 m step to
// 1/65536 of the way changes only the variance; the int step count overflowed before (0 steps:
// no in-scattering at all).
TEST(MarchBound, TinyStepInHomogeneousMediaIsBoundedAndUnbiased) {
    const float sigma_a = 0.05f, sigma_s = 0.1f, depth = 1.0f, e_lux = 1000.0f;
    const HenyeyGreenstein hg{0.3f};
    const MediumSet media(
        {Medium{"sea", HomogeneousMedium{Bounds3{Vec3(-1e6f), Vec3(1e6f, 0.0f, 1e6f)}, Rgb(sigma_a),
                                         Rgb(sigma_s), hg}}});
    const std::vector<Light> lights{Light{"sun", DirectionalLight{Vec3(0, -1, 0), Rgb(e_lux)}}};
    const Ray ray{Vec3(0.0f, -depth, 0.0f), Vec3(1, 0, 0), 0.0f, kInfinity};
    const float sigma_t = sigma_a + sigma_s;
    const double expected = sigma_s * eval(hg, 0.0f) * e_lux * std::exp(-sigma_t * depth) / sigma_t;
    VolumeSettings settings;
    settings.step_m = 1e-30f;
    Pcg32 rng(3u, 5u);
    VolumeCounters counters;
    const int n = 16;
    double sum = 0.0;
    for (int i = 0; i < n; ++i)
        sum +=
            integrate_volume(media, lights, nullptr, ray, settings, true, rng, counters).radiance.g;
    EXPECT_EQ(counters.bounded_marches, static_cast<uint64_t>(n));
    EXPECT_LE(counters.steps, static_cast<uint64_t>(n * kMaxMarchSteps));
    // 65536 stratified nodes per ray over ~90 m of smooth integrand: the relative noise of one
    // ray is far below 1e-4; 0.2% leaves room for the 1e-6 tail cut and float sums.
    EXPECT_NEAR(sum / n, expected, 2e-3 * expected);
}

// The `march` transmittance estimator (and marched single scattering, through the same bound)
// walks a grid node by node: with a 1e-30 m step no node moved t forward and the walk never
// ended.
TEST(MarchBound, TinyStepThroughAGridEnds) {
    const std::string box = test::write_box("robust_box8", 8, 1.0f, 1.0);
    const MediumSet media({vdb_medium(box, {{"density_scale", 0.25}})});
    const Ray ray{Vec3(-5.0f, 3.5f, 3.5f), Vec3(1, 0, 0), 0.0f, kInfinity};
    Pcg32 rng(1u, 2u);
    VolumeCounters counters;
    const Rgb t = estimate_transmittance(media, ray, Estimator::March, 1e-30f, rng, counters);
    EXPECT_EQ(counters.bounded_marches, 1u);
    EXPECT_LE(counters.density_lookups, static_cast<uint64_t>(kMaxMarchSteps) + 16u);
    // tau = 0.25 * 8 (the ramps integrate like a sharp box, vdb_test_grids.h); the trapezoid
    // rule at ~1e-4 voxel is exact to far below 1e-5.
    EXPECT_NEAR(t.r, std::exp(-2.0), 1e-5);
}

/// An 8³ block whose voxels x < 3 hold density 1 and the rest 0: one brick, dense on one side.
std::string half_dense_brick() {
    DenseVoxels v;
    v.dims = IVec3(8);
    v.values.assign(512, 0.0f);
    for (int z = 0; z < 8; ++z)
        for (int y = 0; y < 8; ++y)
            for (int x = 0; x < 3; ++x)
                v.values[static_cast<size_t>(x + 8 * (y + 8 * z))] = 1.0f;
    const std::string path = test::temp_grid_path("robust_half_dense");
    write_fog_volume(path, "density", v, 1.0, Vec3(0.0f));
    return path;
}

// A ray through the empty half of a brick whose other half has density 1e6 or 1e30 per metre:
// the brick's majorant made every tracker take ~mu x length tentative collisions there (8e6 at
// 1e6; at 1e30 the gaps fell below float resolution and t stopped moving). Walked cell by cell
// (cells with eight zero corners have no density anywhere), the empty half costs nothing and is
// exactly clear; through the dense half every estimate is 0 within a bounded walk.
TEST(DenseGrid, HugeDensityScaleEndsAndIsCorrect) {
    const std::string path = half_dense_brick();
    const Ray clear{Vec3(6.5f, 3.5f, -5.0f), Vec3(0, 0, 1), 0.0f, kInfinity};
    const Ray dense{Vec3(1.0f, 3.5f, -5.0f), Vec3(0, 0, 1), 0.0f, kInfinity};
    for (double scale : {1e6, 1e30}) {
        const MediumSet media({vdb_medium(path, {{"density_scale", scale}})});
        for (Estimator e : {Estimator::Delta, Estimator::Ratio, Estimator::ResidualRatio}) {
            Pcg32 rng(7u, 9u);
            VolumeCounters counters;
            for (int i = 0; i < 20; ++i) {
                EXPECT_EQ(estimate_transmittance(media, clear, e, 0.1f, rng, counters), Rgb(1.0f))
                    << estimator_name(e) << " " << scale;
            }
            EXPECT_EQ(counters.density_lookups, 0u) << estimator_name(e) << " " << scale;
            for (int i = 0; i < 20; ++i) {
                EXPECT_EQ(estimate_transmittance(media, dense, e, 0.1f, rng, counters), Rgb(0.0f))
                    << estimator_name(e) << " " << scale;
            }
            // Collisions inside the first dense cell end the walk: a few thousand at most.
            EXPECT_LT(counters.density_lookups, 20u * 3u * 20000u)
                << estimator_name(e) << " " << scale;
            // Free flights (multiple scattering) stop in the dense half, pass the clear one.
            const FreeFlight through = sample_free_flight(media, clear, Rgb(1.0f), rng, counters);
            EXPECT_FALSE(through.scattered) << estimator_name(e) << " " << scale;
            const FreeFlight stopped = sample_free_flight(media, dense, Rgb(1.0f), rng, counters);
            EXPECT_TRUE(stopped.scattered || is_black(stopped.weight))
                << estimator_name(e) << " " << scale;
        }
    }
}

std::string read_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::string write_bytes(const std::string& name, const std::string& bytes) {
    const std::string path = test::temp_grid_path(name);
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
}

std::string header_error(const std::string& path) {
    try {
        check_vdb_header(path, "scene.json: /media/0/file");
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::Input) << e.what();
        return e.what();
    }
    return "";
}

// A .vdb cut inside its header made OpenVDB allocate without bound (std::bad_alloc at 300
// bytes); every cut, and lengths that claim more than the file holds, is now a located error.
TEST(VdbHeader, TruncatedOrLyingHeadersAreInputErrors) {
    const std::string whole = read_bytes(test::write_box("robust_header", 4, 1.0f, 1.0));
    ASSERT_GT(whole.size(), 400u);
    EXPECT_EQ(header_error(write_bytes("robust_whole", whole)), "");
    for (size_t cut : {size_t{0}, size_t{7}, size_t{12}, size_t{30}, size_t{60}, size_t{100},
                       size_t{130}, size_t{300}, whole.size() / 2, whole.size() - 1}) {
        const std::string path = write_bytes("robust_cut", whole.substr(0, cut));
        const std::string m = header_error(path);
        EXPECT_NE(m.find("scene.json: /media/0/file: " + path + ": "), std::string::npos)
            << cut << ": " << m;
        EXPECT_TRUE(m.find("truncated") != std::string::npos ||
                    m.find("not a VDB file") != std::string::npos ||
                    m.find("bytes left in the file") != std::string::npos)
            << cut << ": " << m;
    }
    // The grid count (after magic 8, version 4, library 8, offsets flag 1, UUID 36 and the
    // file's empty metadata count 4: byte 61) claims two billion grids.
    std::string lying = whole;
    ASSERT_EQ(lying.substr(57, 4), std::string(4, '\0'));  // no file-level metadata
    lying.replace(61, 4, std::string("\xff\xff\xff\x7f", 4));
    const std::string m = header_error(write_bytes("robust_lying", lying));
    EXPECT_NE(m.find("the grid count at byte 61 is 2147483647"), std::string::npos) << m;
    // A PNG named .vdb.
    const std::string png =
        header_error(write_bytes("robust_png", std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16)));
    EXPECT_NE(png.find("not a VDB file"), std::string::npos) << png;
}

}  // namespace
}  // namespace kasumi
