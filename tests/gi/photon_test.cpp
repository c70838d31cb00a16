// Photon mapping against exact answers: emission conserves each light's flux exactly and follows
// its intensity distribution (chi-square); the density estimate of a point light's photons on a
// plane converges to the inverse-square cosine law; a closed diffuse sphere around a point light
// reaches E / (1 - ρ); volume photons match the volume integrator's multiple scattering.
#include "core/sampling.h"
#include "gi/photon/photon_emission.h"
#include "gi/photon/photon_estimate.h"
#include "gi/photon/photon_gi.h"
#include "gi/photon/photon_tracer.h"
#include "lights/ies_profile.h"
#include "render/integrator.h"
#include "tests/gi/gi_test_scene.h"
#include "tests/sample_mean.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

namespace kasumi {
namespace {

/// Chi-square critical value for `df` degrees of freedom at tail probability 1e-6 (z = 4.753),
/// by the Wilson-Hilferty cube approximation (accurate to ~1% for df >= 5): a correct sampler
/// fails with probability ~1e-6 per test.
double chi2_critical_1e6(int df) {
    const double z = 4.753, a = 2.0 / (9.0 * df);
    return df * std::pow(1.0 - a + z * std::sqrt(a), 3.0);
}

/// Pearson's statistic of observed counts against expected probabilities; bins expected below 5
/// are pooled into the next (Mitsuba's rule). Returns {chi2, degrees of freedom}.
std::pair<double, int> chi_square(const std::vector<double>& observed,
                                  const std::vector<double>& expected_probability, double n) {
    double chi2 = 0.0, pooled_o = 0.0, pooled_e = 0.0;
    int bins = 0;
    for (size_t i = 0; i < observed.size(); ++i) {
        pooled_o += observed[i];
        pooled_e += expected_probability[i] * n;
        if (pooled_e >= 5.0 || i + 1 == observed.size()) {
            if (pooled_e > 0.0) {
                chi2 += (pooled_o - pooled_e) * (pooled_o - pooled_e) / pooled_e;
                ++bins;
            } else if (pooled_o > 0.0) {
                return {1e30, 1};  // photons where none may go
            }
            pooled_o = pooled_e = 0.0;
        }
    }
    return {chi2, bins - 1};
}

Light make(std::variant<DirectionalLight, PointLight, SpotLight, GoniometricLight, LineLight,
                        PolygonLight, SphereLight>
               emitter) {
    Light l;
    l.emitter = std::move(emitter);
    return l;
}

std::vector<Light> every_light_type() {
    std::vector<Light> lights;
    lights.push_back(make(DirectionalLight{glm::normalize(Vec3(0.3f, -1.0f, 0.2f)), Rgb(2, 3, 4)}));
    lights.push_back(make(PointLight{Vec3(1, 2, 3), Rgb(100, 50, 20)}));
    SpotLight spot;
    spot.position = Vec3(0, 3, 0);
    spot.intensity = Rgb(400, 300, 200);
    spot.cos_cone = std::cos(radians(40.0f));
    spot.cos_falloff = std::cos(radians(25.0f));
    lights.push_back(make(spot));
    GoniometricLight gonio;
    gonio.position = Vec3(-2, 4, 0);
    gonio.local_to_world = luminaire_frame(Vec3(0.0f, 30.0f, 0.0f));
    gonio.profile =
        std::make_shared<IesProfile>(read_ies(KASUMI_SOURCE_DIR "/data/ies/quadrant_roadway.ies"));
    gonio.scale = Rgb(0.5f, 0.4f, 0.3f);
    lights.push_back(make(gonio));
    lights.push_back(make(LineLight{Vec3(0, 2, -1), Vec3(1, 2, 1), Rgb(30, 30, 10)}));
    lights.push_back(make(make_polygon_light(
        {Vec3(0, 3, 0), Vec3(1, 3, 0), Vec3(1, 3, 1), Vec3(0, 3, 1)}, Rgb(80, 90, 100), true)));
    lights.push_back(make(SphereLight{Vec3(2, 1, 0), 0.25f, Rgb(500, 400, 300)}));
    return lights;
}

/// One camera ray's radiance sample (green channel, cd/m²) on the random stream (seed, i).
double camera_radiance(const SceneRuntime& scene, const Ray& ray, uint64_t seed, int i) {
    Pcg32 rng(seed, static_cast<uint64_t>(i));
    RenderCounters counters;
    return static_cast<double>(trace_camera_ray(scene, ray, rng, counters).radiance.g);
}

/// The mean radiance (green channel, cd/m²) seen from `origin` over n directions uniform on the
/// sphere, direction i and its path drawn from the stream (seed, i).
double mean_radiance_over_sphere(const SceneRuntime& scene, const Vec3& origin, uint64_t seed,
                                 int n) {
    RenderCounters counters;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
        Pcg32 rng(seed, static_cast<uint64_t>(i));
        const Vec3 d = sample_uniform_sphere(rng.next_vec2());
        sum += trace_camera_ray(scene, Ray{origin, d, 0.0f, kInfinity}, rng, counters).radiance.g;
    }
    return sum / n;
}

TEST(PhotonEmission, PhotonPowersSumExactlyToEachLightsFlux) {
    const std::vector<Light> lights = every_light_type();
    const BoundingSphere sphere{Vec3(0.5f, 1.0f, 0.0f), 6.0f};
    std::vector<EmissiveTriangle> triangles{
        {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, 2), Rgb(10, 20, 30)}};
    std::vector<EmissiveSphere> spheres{{Vec3(0, 5, 0), 0.5f, Rgb(7, 8, 9)}};
    PhotonEmitter emitter(lights, sphere, triangles, spheres);
    ASSERT_EQ(emitter.sources(), lights.size() + 2);
    for (size_t i = 1; i < lights.size(); ++i) {
        // The RGB flux's luminance is the lights' own photometric flux.
        EXPECT_NEAR(luminance(light_flux(lights[i], sphere)), luminous_flux_lm(lights[i]),
                    2e-5 * luminous_flux_lm(lights[i]))
            << light_type_name(lights[i]);
    }
    EXPECT_FLOAT_EQ(luminance(light_flux(lights[0], sphere)),
                    luminance(Rgb(2, 3, 4)) * kPi * 36.0f);
    for (uint64_t n : {7ull, 1000ull, 12345ull}) {
        emitter.allot(n);
        std::vector<DVec3> sums(emitter.sources(), DVec3(0.0));
        uint64_t index = 0;
        for (size_t s = 0; s < emitter.sources(); ++s) {
            for (uint64_t j = 0; j < emitter.source_count(s); ++j, ++index) {
                Pcg32 rng(5, index);
                const EmittedPhoton p = emitter.emit(index, rng);
                sums[s] += DVec3(p.power);
                ASSERT_NEAR(glm::length(p.ray.direction), 1.0f, 1e-5f);
            }
        }
        ASSERT_EQ(index, n);
        DVec3 total(0.0);
        for (size_t s = 0; s < emitter.sources(); ++s) {
            const Rgb flux = s < lights.size()    ? light_flux(lights[s], sphere)
                             : s == lights.size() ? emissive_flux(triangles[0])
                                                  : emissive_flux(spheres[0]);
            total += sums[s];
            if (emitter.source_count(s) == 0)
                continue;
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(sums[s][c], flux[c], 1e-6 * flux[c]) << "source " << s << " n " << n;
        }
        if (n >= emitter.sources()) {
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(total[c], emitter.total_flux()[c], 1e-5 * emitter.total_flux()[c]);
        }
    }
}

TEST(PhotonEmission, PhotonsAreAllottedInProportionToFlux) {
    const std::vector<Light> lights = every_light_type();
    const BoundingSphere sphere{Vec3(0.0f), 6.0f};
    PhotonEmitter emitter(lights, sphere);
    const uint64_t n = 100000;
    emitter.allot(n);
    const double total = luminance(emitter.total_flux());
    for (size_t s = 0; s < lights.size(); ++s) {
        const double share = n * luminance(light_flux(lights[s], sphere)) / total;
        EXPECT_NEAR(static_cast<double>(emitter.source_count(s)), share, 2.0) << s;
    }
}

/// Directions of `n` photons of one light.
std::vector<Vec3> emit_directions(const Light& light, int n, std::vector<Vec3>* origins = nullptr) {
    PhotonEmitter emitter({light}, BoundingSphere{});
    emitter.allot(static_cast<uint64_t>(n));
    std::vector<Vec3> d;
    for (int i = 0; i < n; ++i) {
        Pcg32 rng(17, static_cast<uint64_t>(i));
        const EmittedPhoton p = emitter.emit(static_cast<uint64_t>(i), rng);
        d.push_back(p.ray.direction);
        if (origins)
            origins->push_back(p.ray.origin);
    }
    return d;
}

TEST(PhotonEmission, SpotDirectionsFollowTheFalloffChiSquare) {
    SpotLight spot;
    spot.direction = glm::normalize(Vec3(0.2f, -1.0f, 0.1f));
    spot.intensity = Rgb(1.0f);
    spot.cos_cone = std::cos(radians(40.0f));
    spot.cos_falloff = std::cos(radians(25.0f));
    const int n = 200000, bins = 40;
    std::vector<double> observed(bins, 0.0), expected(bins, 0.0);
    for (const Vec3& d : emit_directions(make(spot), n)) {
        const float mu = glm::dot(d, spot.direction);
        ASSERT_GE(mu, spot.cos_cone - 1e-5f);
        const int b = std::min(
            bins - 1, static_cast<int>((mu - spot.cos_cone) / (1.0f - spot.cos_cone) * bins));
        observed[static_cast<size_t>(std::max(b, 0))] += 1.0;
    }
    // Expected: ∫ s(μ) dμ per bin by the midpoint rule (1000 nodes a bin), over the total.
    double total = 0.0;
    for (int b = 0; b < bins; ++b) {
        for (int j = 0; j < 1000; ++j) {
            const double mu =
                spot.cos_cone + (1.0 - spot.cos_cone) * (b + (j + 0.5) / 1000.0) / bins;
            expected[static_cast<size_t>(b)] += spot_falloff(spot, static_cast<float>(mu));
        }
        total += expected[static_cast<size_t>(b)];
    }
    for (double& e : expected)
        e /= total;
    const auto [chi2, df] = chi_square(observed, expected, n);
    EXPECT_LT(chi2, chi2_critical_1e6(df)) << "df " << df;
}

TEST(PhotonEmission, LineDirectionsFollowSinAlphaChiSquare) {
    const LineLight line{Vec3(0, 0, 0), Vec3(0.5f, 1.0f, -0.3f), Rgb(1.0f)};
    const Vec3 axis = glm::normalize(line.to - line.from);
    const int n = 200000, bins = 40;
    std::vector<Vec3> origins;
    std::vector<double> observed(bins, 0.0), expected(bins, 0.0), along(10, 0.0);
    const std::vector<Vec3> dirs = emit_directions(make(line), n, &origins);
    for (int i = 0; i < n; ++i) {
        const float mu = glm::dot(dirs[static_cast<size_t>(i)], axis);
        observed[static_cast<size_t>(
            std::clamp(static_cast<int>((mu + 1.0f) * 0.5f * bins), 0, bins - 1))] += 1.0;
        const float s = glm::dot(origins[static_cast<size_t>(i)] - line.from, axis) /
                        glm::length(line.to - line.from);
        along[static_cast<size_t>(std::clamp(static_cast<int>(s * 10.0f), 0, 9))] += 1.0;
    }
    // Intensity ∝ sin α per sr: μ = cos α has density (2/π) √(1 - μ²), CDF (μ√(1-μ²) + asin μ)/π.
    auto cdf = [](double mu) { return (mu * std::sqrt(1.0 - mu * mu) + std::asin(mu)) / kPiD; };
    for (int b = 0; b < bins; ++b)
        expected[static_cast<size_t>(b)] =
            cdf(-1.0 + 2.0 * (b + 1) / bins) - cdf(-1.0 + 2.0 * b / bins);
    const auto [chi2, df] = chi_square(observed, expected, n);
    EXPECT_LT(chi2, chi2_critical_1e6(df)) << "df " << df;
    const auto [chi2_s, df_s] = chi_square(along, std::vector<double>(10, 0.1), n);
    EXPECT_LT(chi2_s, chi2_critical_1e6(df_s));
}

TEST(PhotonEmission, GoniometricDirectionsFollowTheTableChiSquare) {
    GoniometricLight gonio;
    gonio.local_to_world = luminaire_frame(Vec3(10.0f, 20.0f, 0.0f));
    gonio.profile =
        std::make_shared<IesProfile>(read_ies(KASUMI_SOURCE_DIR "/data/ies/quadrant_roadway.ies"));
    const IesProfile& profile = *gonio.profile;
    const int n = 200000, nv = 12, nh = 12;
    std::vector<double> observed(nv * nh, 0.0), expected(nv * nh, 0.0);
    const Mat3 world_to_local = glm::transpose(gonio.local_to_world);
    for (const Vec3& d : emit_directions(make(gonio), n)) {
        const Vec3 local = world_to_local * d;
        const float gamma = degrees(safe_acos(-local.z));
        float c = degrees(std::atan2(local.y, local.x));
        if (c < 0.0f)
            c += 360.0f;
        const int iv = std::min(nv - 1, static_cast<int>(gamma / 180.0f * nv));
        const int ih = std::min(nh - 1, static_cast<int>(c / 360.0f * nh));
        observed[static_cast<size_t>(ih * nv + iv)] += 1.0;
    }
    // Expected by quadrature of ies_candela (independent of the sampler's cell integrals):
    // ∫∫ I sin γ dγ dC, midpoint rule on a 0.1° × 0.5° grid.
    double total = 0.0;
    for (int j = 0; j < 1800; ++j) {
        const double g = (j + 0.5) * 0.1;
        for (int i = 0; i < 720; ++i) {
            const double c = (i + 0.5) * 0.5;
            const double w = ies_candela(profile, static_cast<float>(g), static_cast<float>(c)) *
                             std::sin(g * kPiD / 180.0);
            expected[static_cast<size_t>(static_cast<int>(c / 360.0 * nh) * nv +
                                         static_cast<int>(g / 180.0 * nv))] += w;
            total += w;
        }
    }
    for (double& e : expected)
        e /= total;
    const auto [chi2, df] = chi_square(observed, expected, n);
    EXPECT_LT(chi2, chi2_critical_1e6(df)) << "df " << df;
}

/// Photons of one pass stored by a scene, as a map.
PhotonMap trace_map(const SceneRuntime& scene, PhotonPass pass, uint64_t count, uint64_t seed = 1) {
    PhotonEmitter emitter(scene.desc().lights, scene_bounding_sphere(scene));
    emitter.allot(count);
    return PhotonMap(trace_photons(scene, emitter, pass, 64, seed, 0));
}

TEST(PhotonDensity, PointLightOnAPlaneConvergesToTheInverseSquareCosineLaw) {
    // A point light of I cd at height h over a plane: E(x) = I h / (h² + x²)^{3/2}. The k-nearest
    // density estimate has bias O(r²) ∝ k/N and relative standard deviation 1/√k; with
    // k ∝ N^{2/3} both shrink and the RMS relative error falls as N^{-1/3} (halves per 8× photons).
    const auto scene = gi_runtime_from_text(R"({
        "materials": {"floor": {"type": "phong", "kd": 0.5}},
        "shapes": [{"type": "quad", "material": "floor",
                    "vertices": [[-30, 0, -30], [-30, 0, 30], [30, 0, 30], [30, 0, -30]]}],
        "lights": [{"type": "point", "position": [0, 1, 0], "intensity_cd": 100}]})");
    const float h = 1.0f, intensity = 100.0f;
    std::vector<double> errors;
    for (uint64_t n : {20000ull, 160000ull, 1280000ull}) {
        const PhotonMap map = trace_map(*scene, PhotonPass::Global, n);
        const int k =
            static_cast<int>(std::lround(std::pow(static_cast<double>(n), 2.0 / 3.0) / 8.0));
        PhotonQueryScratch scratch;
        double sum2 = 0.0;
        int points = 0;
        for (int i = 0; i < 40; ++i) {
            const float x = 0.05f + 1.5f * static_cast<float>(i) / 40.0f;
            const float phi = 2.39996f * static_cast<float>(i);  // golden angle: spread in azimuth
            const Vec3 p(x * std::cos(phi), 0.0f, x * std::sin(phi));
            const float exact = intensity * h / std::pow(h * h + x * x, 1.5f);
            const Rgb e = surface_estimate(map, p, Vec3(0, 1, 0), k, 10.0f, PhotonFilter::Box,
                                           scratch, [](const Vec3&) { return Rgb(1.0f); });
            sum2 += std::pow(e.g / exact - 1.0, 2.0);
            ++points;
        }
        errors.push_back(std::sqrt(sum2 / points));
    }
    // Expected ratio 0.5 per 8×; 0.75 leaves room for the estimate's own noise (40 points).
    EXPECT_LT(errors[1], 0.75 * errors[0]) << errors[0] << " " << errors[1];
    EXPECT_LT(errors[2], 0.75 * errors[1]) << errors[1] << " " << errors[2];
    // At N = 1.28e6, k = 1474: the noise alone is 1/√k = 2.6% RMS; measured 3.4% with the bias.
    EXPECT_LT(errors[2], 0.045) << errors[0] << " " << errors[1];
}

const char* kSphereFurnace = R"({
    "materials": {"wall": {"type": "phong", "kd": 0.5}},
    "shapes": [{"type": "sphere", "material": "wall", "center": [0, 0, 0], "radius": 1}],
    "lights": [{"type": "point", "position": [0, 0, 0], "intensity_cd": 10}]})";

TEST(PhotonDensity, ClosedDiffuseSphereReachesEOverOneMinusRho) {
    // Inside a diffuse sphere every point sees every other with the same form factor, so each
    // bounce spreads ρ of the flux uniformly: E_total = E_direct / (1 - ρ), E_direct = I / R².
    // A ball of radius r around a point of the sphere cuts a cap of area exactly π r²
    // (Archimedes), so the box estimate has no curvature bias.
    const auto scene = gi_runtime_from_text(kSphereFurnace);
    const PhotonMap map = trace_map(*scene, PhotonPass::Global, 200000);
    const double expected = 10.0 / (1.0 - 0.5);
    PhotonQueryScratch scratch;
    std::mt19937 gen(3);
    std::normal_distribution<float> g;
    double sum = 0.0;
    const int points = 64;
    for (int i = 0; i < points; ++i) {
        const Vec3 p = glm::normalize(Vec3(g(gen), g(gen), g(gen)));
        sum += surface_estimate(map, p, -p, 400, 0.5f, PhotonFilter::Box, scratch, [](const Vec3&) {
                   return Rgb(1.0f);
               }).g;
    }
    // Each estimate: relative σ 1/√400 = 5%; the mean of 64 nearly independent ones ~0.7%;
    // 3% is 4σ. Direct light alone (ρ ignored) would read half.
    EXPECT_NEAR(sum / points, expected, 0.03 * expected);
}

TEST(PhotonRender, ClosedDiffuseSphereRadianceByFinalGathering) {
    // Seen from the centre, the wall's radiance is ρ E_total / π = ρ I / (π R² (1 - ρ)): half
    // from the direct light (shadow rays) and half from final gathering on the global map.
    std::string text = kSphereFurnace;
    text.insert(text.rfind('}'), R"(, "render": {"gi": "photons", "photons": {
        "global_count": 200000, "caustic_count": 1000, "volume_count": 0, "k": 200,
        "max_radius_m": 0.5, "final_gather_samples": 16}})");
    const auto scene = gi_runtime_from_text(text);
    const auto* gi = dynamic_cast<const PhotonGi*>(scene->gi());
    ASSERT_NE(gi, nullptr);
    EXPECT_EQ(gi->maps().caustic.size(), 0u);      // no specular surface: no caustic photons
    EXPECT_GT(gi->maps().global.size(), 300000u);  // ~2 stored per photon for ρ = 1/2
    const double expected = 0.5 * 10.0 / (kPiD * 0.5);
    EXPECT_NEAR(mean_radiance_over_sphere(*scene, Vec3(0.0f), 9, 2000), expected, 0.03 * expected);
}

}  // namespace
}  // namespace kasumi

namespace kasumi {
namespace {

std::string fog_box(const std::string& integrator, const std::string& render_extra = "") {
    return R"({
        "lights": [{"type": "point", "position": [0, 0, 0], "intensity_cd": 100}],
        "materials": {"black": {"type": "phong", "kd": 0}},
        "shapes": [{"type": "quad", "material": "black",
                    "vertices": [[-1, -9, -1], [-1, -9, 1], [1, -9, 1], [1, -9, -1]]}],
        "media": [{"type": "homogeneous", "bounds": [[-1, -1, -1], [1, 1, 1]],
                   "sigma_a": 0.3, "sigma_s": 1.5}],
        "render": {"volume": {"step_m": 0.05, "integrator": ")" +
           integrator + R"("})" + render_extra + "}}";
}

template <class Sample>
MeanAndError estimate(int n, Sample&& sample) {
    SampleMean m;
    for (int i = 0; i < n; ++i)
        m.add(sample(i));
    return m.result();
}

TEST(PhotonVolume, HomogeneousMediumMatchesTheVolumeIntegratorsMultipleScattering) {
    // A box of fog (albedo 0.83, optical half-width 1.8) around a point light, seen along a ray
    // passing 0.58 m from the light. Reference: the volume path tracer (single + multiple
    // scattering, unbiased). Photons: single scattering by shadow rays plus the volume map's
    // estimate of everything scattered more than once.
    const Ray ray{Vec3(0.5f, 0.3f, -3.0f), Vec3(0, 0, 1), 0.0f, kInfinity};
    auto camera = [&](const SceneRuntime& scene) {
        return estimate(40000, [&](int i) { return camera_radiance(scene, ray, 21, i); });
    };
    const MeanAndError multiple = camera(*gi_runtime_from_text(fog_box("multiple")));
    const MeanAndError single = camera(*gi_runtime_from_text(fog_box("single")));

    const auto scene = gi_runtime_from_text(fog_box("single", R"(, "gi": "photons", "photons": {
        "global_count": 0, "caustic_count": 0, "volume_count": 400000, "k": 100,
        "max_radius_m": 0.3})"));
    const auto* gi = dynamic_cast<const PhotonGi*>(scene->gi());
    ASSERT_NE(gi, nullptr);
    ASSERT_GT(gi->maps().volume.size(), 100000u);
    const MeanAndError photons =
        estimate(2000, [&](int i) { return camera_radiance(*scene, ray, 22, i); });
    // Stated error: 4 combined standard errors (false failures ~6e-5 for normal means) plus 3%
    // for the density estimate's bias (its radius smooths the fluence, O(r²)). The multiple-
    // scattering part alone is several times this: a map that is missing or off by its σ_s
    // factor fails.
    const double tolerance =
        4.0 * std::hypot(multiple.stderr_, photons.stderr_) + 0.03 * multiple.mean;
    EXPECT_NEAR(photons.mean, multiple.mean, tolerance)
        << "single " << single.mean << " ± " << single.stderr_ << ", multiple " << multiple.mean
        << " ± " << multiple.stderr_ << ", photons " << photons.mean << " ± " << photons.stderr_;
    EXPECT_GT(multiple.mean - single.mean, 3.0 * tolerance);
}

}  // namespace
}  // namespace kasumi

namespace kasumi {
namespace {

TEST(PhotonRender, EmissiveFurnaceBoxHasRadianceLeOverOneMinusRho) {
    // A closed box whose every face emits L_e (inward: the quads wind counter-clockwise seen
    // from inside) and reflects ρ diffusely: L = L_e + ρ E / π with E = π L everywhere, so
    // L = L_e / (1 - ρ) = 2 for L_e = 1, ρ = 0.5. Photons come from the emissive faces alone;
    // the camera sees emission + final gathering (emission of the gathered walls + global map).
    const auto scene = gi_runtime_from_text(R"({
        "materials": {"wall": {"type": "phong", "kd": 0.5, "emission_cd_m2": 1}},
        "shapes": [
          {"type": "quad", "material": "wall", "vertices": [[-1,-1,1],[1,-1,1],[1,-1,-1],[-1,-1,-1]]},
          {"type": "quad", "material": "wall", "vertices": [[1,1,-1],[1,1,1],[-1,1,1],[-1,1,-1]]},
          {"type": "quad", "material": "wall", "vertices": [[-1,1,-1],[-1,1,1],[-1,-1,1],[-1,-1,-1]]},
          {"type": "quad", "material": "wall", "vertices": [[1,-1,1],[1,1,1],[1,1,-1],[1,-1,-1]]},
          {"type": "quad", "material": "wall", "vertices": [[1,-1,-1],[1,1,-1],[-1,1,-1],[-1,-1,-1]]},
          {"type": "quad", "material": "wall", "vertices": [[-1,1,1],[1,1,1],[1,-1,1],[-1,-1,1]]}],
        "render": {"gi": "photons", "photons": {"global_count": 200000, "caustic_count": 0,
                   "volume_count": 0, "k": 200, "max_radius_m": 0.3,
                   "final_gather_samples": 16}}})");
    const auto* gi = dynamic_cast<const PhotonGi*>(scene->gi());
    ASSERT_NE(gi, nullptr);
    // Every photon is stored at each wall it hits: ~1/(1 - ρ) = 2 per emitted photon.
    EXPECT_NEAR(static_cast<double>(gi->maps().global.size()), 400000.0, 8000.0);
    const double mean = mean_radiance_over_sphere(*scene, Vec3(0.1f, -0.2f, 0.05f), 31, 2000);
    // 2000 views × 16 gathers of estimates with relative σ 1/√200 = 7% (correlated through
    // the map): ~0.5%; edges bias the disc estimate (photons of the neighbouring wall inside
    // it) by about a percent; 4% bounds both. Without the map the result would read 1.5.
    EXPECT_NEAR(mean, 2.0, 0.08);
}

}  // namespace
}  // namespace kasumi

namespace kasumi {
namespace {

/// Form factor from a point to a parallel rectangle a × b with one corner straight above it at
/// height h (Howell's catalogue, C-11; Siegel & Howell): F = 1/(2π) [A/√(1+A²) atan(B/√(1+A²))
/// + B/√(1+B²) atan(A/√(1+B²))], A = a/h, B = b/h.
double corner_form_factor(double a, double b, double h) {
    const double x = a / h, y = b / h;
    const double sx = std::sqrt(1.0 + x * x), sy = std::sqrt(1.0 + y * y);
    return (x / sx * std::atan(y / sx) + y / sy * std::atan(x / sy)) / (2.0 * kPiD);
}

std::string squares_scene(int gather_samples, int photons) {
    return R"({
        "materials": {"lamp": {"type": "phong", "kd": 0, "emission_cd_m2": 10},
                      "white": {"type": "phong", "kd": 0.8}},
        "shapes": [
          {"type": "quad", "material": "lamp",
           "vertices": [[-0.5, -0.5, 1], [-0.5, 0.5, 1], [0.5, 0.5, 1], [0.5, -0.5, 1]]},
          {"type": "quad", "material": "white",
           "vertices": [[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]]}],
        "render": {"gi": "photons", "photons": {"global_count": )" +
           std::to_string(photons) +
           R"(, "caustic_count": 0, "volume_count": 0, "k": 4000, "max_radius_m": 0.3, "filter": "box",
                   "final_gather_samples": )" +
           std::to_string(gather_samples) + "}}}";
}

TEST(PhotonRender, EmittingSquareOntoFacingSquareGivesRhoFLe) {
    // A unit square emitting L_e = 10 downward, 1 m above the centre of a white (ρ = 0.8)
    // square: the receiver's centre has radiance ρ F L_e, F = 4 × the corner form factor of a
    // 0.5 × 0.5 rectangle at height 1 (0.2395). The emitter is black (kd = 0): no interreflection.
    const double expected = 0.8 * 4.0 * corner_form_factor(0.5, 0.5, 1.0) * 10.0;
    const Ray ray{Vec3(0.0f, 0.0f, 0.5f), Vec3(0, 0, -1), 0.0f, kInfinity};
    {
        // The global map read at the hit (no gathering): one k-NN estimate with k = 4000 photons
        // of ~2e5 on the receiver, relative σ 1/√4000 = 1.6%; 6% is ~4σ (bias at r ≈ 0.08 m
        // where E is flat: < 0.5%).
        const auto scene = gi_runtime_from_text(squares_scene(0, 2000000));
        Pcg32 rng(1, 1);
        RenderCounters counters;
        const double l = trace_camera_ray(*scene, ray, rng, counters).radiance.g;
        EXPECT_NEAR(l, expected, 0.06 * expected);
    }
    {
        // Final gathering sees the emitter's emission (the map adds nothing: the lamp is black).
        const auto scene = gi_runtime_from_text(squares_scene(64, 10000));
        const MeanAndError l =
            estimate(500, [&](int i) { return camera_radiance(*scene, ray, 2, i); });
        EXPECT_NEAR(l.mean, expected, 5.0 * l.stderr_ + 1e-3 * expected);
    }
}

}  // namespace
}  // namespace kasumi
