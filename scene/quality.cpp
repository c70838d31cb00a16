#include "scene/quality.h"

#include "core/error.h"
#include "volume/medium.h"
#include "volume/transmittance.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace kasumi {

namespace {

// The quality table. Every sampling value comes from the studies that bench/studies.sh runs
// and docs/study.md reports (docs/studies/<name>/study.csv; 96x54 or 160x90 pixels, measured
// 2026-11-29/30 on the shared 2-core machine); the expected errors are the relative MSE
// measured there. Final (64 spp): the 16-spp figure divided by 4 where the study showed the
// relative MSE falling as 1/spp for these unbiased settings (fog: 0.00515 -> 0.00134 from 4 to
// 16 spp; cloud: 0.215 -> 0.0358), not for soft shadows (below).
// Reference: the studies' own references have these settings, and their standard error was
// measured from two independent halves (the cloud's at 512 spp, doubled for 256).
// - fog_step_m, fog study (docs/studies/fog): the march of homogeneous fog is unbiased, the
//   step only trades variance for time, and the coarse step buys the most accuracy per
//   second at every spp (efficiency at 16 spp: 234 /s at 1.6 m, 190 at 0.8, 129 at 0.4, 80 at
//   0.2; at 1 spp 319 / 316 / 213 / 120), so draft, default and final all take 1.6 m and buy
//   accuracy with spp. (Final had 0.8 m until 2026-11-30: 31% less error per render for 1.8x
//   the time, less efficient than 1.6 m, against the study.) Reference: 0.2 m, the study's own
//   reference setting.
// - grid_estimator, cloud estimator study (docs/studies/cloud-estimator): ratio tracking has
//   the lowest error and the best efficiency at 16 spp (59 /s; residual ratio 39, delta 34,
//   march 1.9). In multiple scattering unbiased-march lost (cloud.json 96x54, 2026-12-04:
//   efficiency 74 / 105 / 139 /s at 4 / 16 / 64 spp against residual ratio's 149 / 143 / 204;
//   docs/volumes.md), so grid_estimator stays ratio.
// - grid_single_estimator: where the level chooses single scattering for a cloud (draft
//   always), every camera sample is a shadow ray through it, and unbiased-march won at every
//   spp of the cloud.json single-scattering studies (96x54, reference 4096 spp, 2026-12-04):
//   efficiency 844 /s at 4 spp against 295 ratio and 357 residual ratio; 1350 against 133
//   (residual ratio) at 16; 672 against 134 at 64; 115 against 84 (ratio) at 256. On the WDAS
//   cloud (single scattering, 96x54) the win is smaller: 1070 against 918 (ratio) at 4 spp,
//   1800 against 1020 at 16.
// - light_samples: in fog (soft-shadow study, docs/studies/soft-shadows) the march dominates
//   the time, and 4 shadow samples per light cut the error 5-15% against 1 for no measurable
//   time (4 spp: 1 sample 1.84 s, 0.0080; 4 samples 1.79 s, 0.0069); 16 cost 30% more time
//   for ~3%. Without fog (area-samples study, docs/studies/area-samples) the shadow rays are
//   the cost, and a sample spent on the pixel buys more than one spent on the light (1 sample
//   at 16 spp: 0.85 s, 0.0035; 4 samples at 4 spp: 0.47 s, 0.0124; efficiency 331 vs 173 /s),
//   but 4 samples stay on that study's Pareto front at every spp. Draft keeps 1 (its cheapest
//   render), default and final 4 (the fog scene's choice, still Pareto-optimal without fog).
// - Shadow method: not set by any level. The shadow studies (docs/studies/shadows,
//   area-shadows) put ray-traced shadows on the Pareto front at every spp and sample count;
//   shadow maps cost 1.1-100x the time (their build) for equal or larger error at these sizes.
// - spp: 4 / 16 / 64 / 256; the single-scattering tolerances are the left-out light each level
//   accepts (a policy; the cloud-scattering study measured single scattering 22% darker than
//   multiple on cloud.json).
// - shadow_rel_mse of final: the soft-shadow study's 16-spp figure (0.0073) is kept, not
//   divided by 4: on soft_shadows.json the relative MSE did not fall from 4 to 16 spp (0.0069
//   -> 0.0073, held up by a few outlier pixels while the RMSE halved), so 1/spp is not
//   supported there.
// - Height fog (docs/studies/fog-height*, data/scenes/fog_height.json, 2026-11-30): the march
//   of a lone height fog is unbiased at any step (volume_path.cpp, march_single_height_fog) and
//   4 m is the most efficient step at every spp (efficiency at 1 / 4 / 16 spp: 1.8e4 / 2.1e4 /
//   1.5e4 /s at 4 m; 1.6e4 / 1.0e4 / 1.2e4 at 16 m; 6.3e3 / 7.5e3 / 5.4e3 at 1 m), so draft,
//   default and final take 4 m, reference 1 m (the study's reference). Estimator: march, the
//   most efficient in single scattering (4 m at 16 spp: 1.2e4 /s against 79 for residual
//   ratio, 66 delta, 65 ratio: the trackers gather light at one free-flight point per path)
//   and in multiple scattering, where it means the closed-form transmittance for next-event
//   estimation (16 spp: 70 /s against 35 residual ratio, 39 delta, 35 ratio). Expected errors:
//   draft renders fog_height.json with single scattering (tolerance any), 2.4e-4 at 4 spp
//   against the single-scattering answer (the plan's bound states what it leaves out); the
//   other levels choose multiple scattering there: 0.088 at 16 spp, /4 at 64 (1.37 / 0.337 /
//   0.088 at 1 / 4 / 16 spp: 1/spp), and 1.37 / 256 for reference.
// - grid_noise_threshold (film.noise_threshold with VDB media; adaptive sampling): final sets
//   0.1 where its own 64 spp is used, with the neighbourhood pilot rule (film.noise_window 2,
//   the default), which has no early-stop bias (render/adaptive_sampling.h). Study
//   (docs/studies/cloud-ms-adaptive*, 2026-12-05): 64 spp, 96x54, seeds 1-4, the levels'
//   cloud sampling (ratio, shadow roulette 0.05, first flight),
//   references at 2048 spp (cumulus 1024) of another seed; cost in instructions of the whole
//   process (callgrind, seed 1, one thread). Efficiency 1/(rel. MSE x instructions) against
//   uniform 64 spp: cloud.json 1.24x (rel. MSE 0.0112 -> 0.0122, 1704 -> 1263 M), 256³ cumulus
//   1.27x (0.0143 -> 0.0149, 1709 -> 1290 M), WDAS 1.18x (0.0119 -> 0.0122, 2146 -> 1775 M);
//   the mean luminance of each seed within 0.04% of the uniform render of the same seed. The
//   pixel's own rule (window 0) looked more efficient (1.28-1.41x) but moved the mean
//   luminance by -0.4% (cloud.json) and -2.2% (WDAS): biased, not used. The expected cloud
//   error of final is the study's 0.0122 (cloud.json, 64 spp, threshold 0.1). Draft (4 spp)
//   and default (16) leave it off: their spp is at most film.min_spp (16), where no pixel can
//   stop early. A scene that gives film.spp keeps uniform sampling (the threshold was measured
//   at 64 spp only; at 256 spp the old rule lost, docs/volumes.md).
// - grid_shadow_roulette and grid_camera_transmittance, multiple scattering in VDB media
//   (docs/studies/cloud-ms-sampling*, 2026-12-05; estimator ratio, 16 spp, seeds 1-4, against
//   a 1024-spp (4096 for cloud.json) reference of today's settings; cost in instructions of
//   the whole process by callgrind, one thread, because the machine's load made the wall
//   times of the study noisy): efficiency 1/(rel. MSE x instructions) against walk without
//   roulette, for first_flight / shadow_roulette 0.05 / both:
//   cloud.json 1.17x / 1.40x / 1.47x (rel. MSE 0.0474 -> 0.0416, 567 -> 439 M instructions),
//   WDAS 1.32x / 1.33x / 1.49x (0.1004 -> 0.0944, 1015 -> 727 M), the 256³ cumulus 0.91x /
//   0.94x / 0.93x (0.0429 -> 0.0551, 588 -> 491 M: its finer rim adds the first flight's
//   T(1 - T) L² variance). Both win 1.5x on two of the three clouds and lose 7% on the third,
//   so draft, default and final take both; reference keeps today's estimators. The expected
//   cloud error of default is the study's (0.0416 at 16 spp; final's: grid_noise_threshold, above,
//   with adaptive sampling).
// - render.volume.free_flight (decomposition tracking) and nee_roulette: no level sets them.
//   cloud.json, multiple scattering, 16 spp, six seeds (docs/volumes.md, decomposition
//   tracking, 2026-12-04): efficiency 38 /s today against 43 decomposition, 42 nee_roulette, 45
//   both (1.13x / 1.12x / 1.18x, within the seeds' spread); on the 256³ cumulus and the WDAS
//   cloud the single studies disagree in order (48 / 42 / 49 / 71 and 8.4 / 12.6 / 17.2 / 15.7
//   at load 15-19): no win at equal error on all three clouds.
constexpr QualityPreset kTable[] = {
    {QualityLevel::Draft, 4, 1.6, "ratio", 1, INFINITY, 0.00515, 0.215, 0.008, 4.0, "march",
     0.000244, "unbiased-march", 0.05f, CameraTransmittance::FirstFlight, 0.0},
    {QualityLevel::Default, 16, 1.6, "ratio", 4, 0.1, 0.00134, 0.0416, 0.0073, 4.0, "march", 0.088,
     "unbiased-march", 0.05f, CameraTransmittance::FirstFlight, 0.0},
    {QualityLevel::Final, 64, 1.6, "ratio", 4, 0.02, 0.000335, 0.0122, 0.0073, 4.0, "march", 0.022,
     "unbiased-march", 0.05f, CameraTransmittance::FirstFlight, 0.1},
    {QualityLevel::Reference, 256, 0.2, "ratio", 16, 0.0, 8.9e-5, 0.0028, 0.00023, 1.0, "march",
     0.0054, "unbiased-march", 0.0f, CameraTransmittance::Walk, 0.0},
};

bool is_extended_light(const Json& light) {
    if (!light.is_object() || !light.contains("type") || !light["type"].is_string())
        return false;
    const std::string type = light["type"].get<std::string>();
    return type == "line" || type == "polygon" || type == "sphere";
}

std::string medium_type(const Json& medium) {
    if (medium.is_object() && medium.contains("type") && medium["type"].is_string())
        return medium["type"].get<std::string>();
    return "";
}

std::string g3(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", v);
    return buf;
}

/// Sets `pointer` to `value` unless the document has it; records which. Missing objects along
/// the way (render/volume, film) are created; a parent that is not an object is left for the
/// loader to report.
void fill(SceneDocument& doc, const std::string& pointer, const Json& value,
          QualityChoice& choice) {
    if (doc.contains(pointer)) {
        choice.kept.push_back(pointer);
        return;
    }
    const Json* parent = doc.find(pointer.substr(0, pointer.rfind('/')));
    if (parent != nullptr && !parent->is_object())
        return;
    doc.set(pointer, value);
    choice.applied.push_back(pointer + " = " + value.dump());
}

}  // namespace

std::optional<QualityLevel> quality_from_name(const std::string& name) {
    for (const QualityPreset& p : kTable) {
        if (name == quality_name(p.level))
            return p.level;
    }
    return std::nullopt;
}

const char* quality_name(QualityLevel level) {
    switch (level) {
        case QualityLevel::Draft:
            return "draft";
        case QualityLevel::Default:
            return "default";
        case QualityLevel::Final:
            return "final";
        case QualityLevel::Reference:
            return "reference";
    }
    return "default";
}

const QualityPreset& quality_preset(QualityLevel level) {
    return kTable[static_cast<int>(level)];
}

QualityChoice apply_quality(SceneDocument& doc) {
    QualityChoice choice;
    if (!doc.json().is_object() || !doc.contains("/render/quality"))
        return choice;
    const Json& q = doc.get("/render/quality");
    std::optional<QualityLevel> level;
    if (q.is_string())
        level = quality_from_name(q.get<std::string>());
    if (!level) {
        throw_input_error(doc.file() + ": /render/quality = " + q.dump() +
                          ": expected \"draft\", \"default\", \"final\" or \"reference\"");
    }
    choice.level = level;
    const QualityPreset& preset = quality_preset(*level);
    const bool level_spp = !doc.contains("/film/spp");
    fill(doc, "/film/spp", preset.spp, choice);

    bool homogeneous = false, grid = false, height_fog = false;
    const Json* media = doc.find("/media");
    if (media != nullptr && media->is_array()) {
        for (const Json& m : *media) {
            homogeneous = homogeneous || medium_type(m) == "homogeneous";
            grid = grid || medium_type(m) == "vdb";
            height_fog = height_fog || medium_type(m) == "height_fog";
        }
    }
    if (homogeneous)
        fill(doc, "/render/volume/step_m", preset.fog_step_m, choice);
    else if (height_fog)
        fill(doc, "/render/volume/step_m", preset.height_fog_step_m, choice);
    if (grid)
        fill(doc, "/render/volume/estimator", preset.grid_estimator, choice);
    else if (height_fog)
        fill(doc, "/render/volume/estimator", preset.height_fog_estimator, choice);
    if (grid && level_spp && preset.grid_noise_threshold > 0.0)
        fill(doc, "/film/noise_threshold", preset.grid_noise_threshold, choice);
    bool extended = false;
    const Json* lights = doc.find("/lights");
    if (lights != nullptr && lights->is_array()) {
        const size_t count = lights->size();
        for (size_t i = 0; i < count; ++i) {
            if (is_extended_light(doc.get("/lights/" + std::to_string(i)))) {
                extended = true;
                fill(doc, "/lights/" + std::to_string(i) + "/samples", preset.light_samples,
                     choice);
            }
        }
    }

    // The studies' figure for each kind of content the scene holds.
    std::string expected;
    auto add = [&](const char* what, double rel_mse) {
        if (rel_mse > 0.0)
            expected += (expected.empty() ? "" : ", ") + std::string(what) + " " + g3(rel_mse);
    };
    if (homogeneous)
        add("fog", preset.fog_rel_mse);
    if (grid)
        add("cloud", preset.cloud_rel_mse);
    if (height_fog)
        add("height fog", preset.height_fog_rel_mse);
    if (extended)
        add("soft shadows", preset.shadow_rel_mse);
    choice.expected_error =
        expected.empty() ? "no study covers this scene's content"
                         : "relative MSE measured by the studies at these settings: " + expected +
                               " (docs/study.md; more where the scene's own spp or steps are "
                               "coarser)";
    return choice;
}

ScatteringBound scattering_bound(const std::vector<Medium>& media) {
    ScatteringBound b;
    for (const Medium& m : media) {
        Rgb sigma_t_max{0.0f}, sigma_s_max{0.0f};
        Bounds3 box;
        bool bounded = true;
        if (const auto* h = std::get_if<HomogeneousMedium>(&m.model)) {
            sigma_t_max = h->sigma_t();
            sigma_s_max = h->sigma_s;
            bounded = h->bounds.has_value();
            if (bounded)
                box = *h->bounds;
        } else if (const auto* v = std::get_if<VdbMedium>(&m.model)) {
            const float d = v->grid ? v->grid->max_density() : 0.0f;
            sigma_t_max = v->sigma_t_per_density() * d;
            sigma_s_max = v->sigma_s_per_density * d;
            box = v->bounds_world;
        } else if (const auto* f = std::get_if<HeightFogMedium>(&m.model)) {
            // The box's mean extinction: the mean of exp(-(y - h0) / H) over its height,
            // H (e^{-a_min} - e^{-a_max}) / (y_max - y_min), in closed form.
            bounded = f->bounds.has_value();
            double mean = 1.0;
            if (bounded) {
                box = *f->bounds;
                const double a0 = (box.min.y - f->reference_height_m) / f->scale_height_m;
                const double da = (double(box.max.y) - box.min.y) / f->scale_height_m;
                mean = std::exp(-a0) * one_minus_exp_over(da);
            }
            sigma_t_max = f->sigma_t() * static_cast<float>(mean);
            sigma_s_max = f->sigma_s * static_cast<float>(mean);
        }
        for (int c = 0; c < 3; ++c) {
            if (sigma_t_max[c] > 0.0f) {
                b.albedo = std::max(b.albedo, double(sigma_s_max[c]) / sigma_t_max[c]);
                b.scatters = b.scatters || sigma_s_max[c] > 0.0f;
            }
        }
        const double sigma = max_component(sigma_t_max);
        if (!bounded) {
            b.optical_depth = sigma > 0.0 ? INFINITY : b.optical_depth;
            continue;
        }
        const Vec3 e = box.max - box.min;
        const double volume = double(e.x) * e.y * e.z;
        const double surface = 2.0 * (double(e.x) * e.y + double(e.y) * e.z + double(e.z) * e.x);
        const double chord = surface > 0.0 ? 4.0 * volume / surface : 0.0;
        b.optical_depth += sigma * chord;
    }
    const double p = 1.0 - std::exp(-b.optical_depth);
    const double x = b.albedo * p;
    b.bound = x < 1.0 ? x / (1.0 - x) : INFINITY;
    return b;
}

std::string scattering_bound_text(const ScatteringBound& b) {
    const std::string left_out =
        std::isinf(b.bound) ? "an unbounded amount of the single-scattered light"
        : b.bound >= 1.0    ? "at most " + g3(b.bound) + " times the single-scattered light"
                            : "at most " + g3(100.0 * b.bound) + "% of the single-scattered light";
    return "albedo " + g3(b.albedo) + ", optical thickness " + g3(b.optical_depth) +
           " (mean chord): single scattering leaves out " + left_out +
           " (bound omega p / (1 - omega p), p = 1 - exp(-tau))";
}

namespace {

/// With multiple scattering in VDB media: the level's shadow roulette and camera
/// transmittance where the scene leaves them unset.
void choose_multiple_scattering_sampling(const SceneDocument& doc, const QualityPreset& preset,
                                         VolumeSettings& volume, QualityChoice& choice) {
    const char* roulette = "/render/volume/shadow_roulette";
    if (doc.contains(roulette)) {
        choice.kept.push_back(roulette);
    } else if (preset.grid_shadow_roulette > 0.0f) {
        volume.shadow_roulette = preset.grid_shadow_roulette;
        choice.applied.push_back(std::string(roulette) + " = " + g3(preset.grid_shadow_roulette) +
                                 " (multiple scattering)");
    }
    const char* camera_t = "/render/volume/camera_transmittance";
    if (doc.contains(camera_t)) {
        choice.kept.push_back(camera_t);
    } else if (preset.grid_camera_transmittance == CameraTransmittance::FirstFlight) {
        volume.camera_transmittance = CameraTransmittance::FirstFlight;
        choice.applied.push_back(std::string(camera_t) +
                                 " = \"first_flight\" (multiple scattering)");
    }
}

}  // namespace

void choose_integrator(const SceneDocument& doc, const std::vector<Medium>& media,
                       VolumeSettings& volume, QualityChoice& choice) {
    if (!choice.level)
        return;
    const QualityPreset& preset = quality_preset(*choice.level);
    const bool grid = std::any_of(media.begin(), media.end(), [](const Medium& m) {
        return std::holds_alternative<VdbMedium>(m.model);
    });
    if (doc.contains("/render/volume/integrator")) {
        choice.integrator = "render.volume.integrator given by the scene";
        if (grid && volume.integrator == VolumeIntegrator::Multiple)
            choose_multiple_scattering_sampling(doc, preset, volume, choice);
        return;
    }
    const ScatteringBound b = scattering_bound(media);
    if (!b.scatters) {
        choice.integrator = "media do not scatter";
        return;
    }
    const double tolerance = preset.single_scattering_tolerance;
    const bool single = b.bound <= tolerance;
    volume.integrator = single ? VolumeIntegrator::Single : VolumeIntegrator::Multiple;
    choice.integrator = std::string(single ? "single" : "multiple") + " scattering chosen by " +
                        quality_name(*choice.level) + " (tolerance " +
                        (std::isinf(tolerance) ? std::string("any") : g3(100.0 * tolerance) + "%") +
                        "): " + scattering_bound_text(b);
    if (grid && !single)
        choose_multiple_scattering_sampling(doc, preset, volume, choice);
    const auto applied = std::find_if(
        choice.applied.begin(), choice.applied.end(),
        [](const std::string& a) { return a.rfind("/render/volume/estimator = ", 0) == 0; });
    const auto estimator = estimator_from_name(preset.grid_single_estimator);
    if (single && grid && applied != choice.applied.end() && estimator) {
        volume.estimator = *estimator;
        *applied = std::string("/render/volume/estimator = \"") + estimator_name(*estimator) +
                   "\" (with single scattering)";
    }
}

}  // namespace kasumi
