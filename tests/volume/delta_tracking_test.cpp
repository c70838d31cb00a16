// Delta tracking's transmittance against Beer-Lambert, exp(-tau), through a homogeneous box
// and through a constant VDB grid (its brick walk and majorants), at optical depths 1 and 2.
// Delta tracking returns 0 or 1 per estimate, so its mean over n estimates has the binomial
// standard error sqrt(T (1 - T) / n); with n = 1e6 the bound 4.5 s.e. (two-sided
// false-failure rate 6.8e-6 per check, 4 checks) is asserted below a third of the shift a 2%
// error of the extinction the tracker sees makes (tau 0.02 T, e.g. a tracker that takes 2% of
// the real collisions for null ones).
#include "tests/volume/vdb_test_grids.h"
#include "volume/transmittance.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace kasumi {
namespace {

constexpr int kEstimates = 1000000;

void expect_beer_lambert(const MediumSet& media, const Ray& ray, double tau, const char* what) {
    VolumeCounters counters;
    double sum = 0.0;
    for (int i = 0; i < kEstimates; ++i) {
        Pcg32 rng(41, static_cast<uint64_t>(i));
        sum += estimate_transmittance(media, ray, Estimator::Delta, 0.0f, rng, counters).g;
    }
    const double mean = sum / kEstimates;
    const double exact = std::exp(-tau);
    const double se = std::sqrt(exact * (1.0 - exact) / kEstimates);
    std::printf("%-12s tau %.2f: T %.5f, exp(-tau) %.5f (%+.2f%%), 4.5 s.e. %.5f\n", what, tau,
                mean, exact, 100.0 * (mean / exact - 1.0), 4.5 * se);
    EXPECT_LT(4.5 * se, 0.02 * tau * exact / 3.0) << what << ": too few estimates";
    EXPECT_NEAR(mean, exact, 4.5 * se) << what << " tau " << tau;
}

TEST(DeltaTracking, HomogeneousBoxFollowsBeerLambert) {
    for (const double tau : {1.0, 2.0}) {
        const Bounds3 box{Vec3(-1.0f), Vec3(1.0f)};
        const float sigma_t = static_cast<float>(tau / 2.0);  // 2 m across
        const MediumSet media({Medium{
            "box", HomogeneousMedium{box, Rgb(0.5f * sigma_t), Rgb(0.5f * sigma_t), Isotropic{}}}});
        expect_beer_lambert(media, Ray{Vec3(0.0f, 0.0f, -3.0f), Vec3(0, 0, 1), 0.0f, kInfinity},
                            tau, "homogeneous");
    }
}

TEST(DeltaTracking, VdbGridFollowsBeerLambert) {
    // 16³ voxels of density 1, voxel 0.125 m: across two opposite faces the optical depth is
    // sigma_t 16 × 0.125 m = 2 sigma_t (vdb_test_grids.h: the ramps integrate like a sharp box).
    const std::string path = test::write_box("delta_box", 16, 1.0f, 0.125, Vec3(-0.9375f));
    for (const double tau : {1.0, 2.0}) {
        Json keys;
        keys["sigma_a"] = tau / 4.0;
        keys["sigma_s"] = tau / 4.0;
        const MediumSet media({test::vdb_medium(path, keys)});
        expect_beer_lambert(media, Ray{Vec3(0.0f, 0.0f, -3.0f), Vec3(0, 0, 1), 0.0f, kInfinity},
                            tau, "vdb grid");
    }
}

}  // namespace
}  // namespace kasumi
