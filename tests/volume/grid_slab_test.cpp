// Multiple scattering through a VDB grid against the published DISORT answers (Stamnes et al.
// 1988, DISOTEST.f; the cases and values of slab_benchmark_test.cpp): the slab is a constant
// grid read back through the scene loader (vdb_test_grids.h), so free flights, collisions and
// phase sampling go through the grid's brick walk, its density look-ups, its coefficients per
// unit density (albedo and density_scale) and its phase function.
//
// Geometry: 8³ voxels of density 1, voxel 1/8 m, stretched by the medium's transform to
// 2e9 m across (x, z) and 1 m thick (y in [-1, 0]). Trilinear interpolation ramps the density
// to 0 over the outer half voxel top and bottom; the layer stays horizontally uniform, so its
// fluxes depend only on the vertical optical depth (Chandrasekhar 1960, ch. I), which is
// sigma_t * 1 m exactly (the ramps integrate like a sharp box: vdb_test_grids.h). Laterally a
// path would have to fly 1e9 m to leave: with the slabs' extinction of at least 0.03125/m
// below the ramps, the bound of slab_benchmark_test.cpp (flights / (sigma (W - 2/mu0)))
// is below 1e-5 for every case here (asserted).
//
// Statistics as there: 4 standard errors below 0.5% of the answer (asserted; 1d needs 3.3x the
// homogeneous slab's paths: the tracker's null collisions in the ramps spread its weights),
// then within 1%
// of the published value and within 4 standard errors + 0.1% (two-sided false-failure rate
// 6.3e-5 per check, 4 checks). A 2% change of the grid's albedo (1d), density scale (1b) or
// Henyey-Greenstein g (3b) moves these fluxes by more than 1% (measured by the mutation
// harness, docs/testing.md).
#include "tests/sample_mean.h"
#include "tests/volume/vdb_test_grids.h"
#include "volume/guiding/guiding_field.h"
#include "volume/volume_path.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <optional>
#include <vector>

namespace kasumi {
namespace {

struct DisortCase {
    const char* name;
    Json phase;
    double tau, omega, mu0;
    double published;  ///< plane albedo r(mu0) = FLUP / (mu0 FBEAM), or t(mu0) = RFLDN / (...)
    bool reflection;
    int paths;
};

constexpr double kHalfWidthM = 1e9;

/// The slab as a `vdb` medium: sigma_a, sigma_s per unit density (density 1 inside).
MediumSet grid_slab(const DisortCase& c) {
    constexpr int n = 8;
    constexpr double voxel = 1.0 / n;
    // Index i's centre at offset + i voxel; the box spans indices -0.5 .. n - 0.5.
    const std::string path = test::write_box(
        "slab", n, 1.0f, voxel, Vec3(-0.5 + voxel / 2, -1.0 + voxel / 2, -0.5 + voxel / 2));
    Json keys;
    keys["sigma_a"] = c.tau * (1.0 - c.omega);
    keys["sigma_s"] = c.tau * c.omega;
    keys["phase"] = c.phase;
    keys["transform"] = Json{{"scale", {2.0 * kHalfWidthM, 1.0, 2.0 * kHalfWidthM}}};
    return MediumSet({test::vdb_medium(path, keys)});
}

/// Paths that leave the slab upward see a uniform sky of radiance 1; downward, black.
class UpperSky final : public PathEnvironment {
  public:
    float surface_distance(const Ray&) const override { return kInfinity; }
    Rgb radiance(const Ray& ray, Pcg32&) const override {
        return Rgb(ray.direction.y > 0.0f ? 1.0f : 0.0f);
    }
};

/// How the paths are traced: as rendered by default, or with volume path guiding (a field
/// trained on the slab's own paths) and decomposition-tracked free flights both on.
enum class Paths { Default, GuidedDecomposition };

/// r(mu0) or t(mu0) by reciprocity from one camera ray along (or against) the beam under the
/// upper sky (slab_benchmark_test.cpp, sky_estimate).
void check(const DisortCase& c, Paths paths = Paths::Default) {
    const MediumSet slab = grid_slab(c);
    const UpperSky sky;
    const float mu0 = static_cast<float>(c.mu0);
    const Vec3 beam(std::sqrt(1.0f - mu0 * mu0), -mu0, 0.0f);
    const Ray ray = c.reflection
                        ? Ray{beam / beam.y, beam, 0.0f, kInfinity}
                        : Ray{Vec3(0.0f, -1.0f, 0.0f) - beam / beam.y, -beam, 0.0f, kInfinity};
    VolumeSettings settings;
    settings.integrator = VolumeIntegrator::Multiple;
    settings.estimator = Estimator::ResidualRatio;
    settings.max_depth = 1000000;  // Russian roulette ends the paths
    // Guiding: the field trained on 20000 paths of the same ray (other streams), as the
    // renderer's training passes would, with the default leaf size and uniform share. The mix
    // is 0.1, not the default 0.5: the slab's records span 2e9 m across and 1 m deep, so the
    // field splits across (where nothing changes) and its guide cannot follow the depth; at
    // mix 0.5 the albedo-1 cases (3b) need ~18x the paths for the same standard error.
    GuidingField field;
    std::optional<PathGuiding> guiding;
    if (paths == Paths::GuidedDecomposition) {
        settings.free_flight = FreeFlightSampling::Decomposition;
        const GuidingSettings defaults;
        std::vector<GuidingRecord> records;
        constexpr float kMix = 0.1f;
        const PathGuiding training{nullptr, kMix, &records};
        VolumeCounters counters;
        for (int i = 0; i < 20000; ++i) {
            Pcg32 rng(91, static_cast<uint64_t>(i));
            integrate_media(slab, {}, nullptr, &sky, ray, settings, true, rng, counters, true,
                            &training);
        }
        field = GuidingField(records, defaults.leaf_records, defaults.uniform);
        guiding = PathGuiding{&field, kMix, nullptr};
    }
    SampleMean samples;
    VolumeCounters counters;
    for (int i = 0; i < c.paths; ++i) {
        Pcg32 rng(37, static_cast<uint64_t>(i));
        samples.add(integrate_media(slab, {}, nullptr, &sky, ray, settings, true, rng, counters,
                                    true, guiding ? &*guiding : nullptr)
                        .radiance.g);
    }
    const MeanAndError m = samples.result();
    const double leak = static_cast<double>(counters.free_flights) / c.paths /
                        (c.tau * (kHalfWidthM - 2.0 / c.mu0));
    std::printf("%-40s %.5f +- %.5f (published %.5f, %+.2f%%)%s, %.1f lookups/path\n", c.name,
                m.mean, m.stderr_, c.published, 100.0 * (m.mean / c.published - 1.0),
                paths == Paths::GuidedDecomposition ? " guided, decomposition" : "",
                static_cast<double>(counters.density_lookups) / c.paths);
    EXPECT_LT(4.0 * m.stderr_, 0.005 * c.published) << c.name << ": too few paths";
    EXPECT_NEAR(m.mean, c.published, 0.01 * c.published) << c.name;
    EXPECT_NEAR(m.mean, c.published, 4.0 * m.stderr_ + 1e-3 * c.published) << c.name;
    EXPECT_LT(leak, 1e-5) << c.name;
}

// DISOTEST.f problem 1b: isotropic, tau 0.03125, omega 1, UMU0 0.1, FBEAM pi / UMU0.
TEST(DisortGridSlab, Problem1bThinPlaneAlbedo) {
    check({"1b grid, plane albedo", Json{{"model", "isotropic"}}, 0.03125, 1.0, 0.1,
           4.22922e-01 / kPiD, true, 5200000});
}

// Problem 1d: isotropic, tau 32, omega 0.2, UMU0 0.1 (albedo < 1: absorption at collisions).
TEST(DisortGridSlab, Problem1dAbsorbingPlaneAlbedo) {
    check({"1d grid, plane albedo", Json{{"model", "isotropic"}}, 32.0, 0.2, 0.1,
           2.59686e-01 / kPiD, true, 3600000});
}

// Problem 3b: Henyey-Greenstein g 0.75, tau 8, omega 1, UMU0 1, FBEAM pi.
TEST(DisortGridSlab, Problem3bHenyeyGreensteinPlaneAlbedo) {
    check({"3b grid, plane albedo", Json{{"model", "hg"}, {"g", 0.75}}, 8.0, 1.0, 1.0,
           1.59096e+00 / kPiD, true, 850000});
}

TEST(DisortGridSlab, Problem3bHenyeyGreensteinDiffuseTransmission) {
    check({"3b grid, diffuse transmission", Json{{"model", "hg"}, {"g", 0.75}}, 8.0, 1.0, 1.0,
           1.54958e+00 / kPiD, false, 850000});
}

// The same four cases with volume path guiding and decomposition tracking on (issue #19): both
// must leave the published answers where they are. The guided 3b cases take 1.2e6 paths: at
// 850000 their 4 standard errors were 0.49% and 0.51% of the answer, at the 0.5% bound.
TEST(DisortGridSlab, Problem1bGuidedDecomposition) {
    check({"1b grid, plane albedo", Json{{"model", "isotropic"}}, 0.03125, 1.0, 0.1,
           4.22922e-01 / kPiD, true, 5200000},
          Paths::GuidedDecomposition);
}

TEST(DisortGridSlab, Problem1dGuidedDecomposition) {
    check({"1d grid, plane albedo", Json{{"model", "isotropic"}}, 32.0, 0.2, 0.1,
           2.59686e-01 / kPiD, true, 3600000},
          Paths::GuidedDecomposition);
}

TEST(DisortGridSlab, Problem3bGuidedDecompositionPlaneAlbedo) {
    check({"3b grid, plane albedo", Json{{"model", "hg"}, {"g", 0.75}}, 8.0, 1.0, 1.0,
           1.59096e+00 / kPiD, true, 1200000},
          Paths::GuidedDecomposition);
}

TEST(DisortGridSlab, Problem3bGuidedDecompositionDiffuseTransmission) {
    check({"3b grid, diffuse transmission", Json{{"model", "hg"}, {"g", 0.75}}, 8.0, 1.0, 1.0,
           1.54958e+00 / kPiD, false, 1200000},
          Paths::GuidedDecomposition);
}

}  // namespace
}  // namespace kasumi
