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
#include "tests/volume/vdb_test_grids.h"

#include <gtest/gtest.h>

#include <cmath>

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

TEST(LightCache, OutsideTheLatticeAsksTheCallerToWalk) {
    const std::string path = test::write_box("light_cache_small", 8, 1.0f, 1.0);
    const Medium medium = test::vdb_medium(path, {{"density_scale", 0.1}});
    const LightTransmittanceCache cache(std::get<VdbMedium>(medium.model), Vec3(0, 1, 0));
    EXPECT_FALSE(cache.transmittance(Vec3(100.0f, 0.0f, 0.0f)).has_value());
}

}  // namespace
}  // namespace kasumi
