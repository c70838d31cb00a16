// Closed-form checks every GI method must pass (gi_cases() in gi_test_scenes.h lists them):
// - the furnace: a closed box whose every face emits L_e and reflects ρ has radiance
//   L_e / (1 − ρ) everywhere (the Neumann series L_e Σ ρ^k);
// - an emitting square over a facing white square: the receiver's centre has radiance ρ F L_e
//   with F the point-to-square form factor (Howell B-3 over four corner rectangles).
// Each check allows 4 standard errors of the probe's mean plus the case's stated relative
// tolerance; for the unbiased path tracer the false-failure rate per check is about 6e-5 (two-
// sided normal tail beyond 4σ); seeds are fixed, so a run is reproducible.
#include "gi_test_scenes.h"
#include "render/probe.h"
#include "tests/gi/gi_test_scene.h"

#include <gtest/gtest.h>

#include <cmath>

namespace kasumi {
namespace {

class GiClosedFormTest : public ::testing::TestWithParam<GiCase> {};

void expect_radiance(const RadianceProbe& p, double expected, double relative_tolerance,
                     const std::string& what) {
    for (int c = 0; c < 3; ++c) {
        const double bound = 4.0 * p.stderr_[c] + relative_tolerance * expected;
        EXPECT_NEAR(p.radiance[c], expected, bound)
            << what << " channel " << c << " stderr " << p.stderr_[c];
    }
}

TEST_P(GiClosedFormTest, FurnaceBoxHasRadianceLeOverOneMinusRho) {
    const GiCase& c = GetParam();
    for (const double rho : {0.3, 0.7}) {
        const double le = 10.0;
        const auto runtime = gi_runtime_from_text(furnace_scene(c, le, rho));
        const double expected = le / (1.0 - rho);
        // From the centre toward a face centre, an edge and a corner, and from off-centre.
        const Vec3 directions[] = {Vec3(0, 0, -1), Vec3(1, 1, 0), Vec3(-1, -1, 1),
                                   Vec3(0.3, -1, 0.2)};
        for (const Vec3& d : directions) {
            const Vec3 origin = d.y < -0.9f ? Vec3(0.2f, 0.1f, -0.3f) : Vec3(0.0f);
            const RadianceProbe p = probe_radiance(*runtime, origin, glm::normalize(d), c.spp);
            expect_radiance(p, expected, c.relative_tolerance,
                            c.gi + " rho " + std::to_string(rho));
        }
    }
}

/// Howell B-3: differential area to a parallel a × b rectangle at distance h, the normal
/// through one corner.
double point_to_corner_rectangle(double a, double b, double h) {
    const double x = a / h, y = b / h;
    return 1.0 / (2.0 * 3.14159265358979323846) *
           (x / std::sqrt(1 + x * x) * std::atan(y / std::sqrt(1 + x * x)) +
            y / std::sqrt(1 + y * y) * std::atan(x / std::sqrt(1 + y * y)));
}

TEST_P(GiClosedFormTest, FacingSquaresGiveRhoTimesFormFactorTimesLe) {
    const GiCase& c = GetParam();
    const double le = 100.0, rho = 0.8;
    for (const double height : {0.5, 1.0}) {
        const auto runtime = gi_runtime_from_text(facing_squares_scene(c, le, rho, height));
        const double f = 4.0 * point_to_corner_rectangle(0.5, 0.5, height);
        const double expected = rho * f * le;
        // Look at the receiver's centre from the side, between the two squares.
        const Vec3 origin(1.5f, 0.25f * static_cast<float>(height), 0.2f);
        const RadianceProbe p =
            probe_radiance(*runtime, origin, glm::normalize(Vec3(0.0f) - origin), c.spp);
        expect_radiance(p, expected, c.relative_tolerance,
                        c.gi + " height " + std::to_string(height));
    }
}

INSTANTIATE_TEST_SUITE_P(GiMethods, GiClosedFormTest, ::testing::ValuesIn(gi_cases()),
                         [](const ::testing::TestParamInfo<GiCase>& param_info) {
                             return param_info.param.gi;
                         });

}  // namespace
}  // namespace kasumi
