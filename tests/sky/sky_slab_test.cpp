// The sky's reference integrator (sky/sky_reference.h) on a plane-parallel slab: a planet of
// radius 6.36e10 m (10⁴ Earth radii) under a uniform 1 km layer of Rayleigh scatterers over a
// black ground. Over the ~10 km a grazing sun's light travels, the local vertical turns by
// 2e-7 rad and a ray drops by s²/2R < 1 mm: the slab of the plane-parallel problem. In double
// precision the planet-scale geometry keeps its accuracy there (altitudes to ~1e-5 m, sphere
// roots to ~4e-6 m / cos): checked per direction against the closed form of single scattering.
// Then DISORT problem 2b (Rayleigh, tau 0.2, albedo 1, mu0 0.080442; DISOTEST.f, BLOCK DATA
// CHEKDO, Stamnes et al. 1988, checked by its authors against Sweigart 1970) through the
// reference's Monte Carlo orders, as tests/volume/slab_benchmark_test.cpp does through the path
// tracer.
//
// Cost: the reference's quadrature is set for a homogeneous layer (64 view nodes, 1 sun node,
// exact for a constant density). Before the reference stopped tracing paths off a black
// ground, every downward ray forked a second subtree: ~1.5^orders calls per path (2.5 s for 200
// paths at 8 orders with the default 96 x 32 nodes, 0.5 s after).
//
// False-failure rate: the two flux checks allow 4 standard errors + 0.2% (the quadrature's
// bias, -0.05% at 64 view nodes against 1024 in single scattering, and the truncation at 10
// orders: a photon scattered in the layer meets it again with probability at most
// 1.5 (1 - E_2(0.1)) = 0.42 (mid-depth; Rayleigh's phase is at most 1.5 times isotropic), so the
// orders past 10 carry below 0.42^10 / 0.58 = 3e-4 of the first's light). With the fixed seed a
// build passes or fails deterministically; with fresh seeds the pair would fail by noise about
// once in 8000 runs. The single-scattering check is deterministic (64 midpoint nodes: worst
// 1.6e-3, at grazing views where the layer is optically thick along the ray).
#include "sky/atmosphere_json.h"
#include "sky/sky_reference.h"
#include "sky/sky_scene.h"
#include "tests/sample_mean.h"

#include <gtest/gtest.h>

#include <cstdio>

namespace kasumi {
namespace {

constexpr double kTau = 0.2, kMu0 = 0.080442, kThicknessM = 1000.0, kRadiusM = 6.36e10;

std::shared_ptr<const SkyScene> slab(int orders) {
    Atmosphere a = default_earth_atmosphere({550.0}, {680.0, 550.0, 440.0});
    a.ground_radius_m = kRadiusM;
    a.top_radius_m = kRadiusM + kThicknessM;
    a.rayleigh.profile = DensityProfile{};
    a.rayleigh.profile.upper.constant_term = 1.0;  // uniform density 1 through the layer
    a.rayleigh.scattering[0] = kTau / kThicknessM;
    a.rayleigh_depolarization[0] = 0.0;  // DISORT's Rayleigh phase, 3/(16 pi)(1 + mu²)
    a.mie.scattering.fill(0.0);
    a.mie.absorption.fill(0.0);
    a.ozone.absorption.fill(0.0);
    a.ground_albedo.fill(0.0);
    SunDesc sun;
    sun.elevation_deg = std::asin(kMu0) * 180.0 / kPiD;
    sun.azimuth_deg = 0.0;
    SkySettings settings;
    settings.mode = SkyMode::Reference;
    settings.spectral_bands = 1;  // one band, 550 nm
    settings.orders = orders;
    settings.view_steps = 64;
    settings.sun_steps = 1;
    return make_sky_scene(a, sun, settings);
}

/// Direction with cosine `mu` to the vertical (up if `up`) and azimuth phi.
DVec3 direction(double mu, double phi, bool up) {
    const double s = std::sqrt(std::max(0.0, 1.0 - mu * mu));
    return DVec3(s * std::cos(phi), up ? mu : -mu, s * std::sin(phi));
}

TEST(SkySlab, SingleScatteringMatchesThePlaneParallelClosedForm) {
    // Per unit irradiance normal to the beam, single scattering by a layer of depth tau, albedo
    // 1, phase p (the plane-parallel equation integrated once; Chandrasekhar 1960, *Radiative
    // Transfer*, ch. I): leaving the top along
    // mu, L = p mu0 / (mu0 + mu) (1 - e^{-tau (1/mu0 + 1/mu)}); arriving at the bottom,
    // L = p mu0 / (mu0 - mu) (e^{-tau/mu0} - e^{-tau/mu}).
    const auto sky = slab(1);
    const DVec3 top(0.0, kThicknessM + 1.0, 0.0), bottom(0.0, 1e-3, 0.0);
    Pcg32 rng(1, 1);
    double worst = 0.0;
    for (const double mu : {0.05, 0.1, 0.2, 0.35, 0.5, 0.7, 0.9, 1.0}) {
        for (const double phi_deg : {0.0, 45.0, 90.0, 135.0, 180.0}) {
            const double phi = phi_deg * kPiD / 180.0;
            // Upward light at the top: looking down from above.
            const DVec3 d_up = direction(mu, phi, false);
            const double p_up = rayleigh_phase(0.0, glm::dot(d_up, sky->sun_direction));
            const double up_expected =
                p_up * kMu0 / (kMu0 + mu) * -std::expm1(-kTau * (1.0 / kMu0 + 1.0 / mu));
            const double up = reference_sky(*sky, top, d_up, 1e30, false, 1, rng).radiance[0];
            EXPECT_NEAR(up / up_expected, 1.0, 3e-3) << "top, mu " << mu << ", phi " << phi_deg;
            worst = std::max(worst, std::abs(up / up_expected - 1.0));
            // Downward light at the bottom: looking up from the ground.
            const DVec3 d_down = direction(mu, phi, true);
            const double p_down = rayleigh_phase(0.0, glm::dot(d_down, sky->sun_direction));
            const double down_expected =
                p_down * kMu0 / (kMu0 - mu) * (std::exp(-kTau / kMu0) - std::exp(-kTau / mu));
            const double down =
                reference_sky(*sky, bottom, d_down, 1e30, false, 1, rng).radiance[0];
            EXPECT_NEAR(down / down_expected, 1.0, 3e-3)
                << "bottom, mu " << mu << ", phi " << phi_deg;
            worst = std::max(worst, std::abs(down / down_expected - 1.0));
        }
    }
    std::printf("single scattering: worst relative error %.2e\n", worst);
}

TEST(SkySlab, Disort2bFluxesThroughTheReferenceOrders) {
    // Flux leaving the top (plane albedo) and diffuse flux reaching the bottom (diffuse
    // transmission) over the flux mu0 entering: pi E[L] / mu0 over cosine-distributed
    // directions. 10 scattering orders; DISORT sums them all.
    const auto sky = slab(10);
    constexpr int kPaths = 45000;  // per-path spread 0.8 of the mean: 4 s.e. ~1.5%
    const double published[2] = {1.25561e-01 / (kMu0 * kPiD), 1.06123e-01 / (kMu0 * kPiD)};
    for (int face = 0; face < 2; ++face) {
        const bool top = face == 0;
        const DVec3 p(0.0, top ? kThicknessM + 1.0 : 1e-3, 0.0);
        Pcg32 rng(17, static_cast<uint64_t>(face));
        SampleMean mean;
        for (int i = 0; i < kPaths; ++i) {
            const double u1 = rng.next_float(), u2 = rng.next_float();
            const DVec3 d = direction(std::sqrt(1.0 - u1), 2.0 * kPiD * u2, !top);
            mean.add(kPiD * reference_sky(*sky, p, d, 1e30, false, 10, rng).radiance[0] / kMu0);
        }
        const MeanAndError m = mean.result();
        std::printf("%s: %.5f +- %.5f (published %.5f, %+.2f%%)\n",
                    top ? "plane albedo" : "diffuse transmission", m.mean, m.stderr_,
                    published[face], 100.0 * (m.mean / published[face] - 1.0));
        EXPECT_LT(m.stderr_, 0.004 * published[face]) << "too few paths";
        EXPECT_NEAR(m.mean, published[face], 4.0 * m.stderr_ + 0.002 * published[face]);
    }
}

}  // namespace
}  // namespace kasumi
