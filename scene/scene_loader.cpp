#include "scene/scene_loader.h"

#include "core/error.h"
#include "core/json_choice.h"
#include "core/json_int.h"
#include "lights/light_json.h"
#include "scene/animation.h"
#include "scene/quality.h"
#include "sky/sky_renderer.h"
#include "volume/medium_json.h"
#include "volume/medium_set.h"
#include "volume/transmittance.h"

#include <cmath>
#include <filesystem>
#include <map>
#include <set>

namespace kasumi {

namespace {

CameraDesc parse_camera(const JsonNode& node) {
    JsonObjectReader reader(node);
    CameraDesc camera;
    if (auto v = reader.optional("position"))
        camera.position = v->as_point();
    if (auto v = reader.optional("look_at"))
        camera.look_at = v->as_point();
    if (auto v = reader.optional("up"))
        camera.up = v->unit_direction();
    if (auto v = reader.optional("fov_deg"))
        camera.fov_deg = v->in_open(0.0f, 180.0f);
    reader.finish();
    const Vec3 forward = camera.look_at - camera.position;
    const float distance = glm::length(forward);
    if (!(distance > 0.0f)) {
        // Distinct in double but not in float: the squared distance underflowed.
        if (glm::length(DVec3(camera.look_at) - DVec3(camera.position)) > 0.0)
            node.fail("position and look_at are too close together for single precision");
        node.fail("position and look_at must differ");
    }
    if (!std::isfinite(distance))
        node.fail("position and look_at are too far apart for single precision");
    if (!(glm::length(glm::cross(glm::normalize(forward), camera.up)) > 1e-6f)) {
        node.fail("up must not be parallel to the view direction");
    }
    return camera;
}

/// film.denoise: "off", "nlm", or an object {"method", "radius", "patch", "k", "k_feature",
/// "select"}.
DenoiseSettings parse_denoise(const JsonNode& node) {
    DenoiseSettings denoise;
    const auto method = [&](const JsonNode& v) {
        const std::string name = v.is_string() ? v.as_string() : std::string();
        if (name != "off" && name != "nlm")
            v.fail(
                "must be \"off\", \"nlm\" or an object {\"method\", \"radius\", \"patch\", "
                "\"k\", \"k_feature\", \"select\"}");
        return name == "nlm";
    };
    if (!node.is_object()) {
        denoise.enabled = method(node);
        return denoise;
    }
    JsonObjectReader reader(node);
    denoise.enabled = true;
    if (auto v = reader.optional("method"))
        denoise.enabled = method(*v);
    if (auto v = reader.optional("radius"))
        denoise.radius = parse_int_in(*v, 1, 32);
    if (auto v = reader.optional("patch"))
        denoise.patch = parse_int_in(*v, 0, 8);
    if (auto v = reader.optional("k"))
        denoise.k = v->in_open(0.0f, 4.0f);
    if (auto v = reader.optional("k_feature"))
        denoise.k_feature = v->in_open(0.0f, 16.0f);
    if (auto v = reader.optional("select"))
        denoise.select = v->as_bool();
    reader.finish();
    return denoise;
}

FilmDesc parse_film(const JsonNode& node) {
    JsonObjectReader reader(node);
    FilmDesc film;
    if (auto v = reader.optional("width"))
        film.width = parse_int_in(*v, 1, 16384);
    if (auto v = reader.optional("height"))
        film.height = parse_int_in(*v, 1, 16384);
    if (auto v = reader.optional("spp"))
        film.spp = parse_int_in(*v, 1, 1 << 20);
    if (auto v = reader.optional("jitter"))
        film.jitter = v->as_bool();
    if (auto v = reader.optional("noise_threshold"))
        film.noise_threshold = v->non_negative();
    if (auto v = reader.optional("noise_floor_cd_m2"))
        film.noise_floor_cd_m2 = v->positive();
    if (auto v = reader.optional("min_spp"))
        film.min_spp = parse_int_in(*v, 2, 1 << 20);
    if (auto v = reader.optional("noise_window"))
        film.noise_window = parse_int_in(*v, 0, 16);
    if (auto v = reader.optional("pixel_type")) {
        if (!parse_exr_pixel_type(v->as_string(), film.pixel_type))
            v->fail("must be \"float\" or \"half\"");
    }
    if (auto v = reader.optional("denoise"))
        film.denoise = parse_denoise(*v);
    reader.finish();
    return film;
}

/// render.volume.guiding: true / false, or an object of GuidingSettings (enabled unless
/// "enabled": false).
GuidingSettings parse_guiding(const JsonNode& node) {
    GuidingSettings guiding;
    if (!node.is_object()) {
        guiding.enabled = node.as_bool();
        return guiding;
    }
    JsonObjectReader reader(node);
    guiding.enabled = true;
    if (auto v = reader.optional("enabled"))
        guiding.enabled = v->as_bool();
    if (auto v = reader.optional("mix"))
        guiding.mix = v->in_open(0.0f, 1.0f);
    if (auto v = reader.optional("training_passes"))
        guiding.training_passes = parse_int_in(*v, 1, 64);
    if (auto v = reader.optional("training_spp"))
        guiding.training_spp = parse_int_in(*v, 1, 1024);
    if (auto v = reader.optional("leaf_records"))
        guiding.leaf_records = parse_int_in(*v, 16, 1 << 24);
    if (auto v = reader.optional("uniform")) {
        guiding.uniform = v->in_closed(0.0f, 1.0f);
        if (!(guiding.uniform < 1.0f))
            v->fail("must be in [0, 1)");
    }
    reader.finish();
    return guiding;
}

RenderSettings parse_render(const JsonNode& node, const FilmDesc& film) {
    JsonObjectReader reader(node);
    RenderSettings render;
    if (auto v = reader.optional("seed")) {
        const int64_t seed = v->as_int();
        if (seed < 0)
            v->fail("must be >= 0");
        render.seed = static_cast<uint64_t>(seed);
    }
    if (auto v = reader.optional("threads"))
        render.threads = parse_int_in(*v, 0, 1024);
    if (auto v = reader.optional("tile_size"))
        render.tile_size = parse_int_in(*v, 1, 1024);
    if (auto v = reader.optional("shadows"))
        render.shadows = v->as_bool();
    if (auto v = reader.optional("surface")) {
        render.surface = parse_choice<SurfaceMethod>(
            *v, {{"ray", SurfaceMethod::Ray}, {"scanline", SurfaceMethod::Scanline}});
        // The scanline renderer resolves visibility at pixel centres only (one pass per frame).
        if (render.surface == SurfaceMethod::Scanline && film.jitter)
            v->fail(
                "\"scanline\" draws the pixel centres only: set film.jitter to false (jittered "
                "camera samples need \"ray\")");
    }
    if (auto v = reader.optional("volume")) {
        JsonObjectReader volume(*v);
        if (auto step = volume.optional("step_m"))
            render.volume.step_m = step->positive();
        if (auto step = volume.optional("step_voxels"))
            render.volume.step_voxels = step->positive();
        if (auto e = volume.optional("estimator")) {
            const auto estimator = estimator_from_name(e->as_string());
            if (!estimator)
                e->fail(
                    "expected \"march\", \"delta\", \"ratio\", \"residual-ratio\", "
                    "\"unbiased-march\" or \"debiased-march\"");
            render.volume.estimator = *estimator;
            render.volume.estimator_given = true;
        }
        if (auto integrator = volume.optional("integrator"))
            render.volume.integrator = parse_choice<VolumeIntegrator>(
                *integrator,
                {{"single", VolumeIntegrator::Single}, {"multiple", VolumeIntegrator::Multiple}});
        if (auto depth = volume.optional("max_depth"))
            render.volume.max_depth = parse_int_in(*depth, 1, 1 << 16);
        if (auto cache = volume.optional("light_cache"))
            render.volume.light_cache = cache->as_bool();
        if (auto points = volume.optional("nee_points"))
            render.volume.nee_points = parse_int_in(*points, 0, 64);
        if (auto intervals = volume.optional("shadow_intervals"))
            render.volume.shadow_intervals = parse_int_in(*intervals, 0, 4096);
        if (auto roulette = volume.optional("nee_roulette"))
            render.volume.nee_roulette = roulette->as_bool();
        if (auto share = volume.optional("shadow_roulette"))
            render.volume.shadow_roulette = share->in_closed(0.0f, 1.0f);
        if (auto mis = volume.optional("spectral_mis"))
            render.volume.spectral_mis = mis->as_bool();
        if (auto flight = volume.optional("free_flight"))
            render.volume.free_flight = parse_choice<FreeFlightSampling>(
                *flight, {{"tracking", FreeFlightSampling::Tracking},
                          {"decomposition", FreeFlightSampling::Decomposition}});
        if (auto camera_t = volume.optional("camera_transmittance"))
            render.volume.camera_transmittance = parse_choice<CameraTransmittance>(
                *camera_t, {{"walk", CameraTransmittance::Walk},
                            {"first_flight", CameraTransmittance::FirstFlight}});
        if (auto splitting = volume.optional("splitting"))
            render.volume.splitting =
                parse_choice<PathSplitting>(*splitting, {{"off", PathSplitting::Off},
                                                         {"sun", PathSplitting::Sun},
                                                         {"guided", PathSplitting::Guided}});
        if (auto sampling = volume.optional("light_sampling"))
            render.volume.light_sampling = parse_choice<LightSampling>(
                *sampling, {{"all", LightSampling::All}, {"one", LightSampling::One}});
        if (auto guiding = volume.optional("guiding"))
            render.volume.guiding = parse_guiding(*guiding);
        if (auto filter = volume.optional("density_filter")) {
            render.volume.stochastic_filter =
                parse_choice<bool>(*filter, {{"trilinear", false}, {"stochastic", true}});
            if (render.volume.stochastic_filter && render.volume.estimator_given &&
                render.volume.estimator == Estimator::March)
                filter->fail(
                    "\"stochastic\" needs an unbiased tracker (estimator \"delta\", \"ratio\", "
                    "\"residual-ratio\" or \"unbiased-march\"): the march's exp of a noisy "
                    "depth is biased (docs/volumes.md)");
        }
        volume.finish();
    }
    if (auto v = reader.optional("whitted")) {
        JsonObjectReader whitted(*v);
        if (auto depth = whitted.optional("max_depth"))
            render.whitted.max_depth = parse_int_in(*depth, 0, 64);
        if (auto weight = whitted.optional("min_weight"))
            render.whitted.min_weight = weight->in_closed(0.0f, 1.0f);
        whitted.finish();
    }
    if (auto v = reader.optional("gi"))
        render.gi = parse_gi_mode(*v);
    if (auto v = reader.optional("path"))
        render.path = parse_path_settings(*v);
    if (auto v = reader.optional("radiosity"))
        render.radiosity = parse_radiosity_settings(*v);
    if (auto v = reader.optional("photons"))
        render.photons = parse_photon_settings(*v);
    reader.optional("quality");  // validated and applied by apply_quality (scene/quality.h)
    if (auto v = reader.optional("preview")) {
        JsonObjectReader preview(*v);
        if (auto view = preview.optional("view"))
            render.preview.view = view->as_string();
        if (auto e = preview.optional("exposure_stops")) {
            if (e->is_string() && e->as_string() == "auto")
                render.preview.exposure_auto = true;
            else if (e->is_number())
                render.preview.exposure_stops = e->in_closed(-64.0f, 64.0f);
            else
                e->fail("expected a number of stops in [-64, 64] or \"auto\"");
        }
        preview.finish();
    }
    parse_sky_render_keys(reader, render.sky);
    reader.finish();
    return render;
}

}  // namespace

SceneDesc parse_scene(const Json& root_value, const std::string& file, ElementCache* cache) {
    SceneDocument with_quality(root_value, file);
    QualityChoice quality = apply_quality(with_quality);
    const JsonNode root(with_quality.json(), file);
    JsonObjectReader reader(root);
    SceneDesc scene;
    scene.file = file;
    scene.base_dir = std::filesystem::path(file).parent_path().string();

    if (auto v = reader.optional("camera"))
        scene.camera = parse_camera(*v);
    if (auto v = reader.optional("film"))
        scene.film = parse_film(*v);
    if (auto v = reader.optional("render"))
        scene.render = parse_render(*v, scene.film);
    if (auto v = reader.optional("ambient"))
        scene.ambient = v->non_negative_rgb();
    if (auto v = reader.optional("background"))
        scene.background = v->non_negative_rgb();

    std::map<std::string, uint32_t> material_index;
    if (auto v = reader.optional("materials")) {
        if (!v->is_object())
            v->fail("expected an object of named materials");
        for (const auto& item : v->value().items()) {
            const JsonNode m = v->child(item.key());
            material_index[item.key()] = static_cast<uint32_t>(scene.materials.size());
            scene.material_names.push_back(item.key());
            scene.materials.push_back(parse_material(m));
        }
    }
    if (auto v = reader.optional("shapes")) {
        for (const JsonNode& s : v->elements()) {
            scene.shapes.push_back(cache ? cache->shape(s, material_index, scene.base_dir)
                                         : parse_shape(s, material_index, scene.base_dir));
        }
    }
    if (auto v = reader.optional("lights")) {
        for (const JsonNode& l : v->elements()) {
            scene.lights.push_back(cache ? cache->light(l, scene.lights.size())
                                         : parse_light(l, scene.lights.size()));
        }
    }
    if (auto v = reader.optional("media")) {
        if (v->size() > kMaxMedia)
            v->fail("at most " + std::to_string(kMaxMedia) + " media");
        for (const JsonNode& m : v->elements()) {
            scene.media.push_back(cache ? cache->medium(m, scene.media.size(), scene.base_dir)
                                        : parse_medium(m, scene.media.size(), scene.base_dir));
        }
    }
    // Unless the scene names one: exact stretches suit homogeneous media, residual ratio
    // tracking (unbiased, exact where a brick is constant) suits grids.
    if (!scene.render.volume.estimator_given) {
        scene.render.volume.estimator =
            MediumSet(scene.media).all_homogeneous() ? Estimator::March : Estimator::ResidualRatio;
    }
    parse_sky_keys(reader, scene.render.sky, scene.sky, scene.lights);
    choose_integrator(with_quality, scene.media, scene.render.volume, quality);
    scene.render.quality = quality;
    reader.optional("comment");  // free text for the scene's author
    reader.finish();
    return scene;
}

SceneSource::SceneSource(const std::string& path, std::vector<Override> overrides)
    : SceneSource(SceneDocument::read(path), std::move(overrides)) {}

SceneSource::SceneSource(SceneDocument document, std::vector<Override> overrides)
    : m_overrides(std::move(overrides)), m_document(std::move(document)) {
    apply_overrides(m_document, m_overrides);
    m_animation = parse_animation(m_document);
}

SceneDocument SceneSource::frame_document(int64_t frame) const {
    if (!m_document.json().is_object() || !m_document.json().contains("animate"))
        return m_document;
    SceneDocument doc = kasumi::frame_document(m_document, m_animation, frame);
    reapply_overrides(doc, m_overrides);
    return doc;
}

SceneDesc SceneSource::scene(int64_t frame, ElementCache* cache) const {
    return parse(frame_document(frame).json(), frame, cache);
}

SceneDesc SceneSource::parse(const Json& doc, int64_t frame, ElementCache* cache) const {
    try {
        return parse_scene(doc, m_document.file(), cache);
    } catch (const Error& e) {
        if (e.kind() != ErrorKind::Input || m_animation.empty())
            throw;
        throw Error(e.kind(), e.what() + frame_context(m_animation, frame, e.what()));
    }
}

std::vector<int64_t> SceneSource::key_frames() const {
    std::set<int64_t> frames;
    for (const Track& track : m_animation.tracks) {
        for (const Keyframe& key : track.keys)
            frames.insert(key.frame);
    }
    return {frames.begin(), frames.end()};
}

SceneDesc load_scene(const std::string& path, const std::vector<Override>& overrides,
                     int64_t frame) {
    return SceneSource(path, overrides).scene(frame);
}

}  // namespace kasumi
