// Transmittance estimators on one scene's media, at equal work: the variance of one estimate
// and its CPU cost, per estimator, on shadow rays from points inside the media (half toward the
// scene's first directional light, half in uniformly random directions), and the efficiency
// 1 / (variance x CPU seconds) relative to ratio tracking. Each repeat draws new random numbers
// and runs the estimators in alternating order on the same rays in this one process; the
// medians over repeats are printed, one JSON line per estimator, with a check of each against
// a 1/64-voxel march per ray (largest per-ray gap in standard errors, relative gap of the sums).
// Measured figures: docs/volumes.md (unbiased ray marching).
// Usage: transmittance_bench scene.json [rays=64] [samples=256] [repeats=5] [estimators] [light]
//   estimators: comma-separated render.volume.estimator names
//   (default ratio,residual-ratio,unbiased-march), or "cache-controlled": the unbiased march
//   debiased about the light cache's depth (unbiased_march_about, volume/unbiased_march.h),
//   only on rays toward the first directional light (its cache's direction);
//   light: every shadow ray toward that light (default: half of them in random directions).
#include "core/rng.h"
#include "scene/scene_loader.h"
#include "volume/light_cache.h"
#include "volume/medium_set.h"
#include "volume/transmittance.h"
#include "volume/unbiased_march.h"

#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace kasumi;

double thread_cpu_seconds() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/// Shadow rays from points where the media have extinction, inside the union of the grid boxes
/// (or a 1 km box around the origin when no medium is a grid).
std::vector<Ray> shadow_rays(const SceneDesc& scene, const MediumSet& media, int count,
                             bool all_toward_light) {
    Bounds3 box{Vec3(-500.0f), Vec3(500.0f)};
    if (const MediumSet::FastMedium* g = media.single_grid())
        box = g->bounds_world;
    Vec3 toward_light(0.0f, 1.0f, 0.0f);
    for (const Light& l : scene.lights)
        if (const auto* d = std::get_if<DirectionalLight>(&l.emitter)) {
            toward_light = -d->direction;
            break;
        }
    const uint32_t all_media = (1u << scene.media.size()) - 1u;
    Pcg32 rng(2026, 19);
    std::vector<Ray> rays;
    for (int tries = 0; static_cast<int>(rays.size()) < count && tries < 1000000; ++tries) {
        const Vec3 u(rng.next_float(), rng.next_float(), rng.next_float());
        const Vec3 p = box.min + u * (box.max - box.min);
        if (!(max_component(media.coefficients(p, all_media).sigma_t) > 0.0f))
            continue;
        Vec3 d = toward_light;
        if (rays.size() % 2 == 1 && !all_toward_light) {
            const float z = 1.0f - 2.0f * rng.next_float(), phi = 6.2831853f * rng.next_float();
            const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
            d = Vec3(r * std::cos(phi), r * std::sin(phi), z);
        }
        rays.push_back(Ray{p, glm::normalize(d), 0.0f, kInfinity});
    }
    return rays;
}

struct Run {
    double variance = 0.0;  ///< one estimate's variance (green channel), mean over rays
    double seconds = 0.0;   ///< CPU seconds per estimate
    double lookups = 0.0;   ///< density lookups per estimate
    std::vector<double> means;
    std::vector<double> variances;  ///< per ray
};

/// An estimator of the bench: a render.volume.estimator, or the cache-controlled march (`cache`
/// non-null: the light cache whose depth is the pivot).
struct BenchEstimator {
    std::string name;
    Estimator estimator = Estimator::Ratio;
    const LightTransmittanceCache* cache = nullptr;
};

Rgb estimate(const MediumSet& media, const Ray& ray, const BenchEstimator& e, float step,
             Pcg32& rng, VolumeCounters& counters) {
    if (e.cache == nullptr)
        return estimate_transmittance(media, ray, e.estimator, step, rng, counters);
    float depth = 0.0f;
    if (!e.cache->density_integral(e.cache->line(ray.origin, ray.direction), 0.0f, depth))
        depth = 0.0f;  // off the lattice: the pivot 0 (still unbiased)
    const DVec3 pivot = static_cast<double>(depth) * DVec3(e.cache->sigma_t_per_density());
    if (const auto t = unbiased_march_about(media, ray, pivot, rng, counters))
        return *t;
    return estimate_transmittance(media, ray, Estimator::UnbiasedMarch, step, rng, counters);
}

Run run(const MediumSet& media, const std::vector<Ray>& rays, const BenchEstimator& e, float step,
        int samples, uint64_t seed) {
    Run r;
    VolumeCounters counters;
    std::vector<double> sum(rays.size(), 0.0), sum2(rays.size(), 0.0);
    const double t0 = thread_cpu_seconds();
    for (size_t i = 0; i < rays.size(); ++i)
        for (int s = 0; s < samples; ++s) {
            Pcg32 rng(seed, i * static_cast<uint64_t>(samples) + static_cast<uint64_t>(s));
            const double t = estimate(media, rays[i], e, step, rng, counters).g;
            sum[i] += t;
            sum2[i] += t * t;
        }
    const double n = static_cast<double>(rays.size()) * samples;
    r.seconds = (thread_cpu_seconds() - t0) / n;
    r.lookups = static_cast<double>(counters.density_lookups) / n;
    for (size_t i = 0; i < rays.size(); ++i) {
        const double mean = sum[i] / samples;
        r.means.push_back(mean);
        r.variances.push_back(std::max(0.0, sum2[i] / samples - mean * mean) * samples /
                              (samples - 1.0));
        r.variance += r.variances.back();
    }
    r.variance /= static_cast<double>(rays.size());
    return r;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr,
                     "usage: transmittance_bench scene.json [rays] [samples] [repeats] "
                     "[estimators] [light]\n");
        return 2;
    }
    try {
        const int ray_count = argc > 2 ? std::stoi(argv[2]) : 64;
        const int samples = argc > 3 ? std::stoi(argv[3]) : 256;
        const int repeats = argc > 4 ? std::stoi(argv[4]) : 5;
        const bool all_toward_light = argc > 6 && std::string(argv[6]) == "light";
        const SceneDesc scene = load_scene(argv[1]);
        const MediumSet media(scene.media);
        std::vector<BenchEstimator> estimators;
        std::stringstream names(argc > 5 ? argv[5] : "ratio,residual-ratio,unbiased-march");
        for (std::string name; std::getline(names, name, ',');) {
            BenchEstimator b;
            b.name = name;
            if (name == "cache-controlled") {
                for (size_t l = 0; l < scene.lights.size() && b.cache == nullptr; ++l)
                    b.cache = media.light_cache(l, scene.lights[l]);
                if (b.cache == nullptr || !all_toward_light)
                    throw std::runtime_error(
                        "cache-controlled needs one grid medium, a directional light and the "
                        "\"light\" argument");
            } else {
                const auto e = estimator_from_name(name);
                if (!e)
                    throw std::runtime_error("unknown estimator \"" + name + "\"");
                b.estimator = *e;
            }
            estimators.push_back(b);
        }
        const float step = march_step_m(media, scene.render.volume);
        const std::vector<Ray> rays = shadow_rays(scene, media, ray_count, all_toward_light);
        std::vector<double> reference;
        for (const Ray& ray : rays) {
            Pcg32 rng(1, 1);
            VolumeCounters counters;
            reference.push_back(estimate_transmittance(media, ray, Estimator::March,
                                                       media.smallest_voxel_m() / 64.0f, rng,
                                                       counters)
                                    .g);
        }
        const size_t k = estimators.size();
        std::vector<std::vector<double>> variance(k), seconds(k), lookups(k);
        std::vector<std::vector<double>> means(k, std::vector<double>(rays.size(), 0.0));
        std::vector<std::vector<double>> variances = means;
        for (int rep = 0; rep < repeats; ++rep)
            for (size_t j = 0; j < k; ++j) {
                // Alternate the order so no estimator always runs first (cache, clock).
                const size_t e = rep % 2 == 0 ? j : k - 1 - j;
                const Run r = run(media, rays, estimators[e], step, samples, 1000 + rep);
                variance[e].push_back(r.variance);
                seconds[e].push_back(r.seconds);
                lookups[e].push_back(r.lookups);
                for (size_t i = 0; i < rays.size(); ++i) {
                    means[e][i] += r.means[i] / repeats;
                    variances[e][i] += r.variances[i] / repeats;
                }
            }
        std::vector<double> efficiency(k);
        for (size_t e = 0; e < k; ++e)
            efficiency[e] = 1.0 / (median(variance[e]) * median(seconds[e]));
        double mean_t = 0.0;
        for (double m : means[0])
            mean_t += m / static_cast<double>(rays.size());
        std::printf(
            "# %s: %zu shadow rays from inside the media, %d estimates per ray, %d "
            "alternating repeats, medians; mean T %.4f\n",
            argv[1], rays.size(), samples, repeats, mean_t);
        for (size_t e = 0; e < k; ++e) {
            // Against the 1/64-voxel march (deterministic up to its O(h²) error): the largest
            // per-ray gap in the estimator's own standard errors (rays where it varied), and
            // the relative gap of the sums over all rays with its standard error. A tracker's
            // estimates of T ~ 1e-4 are heavy-tailed (mostly 0), so its sample variance can
            // understate its error on such rays; the sums are the robust check.
            double largest_z = 0.0, gap = 0.0, gap_var = 0.0, ref_sum = 0.0;
            const double n = static_cast<double>(samples) * repeats;
            for (size_t i = 0; i < rays.size(); ++i) {
                const double d = means[e][i] - reference[i];
                gap += d;
                gap_var += variances[e][i] / n;
                ref_sum += reference[i];
                if (variances[e][i] > 0.0)
                    largest_z = std::max(largest_z, std::abs(d) / std::sqrt(variances[e][i] / n));
            }
            const double relative_gap = gap / ref_sum,
                         relative_gap_se = std::sqrt(gap_var) / ref_sum;
            std::printf(
                "{\"estimator\": \"%s\", \"variance\": %.6g, \"cpu_seconds_per_estimate\": %.6g, "
                "\"lookups_per_estimate\": %.4g, \"efficiency\": %.6g, \"efficiency_ratio\": "
                "%.4g, \"largest_gap_z\": %.3g, \"relative_gap\": %.2e, \"relative_gap_se\": "
                "%.2e}\n",
                estimators[e].name.c_str(), median(variance[e]), median(seconds[e]),
                median(lookups[e]), efficiency[e], efficiency[e] / efficiency[0], largest_z,
                relative_gap, relative_gap_se);
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "transmittance_bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
