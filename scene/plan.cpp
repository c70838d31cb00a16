#include "scene/plan.h"

#include "scene/gi_plan.h"
#include "scene/quality_plan.h"
#include "surface/emitter_hit.h"
#include "surface/shadows/shadow_map.h"
#include "volume/medium_set.h"
#include "volume/scattered_direct.h"
#include "volume/transmittance.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

namespace kasumi {

namespace {

bool any_ambient_material(const SceneDesc& scene) {
    for (const Material& m : scene.materials) {
        const auto* phong = std::get_if<PhongMaterial>(&m);
        if (phong != nullptr && max_component(phong->ka) > 0.0f)
            return true;
    }
    return false;
}

std::string count(size_t n, const char* what) {
    return std::to_string(n) + " " + what + (n == 1 ? "" : "s");
}

std::string media_summary(const SceneDesc& scene) {
    size_t grids = 0, fogs = 0;
    for (const Medium& m : scene.media) {
        grids += std::holds_alternative<VdbMedium>(m.model) ? 1 : 0;
        fogs += std::holds_alternative<HeightFogMedium>(m.model) ? 1 : 0;
    }
    const size_t boxes = scene.media.size() - grids - fogs;
    std::string text;
    if (boxes > 0)
        text = count(boxes, "homogeneous medium");
    if (fogs > 0)
        text += (text.empty() ? "" : " + ") + count(fogs, "height fog") +
                " (closed-form optical depth; e-fold majorant segments)";
    if (grids > 0)
        text += (text.empty() ? "" : " + ") + count(grids, "VDB grid");
    return text;
}

std::string estimator_summary(const SceneDesc& scene) {
    const VolumeSettings& volume = scene.render.volume;
    const bool homogeneous = MediumSet(scene.media).all_homogeneous();
    std::string text = std::string("estimator ") + estimator_name(volume.estimator) +
                       (volume.estimator_given ? "" : " (default for these media)");
    switch (volume.estimator) {
        case Estimator::March:
            text += homogeneous ? ", exact Beer-Lambert per stretch"
                                : ", trapezoid rule, jittered fixed step (biased)";
            break;
        case Estimator::Delta:
            text += ", delta tracking (unbiased, 0 or 1)";
            break;
        case Estimator::Ratio:
            text += ", ratio tracking (unbiased)";
            break;
        case Estimator::ResidualRatio:
            text += ", residual ratio tracking against the minorant (unbiased)";
            break;
        case Estimator::DebiasedMarch:
        case Estimator::UnbiasedMarch:
            text += homogeneous ? ", exact Beer-Lambert per stretch"
                                : ", debiased jittered march against the minorant (unbiased, "
                                  "signed single estimates)";
            break;
    }
    const bool grids = std::any_of(scene.media.begin(), scene.media.end(), [](const Medium& m) {
        return std::holds_alternative<VdbMedium>(m.model);
    });
    if (grids)
        text += "; per-brick majorants, DDA skips empty bricks";
    return text;
}

std::string format_g(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", x);
    return text;
}

std::string join(const std::vector<std::string>& items) {
    std::string text;
    for (const std::string& item : items)
        text += (text.empty() ? "" : "; ") + item;
    return text;
}

/// Soft shadows, shadow maps, shadow volumes, Whitted recursion and lights seen directly.
void add_shadow_stages(const SceneDesc& scene, Plan& plan) {
    const bool shadows_on = !scene.shapes.empty() && scene.render.shadows;
    const char* why_off =
        scene.shapes.empty() ? "no shapes can cast shadows" : "render.shadows is false";
    std::vector<std::string> soft, maps, volumes, object_space, scanline;
    for (const Light& light : scene.lights) {
        if (!is_delta(light) && light.shadows == ShadowMode::Ray)
            soft.push_back(light.name + ": " + std::to_string(light.samples) + " shadow rays" +
                           (light.shadow_probes > 0 && light.shadow_probes < light.samples
                                ? ", stopping after " + std::to_string(light.shadow_probes) +
                                      " probes that agree (biased)"
                                : "") +
                           (light.outline_probes > 0
                                ? ", " + std::to_string(light.outline_probes) +
                                      " outline probes decide lit and umbra points (biased, "
                                      "bounded)"
                                : "") +
                           (light.exact_penumbra
                                ? ", exact penumbra against spheres, boxes and quads where the "
                                  "closed form applies (sampled elsewhere)"
                                : ""));
        if (light.shadows == ShadowMode::Map)
            maps.push_back(light.name + ": " + describe_shadow_maps(light));
        if (light.shadows == ShadowMode::ShadowVolume)
            volumes.push_back(light.name);
        if (light.shadows == ShadowMode::ObjectSpace)
            object_space.push_back(light.name);
        if (light.shadows == ShadowMode::Scanline)
            scanline.push_back(light.name);
    }
    plan.stages.push_back(
        {"soft-shadows", shadows_on && !soft.empty(),
         !shadows_on    ? why_off
         : soft.empty() ? "no line, polygon or sphere light with \"shadows\": \"ray\""
                        : "extended lights sampled per shading point, ratio estimator (analytic "
                          "illuminance times visible fraction): " +
                              join(soft)});
    plan.shadow_maps = shadows_on && !maps.empty();
    plan.stages.push_back(
        {"shadow-maps", plan.shadow_maps,
         !shadows_on    ? why_off
         : maps.empty() ? "no light has \"shadows\": \"map\""
                        : "depth rendered from the light by ray casting once per render, before "
                          "the first pixel; bias + slope-scaled bias, PCF: " +
                              join(maps)});
    plan.shadow_volumes = shadows_on && !volumes.empty();
    plan.stages.push_back(
        {"shadow-volumes", plan.shadow_volumes,
         !shadows_on       ? why_off
         : volumes.empty() ? "no light has \"shadows\": \"shadow-volume\""
                           : "silhouette edges of boxes, quads and meshes extruded from the light "
                             "(along its direction for a directional light), closed by caps; "
                             "depth-fail counting by ray casting (spheres: shadow rays): " +
                                 join(volumes)});
    plan.object_space_shadows = shadows_on && !object_space.empty();
    plan.stages.push_back(
        {"object-space-shadows", plan.object_space_shadows,
         !shadows_on ? why_off
         : object_space.empty()
             ? "no light has \"shadows\": \"object-space\""
             : "pass 1 from the light clips every box, quad and mesh triangle against the "
               "united shadows of the polygons in front of it (Weiler-Atherton) into lit and "
               "shadowed detail polygons (cached while "
               "light and geometry stay); pass 2 finds the detail polygon under each visible "
               "point, no shadow ray (spheres are not tessellated: they receive and cast by "
               "shadow rays): " +
                   join(object_space)});
    plan.scanline_shadows = shadows_on && !scanline.empty();
    plan.stages.push_back(
        {"scanline-shadows", plan.scanline_shadows,
         !shadows_on ? why_off
         : scanline.empty()
             ? "no light has \"shadows\": \"scanline\""
             : std::string("one scanline pass per light at ") + std::to_string(scene.film.width) +
                   "x" + std::to_string(scene.film.height) +
                   " through the pixel centres (spans, depth along the scanline, the faces "
                   "between each visible span and the light projected onto its plane: shadowed "
                   "sub-spans, Bouknight & Kelley 1970); a camera hit at a pixel centre on the "
                   "pass's visible face takes its answer (plus shadow rays against spheres); "
                   "shadow rays for the rest: " +
                   (scene.film.jitter ? "jittered camera samples (film.jitter is on: nearly "
                                        "every sample), "
                                      : "") +
                   "secondary rays (reflection, refraction, GI, media), points on spheres: " +
                   join(scanline)});
    bool specular = false;
    for (const Shape& shape : scene.shapes) {
        const Material& m = scene.materials[shape.material];
        specular = specular || std::holds_alternative<MirrorMaterial>(m) ||
                   std::holds_alternative<DielectricMaterial>(m);
    }
    const WhittedSettings& whitted = scene.render.whitted;
    plan.stages.push_back(
        {"whitted", specular,
         specular ? "mirror/dielectric surfaces: reflected and refracted rays (exact Fresnel), "
                    "max_depth " +
                        std::to_string(whitted.max_depth) + ", min_weight " +
                        format_g(whitted.min_weight)
                  : "no mirror or dielectric surface: no secondary rays"});
    plan.visible_lights = has_visible_emitters(scene.lights);
    plan.stages.push_back(
        {"visible-lights", plan.visible_lights,
         plan.visible_lights
             ? "polygon and sphere lights seen by camera and Whitted rays with their luminance "
               "(point, spot, goniometric, directional and line lights are invisible)"
             : "no polygon or sphere light (point-like, directional and line lights are "
               "invisible)"});
}

/// Light shafts in the atmosphere (render/sky_shafts.h).
PlanStage sky_shafts_plan_stage(const SceneDesc& scene, const Plan& plan) {
    const SkySettings& sky = scene.sky->settings;
    if (!sky.shafts)
        return {"sky-shafts", false,
                "render.sky.shafts is false: the air is lit by the sun everywhere (no light "
                "shafts)"};
    std::vector<std::string> casters;
    if (plan.shadow_rays)
        casters.push_back("surfaces (one shadow ray per node)");
    if (plan.volume)
        casters.push_back(std::string("media (") + estimator_name(scene.render.volume.estimator) +
                          " transmittance toward the sun)");
    if (casters.empty())
        return {"sky-shafts", false,
                "render.sky.shafts is true but nothing can shadow the air (no shapes casting "
                "shadows, no media)"};
    return {"sky-shafts", true,
            "single-scattered sunlight of the air hidden by " + casters.front() +
                (casters.size() > 1 ? " and " + casters.back() : std::string()) +
                " subtracted over the first " + format_g(sky.shaft_distance_m) +
                " m of camera rays, " + std::to_string(sky.shaft_samples) +
                " jittered strata; multiply scattered sky light unshadowed"};
}

}  // namespace

namespace {

/// The adaptive-sampling stage: on when film.noise_threshold > 0, with its criterion.
PlanStage adaptive_sampling_plan_stage(const FilmDesc& film) {
    if (!(film.noise_threshold > 0.0f))
        return {"adaptive-sampling", false,
                "film.noise_threshold is 0: every pixel takes " + std::to_string(film.spp) +
                    " samples"};
    std::ostringstream reason;
    reason << "film.noise_threshold " << film.noise_threshold;
    if (film.noise_window > 0)
        reason << ", noise_window " << film.noise_window << ": after a pilot of "
               << std::min(film.min_spp, film.spp) << " samples a pixel takes the count (up to "
               << film.spp << ") at which its standard error is that fraction of the mean (or of "
               << film.noise_floor_cd_m2
               << " cd/m2), the variance and mean from the pilots of its neighbours within "
               << film.noise_window
               << " pixels in the tile, itself left out (no early-stop bias); samples.count AOV";
    else
        reason << ", noise_window 0: a pixel stops when the standard error of its own mean "
                  "luminance is below that fraction of the mean (or of "
               << film.noise_floor_cd_m2 << " cd/m2), after " << std::min(film.min_spp, film.spp)
               << " to " << film.spp
               << " samples (biased where pixels have heavy tails); samples.count AOV";
    return {"adaptive-sampling", true, reason.str()};
}

/// The denoise stage (film.denoise, render/denoise/nlm_filter.h): on when asked for and every
/// pixel has at least 2 samples in each half buffer.
PlanStage denoise_plan_stage(const FilmDesc& film) {
    const DenoiseSettings& d = film.denoise;
    if (!d.enabled)
        return {"denoise", false, "film.denoise is \"off\": the beauty is the raw sample mean"};
    const int fewest = film.noise_threshold > 0.0f ? std::min(film.min_spp, film.spp) : film.spp;
    std::ostringstream reason;
    reason << "non-local means cross-filtered between even and odd samples (Rousselle et al. "
              "2012), window "
           << 2 * d.radius + 1 << "x" << 2 * d.radius + 1 << ", patch " << 2 * d.patch + 1 << "x"
           << 2 * d.patch + 1 << ", k " << d.k << ", transmittance feature k " << d.k_feature
           << "; bias <~ 0.86 k standard errors of a half's mean; raw beauty in noisy.R/G/B";
    if (d.select)
        reason << "; select: per pixel the raw mean or the filter at 1, 2 or 4 times k and "
                  "k_feature, whichever has the least SURE estimate of the error over 7x7 pixels "
                  "(bias up to that of 4 k)";
    if (fewest < 4)
        reason << "; pixels of fewer than 4 samples (here " << fewest
               << ") have no variance estimate in a half and stay raw";
    return {"denoise", true, reason.str()};
}

}  // namespace

namespace {

/// How the path tracer samples free flights (render.volume.spectral_mis, used only for
/// chromatic, non-emitting media; render.volume.free_flight; volume/scattered_paths.cpp).
std::string flight_summary(const SceneDesc& scene) {
    const MediumSet media(scene.media);
    const bool decomposition = scene.render.volume.free_flight == FreeFlightSampling::Decomposition;
    std::string tracking = "spectral (delta) tracking";
    if (decomposition) {
        tracking = media.emits() ? tracking + " (free_flight decomposition: media emit)"
                                 : "decomposition tracking (Kutz et al. 2017; the per-brick "
                                   "minorant's collisions drawn without lookups)";
        if (scene.render.volume.nee_points > 0)
            tracking += " past a roulette stop; the tracked walk (nee_points) draws the rest";
    }
    if (!scene.render.volume.spectral_mis)
        return tracking;
    if (media.grey_extinction())
        return tracking + " (spectral_mis: extinction is grey)";
    if (media.emits())
        return tracking + " (spectral_mis: media emit)";
    return "spectral MIS (Miller, Georgiev & Jarosz 2019; one-sample balance heuristic over "
           "hero channels)";
}

/// render.surface "scanline": the camera's visible surfaces from a scanline renderer of the
/// shapes' triangles (surface/scanline/scanline_surface.h).
void add_scanline_surface_stage(const SceneDesc& scene, Plan& plan) {
    const bool wanted = scene.render.surface == SurfaceMethod::Scanline;
    size_t polygons = 0, spheres = 0;
    for (const Shape& shape : scene.shapes) {
        if (std::holds_alternative<SphereShape>(shape.geometry))
            ++spheres;
        else if (std::holds_alternative<QuadShape>(shape.geometry))
            polygons += 2;
        else if (std::holds_alternative<BoxShape>(shape.geometry))
            polygons += 12;
        else if (const auto* mesh = std::get_if<MeshShape>(&shape.geometry))
            polygons += mesh->mesh.triangles.size();
    }
    plan.scanline_surface = wanted && plan.surfaces;
    plan.stages.push_back(
        {"scanline-surface", plan.scanline_surface,
         !wanted ? "render.surface is \"ray\": primary rays through Embree"
         : !plan.surfaces
             ? "no shapes to draw"
             : "surface: scanline renderer (Bouknight & Kelley 1970), " +
                   count(polygons, "polygon") +
                   " (edge table by first scanline, active edge list, a span per "
                   "polygon, depth per span segment) at the pixel centres of " +
                   std::to_string(scene.film.width) + "x" + std::to_string(scene.film.height) +
                   "; position, normal and uv perspective-correct along the span; " +
                   (spheres > 0
                        ? count(spheres, "sphere") + " ray-cast per pixel and depth-resolved "
                                                     "against the scanline face"
                        : std::string("no spheres")) +
                   "; Whitted, GI and shadow rays secondary through Embree"});
}

}  // namespace

namespace {

/// Russian roulette and splitting of the paths (render.volume.splitting; volume/weight_window.h).
std::string path_roulette_summary(const VolumeSettings& volume) {
    if (volume.splitting == PathSplitting::Off)
        return ", Russian roulette from the third scattering";
    const std::string name = volume.splitting == PathSplitting::Sun ? "sun" : "guided";
    if (volume.nee_points > 0)
        return ", Russian roulette from the third scattering (splitting \"" + name +
               "\": not with nee_points)";
    if (volume.splitting == PathSplitting::Sun)
        return ", Russian roulette and splitting by a weight window on throughput x the cached "
               "sun transmittance (Vorba & Krivanek 2016; not in guiding's training passes)";
    return ", Russian roulette and splitting by a weight window on throughput x the radiance "
           "learnt in " +
           std::to_string(volume.guiding.training_passes) + " training passes of " +
           std::to_string(volume.guiding.training_spp) +
           " spp, centred on each pixel's training estimate (Vorba & Krivanek 2016)";
}

/// Russian roulette of the trackers' shadow rays by their cached contribution
/// (render.volume.shadow_roulette; volume/scattered_direct.h, contribution_survival).
std::string shadow_roulette_summary(const SceneDesc& scene) {
    const VolumeSettings& volume = scene.render.volume;
    if (!(volume.shadow_roulette > 0.0f))
        return std::string();
    const bool one_grid =
        scene.media.size() == 1 && std::holds_alternative<VdbMedium>(scene.media[0].model);
    const bool sun = std::any_of(scene.lights.begin(), scene.lights.end(), [](const Light& l) {
        return std::holds_alternative<DirectionalLight>(l.emitter);
    });
    if (!one_grid || !sun)
        return ", shadow_roulette skipped (it needs a directional light through one grid "
               "medium, for the light cache)";
    return ", shadow rays of directional lights by Russian roulette on their expected "
           "contribution (path weight x sigma_s p x the light cache's T, against " +
           format_g(volume.shadow_roulette) +
           " of an isotropic lit scatterer's; traced with probability >= " +
           format_g(kShadowSurvivalFloor) + ", weighted 1/q: unbiased)";
}

/// Where the camera segment's transmittance comes from (render.volume.camera_transmittance).
std::string camera_transmittance_summary(const VolumeSettings& volume) {
    if (volume.camera_transmittance == CameraTransmittance::Walk)
        return std::string();
    if (volume.nee_points > 0)
        return ", camera transmittance from the tracked walk";
    return ", camera transmittance from the first free flight's escape weight (no separate walk)";
}

}  // namespace

Plan make_plan(const SceneDesc& scene) {
    Plan plan;
    const bool has_shapes = !scene.shapes.empty();
    const bool has_lights = !scene.lights.empty();
    const bool has_media = !scene.media.empty();
    const bool media_scatter = MediumSet(scene.media).scatters();

    plan.surfaces = has_shapes;
    plan.stages.push_back({"surfaces", plan.surfaces,
                           has_shapes
                               ? count(scene.shapes.size(), "shape") + ": Embree BVH, closest hit"
                               : "no shapes: no BVH built"});

    add_scanline_surface_stage(scene, plan);

    plan.direct_light = has_shapes && has_lights;
    plan.stages.push_back({"direct-light", plan.direct_light,
                           plan.direct_light
                               ? count(scene.lights.size(), "light") + ", Phong shading"
                           : !has_shapes ? "no shapes to light"
                                         : "no lights"});

    plan.shadow_rays = has_shapes && has_lights && scene.render.shadows;
    plan.stages.push_back({"shadow-rays", plan.shadow_rays,
                           plan.shadow_rays        ? "one shadow ray per delta light (hard shadows)"
                           : !scene.render.shadows ? "render.shadows is false"
                           : !has_shapes           ? "no shapes can cast shadows"
                                                   : "no lights"});

    add_shadow_stages(scene, plan);

    plan.ambient = has_shapes && max_component(scene.ambient) > 0.0f && any_ambient_material(scene);
    plan.stages.push_back({"ambient", plan.ambient,
                           plan.ambient ? "ambient light and materials with ka > 0"
                                        : "ambient light or every ka is zero"});

    const VolumeSettings& volume = scene.render.volume;
    const bool multiple = volume.integrator == VolumeIntegrator::Multiple;
    plan.volume = has_media;
    plan.stages.push_back(
        {"volume-transmittance", plan.volume,
         has_media ? media_summary(scene) + ": " + estimator_summary(scene) : "no media"});

    // Multiple scattering lights media from the background too, without lights.
    const bool lit = has_lights || (multiple && max_component(scene.background) > 0.0f);
    plan.in_scattering = has_media && media_scatter && lit;
    const bool exact_stretches = MediumSet(scene.media).all_homogeneous() &&
                                 volume.estimator == Estimator::March && !multiple;
    const bool lone_height_fog = scene.media.size() == 1 &&
                                 std::holds_alternative<HeightFogMedium>(scene.media[0].model) &&
                                 volume.estimator == Estimator::March && !multiple;
    plan.stages.push_back(
        {"volume-in-scattering", plan.in_scattering,
         !plan.in_scattering ? (!has_media       ? "no media"
                                : !media_scatter ? "media do not scatter (sigma_s = 0): "
                                                   "transmittance only"
                                                 : "no lights to scatter")
         : exact_stretches
             ? "single scattering, marched with step " + std::to_string(volume.step_m) + " m" +
                   (plan.shadow_rays ? ", shadowed by surfaces" : "")
         : lone_height_fog
             ? "single scattering, march of the height fog: nodes stratified in its closed-form "
               "column (step " +
                   std::to_string(volume.step_m) +
                   " m where the ray's fog is densest; unbiased), exact transmittance" +
                   (plan.shadow_rays ? ", shadowed by surfaces" : "")
         : volume.estimator == Estimator::DebiasedMarch && !multiple
             ? "single scattering, debiased march (unbiased): fixed-step nodes (" +
                   std::to_string(volume.step_m) +
                   " m or step_voxels), camera transmittance debiased about the trapezoid, "
                   "directional lights' shadows debiased about the light cache's depth "
                   "(docs/volumes.md)" +
                   (plan.shadow_rays ? ", shadowed by surfaces" : "")
         : volume.estimator == Estimator::March && !multiple
             ? "single scattering, fixed-step march (" + std::to_string(volume.step_m) +
                   " m or step_voxels), light to every node through the march"
             : std::string(multiple ? "paths" : "single scattering") + ": free flights by " +
                   flight_summary(scene) +
                   " over per-brick majorants, next-event estimation to every light through " +
                   estimator_name(volume.estimator) + shadow_roulette_summary(scene) +
                   (plan.shadow_rays ? ", shadowed by surfaces" : "")});

    plan.stages.push_back(
        {"multiple-scattering", plan.in_scattering && multiple,
         !plan.in_scattering ? "no in-scattering"
         : multiple
             ? "volumetric path tracing, max_depth " + std::to_string(volume.max_depth) +
                   path_roulette_summary(volume) + camera_transmittance_summary(volume) +
                   (volume.guiding.enabled
                        ? ", directions guided (mix " + format_g(volume.guiding.mix) +
                              " of incident-radiance histograms x phase, kd-tree trained in " +
                              std::to_string(volume.guiding.training_passes) + " passes of " +
                              std::to_string(volume.guiding.training_spp) + " spp)"
                        : std::string())
             : "render.volume.integrator is \"single\": light scattered more than once "
               "is left out"});
    plan.stages.push_back(scattering_bound_plan_stage(scene, plan));
    plan.stages.push_back(gi_plan_stage(scene));
    plan.stages.push_back({"background", max_component(scene.background) > 0.0f,
                           max_component(scene.background) > 0.0f ? "constant background radiance"
                                                                  : "black background"});
    for (const SkyPlanStage& s : sky_plan_stages(scene.sky.get()))
        plan.stages.push_back({s.name, s.enabled, s.reason});
    if (scene.sky != nullptr) {
        plan.stages.push_back(sky_shafts_plan_stage(scene, plan));
        plan.stages.push_back(
            {"air-and-media", plan.volume,
             plan.volume ? "the atmosphere and the media composed as one medium along camera "
                           "rays (render/air_and_media.h): the air in front of, among (pieces "
                           "of max(250 m, t/8)) and behind the media, each piece's media lit "
                           "by the sun through the air above it"
                         : "no media: the air alone in front of surfaces"});
    }
    plan.stages.push_back(quality_plan_stage(scene));
    plan.stages.push_back(adaptive_sampling_plan_stage(scene.film));
    plan.stages.push_back(denoise_plan_stage(scene.film));
    return plan;
}

std::string plan_to_text(const Plan& plan) {
    std::ostringstream out;
    for (const PlanStage& s : plan.stages) {
        out << (s.enabled ? "  run   " : "  skip  ") << s.name << ": " << s.reason << "\n";
    }
    return out.str();
}

Json plan_to_json(const Plan& plan) {
    Json stages = Json::array();
    for (const PlanStage& s : plan.stages) {
        stages.push_back({{"name", s.name}, {"enabled", s.enabled}, {"reason", s.reason}});
    }
    return Json{{"stages", stages}};
}

}  // namespace kasumi
