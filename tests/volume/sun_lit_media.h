#pragma once
// The sunlit media shared by the tests of the tracking in-scattering estimators
// (tracked_in_scattering_test, nee_roulette_test): a homogeneous box with a closed form, and a
// heterogeneous grid with a finely marched reference.
#include "tests/sample_mean.h"
#include "vdb_test_grids.h"
#include "volume/volume_path.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace kasumi::test {

/// A box [-1, 1]³ of sigma_s = 2, sigma_a = 0.5 per metre with phase `phase`, lit from +y by a
/// sun of irradiance 1; the camera ray runs along +x at height y0 = 0.2 and crosses it over 2 m.
/// Every point of the ray is 1 - y0 below the top face and sees the sun at scattering cosine
/// mu = 0, so single scattering is
///   L = sigma_s p(0) exp(-sigma_t (1 - y0)) (1 - exp(-2 sigma_t)) / sigma_t,
/// and the ray's transmittance T = exp(-2 sigma_t).
struct SunLitBox {
    static constexpr float kSigmaS = 2.0f, kSigmaA = 0.5f, kSigmaT = kSigmaS + kSigmaA;
    static constexpr float kY0 = 0.2f;

    explicit SunLitBox(PhaseFunction phase)
        : media({Medium{"box", HomogeneousMedium{Bounds3{Vec3(-1.0f), Vec3(1.0f)}, Rgb(kSigmaA),
                                                 Rgb(kSigmaS), phase}}}) {}

    /// L above, given the phase function's value at mu = 0 (1/sr).
    static double single_scattering(double phase_at_mu_0) {
        return kSigmaS * phase_at_mu_0 * std::exp(-double(kSigmaT) * (1.0 - kY0)) *
               (1.0 - std::exp(-2.0 * kSigmaT)) / kSigmaT;
    }
    static double transmittance() { return std::exp(-2.0 * kSigmaT); }

    MediumSet media;
    std::vector<Light> sun{Light{"sun", DirectionalLight{Vec3(0, -1, 0), Rgb(1.0f)}}};
    Ray ray{Vec3(-3.0f, kY0, 0.1f), Vec3(1, 0, 0), 0.0f, kInfinity};
};

/// A 24³ grid of smoothly varying density (0.1 .. 1.9, voxels 0.1 m, written to the temporary
/// grid `grid_name`, density scale 2), albedo 0.8, HG phase g, lit by an oblique sun of
/// irradiance 3, and a camera ray across it.
struct SunLitGrid {
    SunLitGrid(const std::string& grid_name, float g)
        : media({vdb_medium(
              write_grid(grid_name),
              {{"density_scale", 2.0}, {"albedo", 0.8}, {"phase", {{"model", "hg"}, {"g", g}}}})}) {
    }

    /// Marched single scattering at 1/8 voxel (O(h²) bias, below the statistics of the tests),
    /// averaged over 64 jitter offsets of stream `seed`: the reference for the trackers.
    MeanAndError march_reference(uint64_t seed) const {
        VolumeSettings march;
        march.estimator = Estimator::March;
        march.step_voxels = 0.125f;
        return mean_over_streams(64, seed, [&](Pcg32& rng) {
            VolumeCounters counters;
            return integrate_media(media, sun, nullptr, nullptr, ray, march, true, rng, counters)
                .radiance.g;
        });
    }

    /// A tracker's estimate with settings `s` (160000 paths of stream `seed`) agrees with the
    /// march `reference` within 4 standard errors of both (two-sided Gaussian false-failure
    /// rate 6e-5) plus 0.1% for the reference's bias, and has teeth: 4 standard errors are
    /// below `resolution` of the reference.
    void expect_matches(const MeanAndError& reference, const VolumeSettings& s, uint64_t seed,
                        double resolution, const std::string& what) const {
        const MeanAndError l = mean_over_streams(160000, seed, [&](Pcg32& rng) {
            VolumeCounters counters;
            return integrate_media(media, sun, nullptr, nullptr, ray, s, true, rng, counters)
                .radiance.g;
        });
        const double se = std::hypot(l.stderr_, reference.stderr_);
        EXPECT_NEAR(l.mean, reference.mean, 4.0 * se + 1e-3 * reference.mean) << what;
        EXPECT_LT(4.0 * se, resolution * reference.mean) << what;
        std::printf("%s: %.6g +- %.2g, march %.6g +- %.2g\n", what.c_str(), l.mean, l.stderr_,
                    reference.mean, reference.stderr_);
    }

    MediumSet media;
    std::vector<Light> sun{
        Light{"sun", DirectionalLight{glm::normalize(Vec3(-0.3f, -1.0f, 0.4f)), Rgb(3.0f)}}};
    Ray ray{Vec3(-1.0f, 1.1f, 0.9f), glm::normalize(Vec3(1.0f, 0.1f, 0.15f)), 0.0f, kInfinity};

  private:
    static std::string write_grid(const std::string& name) {
        constexpr int n = 24;
        DenseVoxels v;
        v.dims = IVec3(n);
        v.values.resize(static_cast<size_t>(n) * n * n);
        for (int z = 0; z < n; ++z)
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x)
                    v.values[x + n * (y + n * z)] =
                        1.0f + 0.9f * std::sin(0.7f * x) * std::cos(0.45f * y + 0.3f * z);
        const std::string path = temp_grid_path(name);
        write_fog_volume(path, "density", v, 0.1, Vec3(0.0f));
        return path;
    }
};

}  // namespace kasumi::test
