// The tracking integrators against exact answers: white furnace, the plane albedo of a
// semi-infinite isotropic medium (Chandrasekhar's H-function), and single scattering of a
// point light in fog (the airlight integral of Sun et al. 2005).
#include "core/sampling.h"
#include "tests/sample_mean.h"
#include "vdb_test_grids.h"
#include "volume/volume_path.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

namespace kasumi {
namespace {

/// Paths that leave the media see a uniform background (no surfaces).
class UniformBackground final : public PathEnvironment {
  public:
    explicit UniformBackground(Rgb radiance) : m_radiance(radiance) {}
    float surface_distance(const Ray&) const override { return kInfinity; }
    Rgb radiance(const Ray&, Pcg32&) const override { return m_radiance; }

  private:
    Rgb m_radiance;
};

using Mean = MeanAndError;

Mean average(int n, const std::function<double(Pcg32&)>& sample) {
    SampleMean m;
    for (int i = 0; i < n; ++i) {
        Pcg32 rng(17, static_cast<uint64_t>(i));
        m.add(sample(rng));
    }
    return m.result();
}

VolumeSettings multiple(Estimator estimator) {
    VolumeSettings s;
    s.integrator = VolumeIntegrator::Multiple;
    s.estimator = estimator;
    s.max_depth = 100000;  // no truncation: Russian roulette ends the paths
    return s;
}

/// L = L_volume + T * L_background for a camera ray ending nowhere.
double furnace_radiance(const MediumSet& media, const VolumeSettings& settings, const Ray& ray,
                        Pcg32& rng) {
    const UniformBackground background(Rgb(1.0f));
    VolumeCounters counters;
    const VolumeResult v =
        integrate_media(media, {}, nullptr, &background, ray, settings, true, rng, counters);
    return v.radiance.g + v.transmittance.g;
}

TEST(WhiteFurnace, AlbedoOneMediaReturnTheEnvironment) {
    // Energy conservation: with albedo 1 and a uniform environment of radiance 1, every path
    // carries weight 1 whatever its length, so L = 1 exactly in expectation.
    const std::string box = test::write_box("furnace", 16, 1.0f, 0.25);
    const MediumSet grid({test::vdb_medium(
        box, {{"density_scale", 3.0}, {"albedo", 1.0}, {"phase", {{"model", "hg"}, {"g", 0.6}}}})});
    const MediumSet fog({Medium{"fog", HomogeneousMedium{Bounds3{Vec3(-1.0f), Vec3(1.0f)},
                                                         Rgb(0.0f), Rgb(4.0f), Isotropic{}}}});
    const Ray inside_grid{Vec3(2.0f, 1.9f, 2.1f), glm::normalize(Vec3(1, 0.3f, -0.2f)), 0.0f,
                          kInfinity};
    const Ray inside_fog{Vec3(0.1f, 0.2f, 0.0f), glm::normalize(Vec3(-1, 0.5f, 0.2f)), 0.0f,
                         kInfinity};
    for (Estimator e : {Estimator::Delta, Estimator::Ratio, Estimator::ResidualRatio}) {
        for (const auto& [media, ray] :
             {std::pair{&grid, inside_grid}, std::pair{&fog, inside_fog}}) {
            const Mean l = average(
                4000, [&](Pcg32& rng) { return furnace_radiance(*media, multiple(e), ray, rng); });
            // 4 standard errors; the bound has teeth (a 2% loss fails).
            EXPECT_NEAR(l.mean, 1.0, 4.0 * l.stderr_ + 1e-6);
            EXPECT_LT(4.0 * l.stderr_, 0.02);
        }
    }
}

/// Chandrasekhar's H-function for isotropic scattering with albedo w, from the iteration
/// 1/H(mu) = sqrt(1 - w) + (w/2) int_0^1 mu' H(mu') / (mu + mu') dmu' (Chandrasekhar 1960,
/// "Radiative Transfer", Dover, §39 eq. (4)), on Gauss-Legendre nodes.
double h_function(double w, double mu) {
    constexpr int kNodes = 64;
    static double x[kNodes], wt[kNodes];
    static bool ready = false;
    if (!ready) {
        // Gauss-Legendre on [0, 1] by Newton iteration on P_n.
        for (int i = 0; i < kNodes; ++i) {
            double z = std::cos(kPiD * (i + 0.75) / (kNodes + 0.5)), dp = 0.0;
            for (int it = 0; it < 100; ++it) {
                double p0 = 1.0, p1 = z;
                for (int k = 2; k <= kNodes; ++k) {
                    const double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
                    p0 = p1;
                    p1 = p2;
                }
                dp = kNodes * (z * p1 - p0) / (z * z - 1.0);
                const double dz = p1 / dp;
                z -= dz;
                if (std::abs(dz) < 1e-15)
                    break;
            }
            x[i] = 0.5 * (1.0 - z);
            wt[i] = 1.0 / ((1.0 - z * z) * dp * dp);  // 2/((1-z^2)P'^2), halved for [0, 1]
        }
        ready = true;
    }
    double h[kNodes];
    std::fill(h, h + kNodes, 1.0);
    const auto eval = [&](double m) {
        double integral = 0.0;
        for (int j = 0; j < kNodes; ++j)
            integral += wt[j] * x[j] * h[j] / (m + x[j]);
        return 1.0 / (std::sqrt(1.0 - w) + 0.5 * w * integral);
    };
    // The plain iteration H <- eval(H) flips the scale of H each step when w = 1 (eval is
    // homogeneous of degree -1 in H); the geometric mean of H and eval(H) removes the flip.
    for (int it = 0; it < 500; ++it) {
        double next[kNodes];
        for (int i = 0; i < kNodes; ++i)
            next[i] = std::sqrt(h[i] * eval(x[i]));
        std::copy(next, next + kNodes, h);
    }
    return eval(mu);
}

TEST(SemiInfinite, HFunctionMatchesChandrasekharsTable) {
    // Chandrasekhar (1960), Table XI (conservative isotropic scattering): H(1) = 2.9078,
    // H(0.5) = 2.0133 -- anchors the solver used below.
    EXPECT_NEAR(h_function(1.0, 1.0), 2.9078, 2e-3);
    EXPECT_NEAR(h_function(1.0, 0.5), 2.0133, 2e-3);
}

TEST(SemiInfinite, PlaneAlbedoMatchesChandrasekhar) {
    // A semi-infinite isotropic medium lit at normal incidence reflects the fraction
    // r(1) = 1 - H(1) sqrt(1 - w) of the incident flux (Chandrasekhar 1960, §47; van de Hulst
    // 1980, "Multiple Light Scattering" vol. 1, ch. 4). Measured as pi <L_up> / E with
    // cosine-weighted view directions.
    for (const double w : {0.9, 0.99}) {
        const MediumSet sea(
            {Medium{"sea", HomogeneousMedium{Bounds3{Vec3(-1e7f), Vec3(1e7f, 0.0f, 1e7f)},
                                             Rgb(static_cast<float>(1.0 - w)),
                                             Rgb(static_cast<float>(w)), Isotropic{}}}});
        const std::vector<Light> sun{Light{"sun", DirectionalLight{Vec3(0, -1, 0), Rgb(1.0f)}}};
        const Mean l = average(160000, [&](Pcg32& rng) {
            const Vec3 d = sample_cosine_hemisphere(rng.next_vec2());
            const Ray ray{Vec3(0.0f, 1.0f, 0.0f), Vec3(d.x, -d.z, d.y), 0.0f, kInfinity};
            VolumeCounters counters;
            return kPiD * integrate_media(sea, sun, nullptr, nullptr, ray,
                                          multiple(Estimator::ResidualRatio), true, rng, counters)
                              .radiance.g;
        });
        const double expected = 1.0 - h_function(w, 1.0) * std::sqrt(1.0 - w);
        // Within 1% (the bound) and within the statistics.
        EXPECT_NEAR(l.mean, expected, 0.01 * expected) << "albedo " << w;
        EXPECT_NEAR(l.mean, expected, 4.0 * l.stderr_ + 1e-4) << "albedo " << w;
        EXPECT_LT(4.0 * l.stderr_, 0.01 * expected);
    }
}

/// F(u, v) = int_0^v exp(-u tan xi) dxi (Sun et al. 2005, eq. 5), by Simpson's rule.
double sun_f(double u, double v) {
    const int n = 20000;
    const double h = v / n;
    double s = 0.0;
    for (int i = 0; i <= n; ++i) {
        const double f = std::exp(-u * std::tan(i * h));
        s += (i == 0 || i == n ? 1.0 : (i % 2 ? 4.0 : 2.0)) * f;
    }
    return s * h / 3.0;
}

TEST(Airlight, PointLightInFogMatchesSunEtAl2005) {
    // Sun, Ramamoorthi, Narasimhan & Nayar 2005, "A Practical Analytic Single Scattering Model
    // for Real Time Rendering", ACM TOG 24(3), eqs. 3-5: an isotropic point light of intensity
    // I at distance D_sv from the viewer, in a purely scattering medium of coefficient beta
    // with isotropic phase, seen at angle gamma from the light's direction, over a view ray of
    // length D_vp:
    //   L = A0 [F(A1, pi/4 + atan((T_vp - T_sv cos g) / (T_sv sin g)) / 2) - F(A1, g/2)],
    //   A0 = beta^2 I exp(-T_sv cos g) / (2 pi T_sv sin g), A1 = T_sv sin g, T = beta D,
    // with the upper limit pi/2 for an endless ray.
    const double beta = 0.4, intensity = 100.0, d_sv = 2.0;
    const MediumSet fog(
        {Medium{"fog", HomogeneousMedium{std::nullopt, Rgb(0.0f), Rgb(static_cast<float>(beta)),
                                         Isotropic{}}}});
    const std::vector<Light> lamp{
        Light{"lamp", PointLight{Vec3(0.0f, 0.0f, static_cast<float>(-d_sv)), Rgb(100.0f)}}};
    struct Case {
        double gamma_deg, d_vp;
    };
    for (const Case c :
         {Case{30.0, kInfinity}, Case{75.0, kInfinity}, Case{120.0, kInfinity}, Case{50.0, 3.0}}) {
        const double g = c.gamma_deg * kPiD / 180.0;
        const Ray ray{Vec3(0.0f),
                      Vec3(static_cast<float>(std::sin(g)), 0.0f, static_cast<float>(-std::cos(g))),
                      0.0f, static_cast<float>(c.d_vp)};
        const double t_sv = beta * d_sv, a1 = t_sv * std::sin(g);
        const double upper =
            c.d_vp >= kInfinity
                ? kPiD / 2.0
                : kPiD / 4.0 + 0.5 * std::atan((beta * c.d_vp - t_sv * std::cos(g)) / a1);
        const double expected = beta * beta * intensity * std::exp(-t_sv * std::cos(g)) /
                                (2.0 * kPiD * a1) * (sun_f(a1, upper) - sun_f(a1, g / 2.0));
        VolumeSettings single;
        single.estimator = Estimator::ResidualRatio;
        const Mean l = average(800000, [&](Pcg32& rng) {
            VolumeCounters counters;
            return integrate_media(fog, lamp, nullptr, nullptr, ray, single, true, rng, counters)
                .radiance.g;
        });
        // 0.5% (the bound), and the statistics are tight enough to see it.
        EXPECT_NEAR(l.mean, expected, 0.005 * expected) << "gamma " << c.gamma_deg;
        EXPECT_NEAR(l.mean, expected, 4.0 * l.stderr_ + 1e-4 * expected) << "gamma " << c.gamma_deg;
        EXPECT_LT(4.0 * l.stderr_, 0.005 * expected) << "gamma " << c.gamma_deg;
    }
}

}  // namespace
}  // namespace kasumi
