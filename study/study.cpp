#include "study/study.h"

#include "core/error.h"
#include "core/exr_io.h"
#include "gi/gi.h"
#include "render/probe.h"
#include "render/renderer.h"
#include "scene/json_pointer.h"
#include "scene/scene_loader.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <set>

namespace kasumi {

namespace {

/// Splits at commas outside brackets, braces and double quotes.
std::vector<std::string> split_top_level(const std::string& text) {
    std::vector<std::string> parts;
    std::string current;
    int depth = 0;
    bool quoted = false;
    for (size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (quoted) {
            if (c == '\\' && i + 1 < text.size()) {
                current += c;
                current += text[++i];
                continue;
            }
            quoted = c != '"';
        } else if (c == '"') {
            quoted = true;
        } else if (c == '[' || c == '{') {
            ++depth;
        } else if (c == ']' || c == '}') {
            --depth;
        } else if (c == ',' && depth == 0) {
            parts.push_back(current);
            current.clear();
            continue;
        }
        current += c;
    }
    parts.push_back(current);
    return parts;
}

std::optional<double> as_number(const std::string& text) {
    try {
        const Json j = Json::parse(text);
        if (j.is_number())
            return j.get<double>();
    } catch (const Json::exception&) {
    }
    return std::nullopt;
}

/// The text of a value as a word: JSON strings lose their quotes.
std::string as_word(const std::string& text) {
    try {
        const Json j = Json::parse(text);
        if (j.is_string())
            return j.get<std::string>();
    } catch (const Json::exception&) {
    }
    return text;
}

bool names_a_step(const std::string& key) {
    const std::string last = key.substr(key.rfind('/') + 1);
    for (const char* word : {"step", "tolerance", "error", "eps"}) {
        if (last.find(word) != std::string::npos)
            return true;
    }
    return false;
}

double median(std::vector<double> v) {
    if (v.empty())
        return 0.0;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/// The child of `node` that `token` names, or null when there is none.
const Json* child(const Json* node, const std::string& token) {
    return node == nullptr ? nullptr : find_value(*node, {token});
}

void expand_from(const Json* node, const std::vector<std::string>& tokens, size_t i,
                 const std::string& prefix, const std::string& pointer, const std::string& file,
                 std::vector<std::string>& out) {
    if (i == tokens.size()) {
        out.push_back(prefix);
        return;
    }
    if (tokens[i] != "*") {
        expand_from(child(node, tokens[i]), tokens, i + 1,
                    prefix + "/" + json_pointer_escape(tokens[i]), pointer, file, out);
        return;
    }
    const std::string where = prefix.empty() ? "the document" : prefix;
    if (node != nullptr && node->is_array() && !node->empty()) {
        for (size_t k = 0; k < node->size(); ++k) {
            expand_from(&(*node)[k], tokens, i + 1, prefix + "/" + std::to_string(k), pointer, file,
                        out);
        }
    } else if (node != nullptr && node->is_object() && !node->empty()) {
        for (auto it = node->begin(); it != node->end(); ++it) {
            expand_from(&it.value(), tokens, i + 1, prefix + "/" + json_pointer_escape(it.key()),
                        pointer, file, out);
        }
    } else {
        throw_input_error(file + ": " + pointer + ": '*' needs a non-empty array or object at " +
                          where);
    }
}

std::string join_sets(const std::vector<StudySetting>& sets) {
    std::string text;
    for (const StudySetting& s : sets)
        text += (text.empty() ? "" : " ") + s.pointer + "=" + s.value;
    return text;
}

std::vector<StudySetting> settings_of(const std::vector<std::string>& sets) {
    std::vector<StudySetting> out;
    for (const std::string& s : sets) {
        const Override o = parse_override(s);
        out.push_back({o.pointer, o.value, false});
    }
    return out;
}

bool is_json_object(const std::string& text) {
    try {
        return Json::parse(text).is_object();
    } catch (const Json::exception&) {
        return false;
    }
}

/// The setting of one axis pointer to one of its values (objects merge, docs/study.md).
StudySetting axis_setting(const std::string& pointer, const std::string& value) {
    return {pointer, value, is_json_object(value)};
}

SceneDesc load_desc(const std::string& scene_path, const std::vector<StudySetting>& sets) {
    return parse_scene(study_document_of(scene_path, sets), scene_path);
}

std::unique_ptr<SceneRuntime> load_runtime(const std::string& scene_path,
                                           const std::vector<StudySetting>& sets) {
    return std::make_unique<SceneRuntime>(load_desc(scene_path, sets), make_gi_method);
}

/// One configuration's measured value (an image, or a probe as a 1x1 image) and its time.
struct Measurement {
    RgbPlane plane;
    double seconds = 0.0;
};

RgbPlane single_pixel(const Rgb& value) {
    RgbPlane plane;
    plane.width = plane.height = 1;
    plane.pixels = {value};
    return plane;
}

/// Renders the scene (time: render_image only), or runs the probe with film.spp samples (time:
/// the probe call only; estimator: the scene's render.volume.estimator).
Measurement measure(const SceneRuntime& runtime, const StudySpec& spec, const std::string& what);

/// StudyTiming::BuildRender: builds the runtime from `desc` and measures, the time including
/// the build.
Measurement build_and_measure(const SceneDesc& desc, const StudySpec& spec,
                              const std::string& what) {
    const auto start = std::chrono::steady_clock::now();
    const SceneRuntime runtime(desc, make_gi_method);
    const std::chrono::duration<double> build = std::chrono::steady_clock::now() - start;
    Measurement m = measure(runtime, spec, what);
    m.seconds += build.count();
    return m;
}

Measurement measure(const SceneRuntime& runtime, const StudySpec& spec, const std::string& what) {
    if (!spec.probe) {
        RenderOptions options;
        options.threads = spec.threads;
        options.progress = false;
        const RenderResult r = render_image(runtime, options);
        return {rgb_plane(r.film.to_image(), what), r.seconds};
    }
    const StudyProbe& probe = *spec.probe;
    const int samples = runtime.desc().film.spp;
    const auto start = std::chrono::steady_clock::now();
    const Rgb value = probe.kind == StudyProbe::Kind::Radiance
                          ? probe_radiance(runtime, probe.a, probe.b, samples).radiance
                          : probe_transmittance(runtime, probe.a, probe.b,
                                                runtime.desc().render.volume.estimator, samples)
                                .transmittance;
    const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
    return {single_pixel(value), elapsed.count()};
}

/// exp(-tau) from `from` to `to` with tau integrated analytically (homogeneous media only).
Rgb beer_lambert(const SceneRuntime& runtime, const Vec3& from, const Vec3& to) {
    if (!runtime.media().all_homogeneous() || runtime.sky() != nullptr) {
        throw Error(ErrorKind::Usage,
                    "--exact beer-lambert needs a scene whose media are all homogeneous (no grid, "
                    "no atmosphere); give the exact value as --exact R,G,B instead");
    }
    const Vec3 d = to - from;
    const float length = glm::length(d);
    if (!(length > 0.0f))
        return Rgb(1.0f);
    Ray ray;
    ray.origin = from;
    ray.direction = d / length;
    ray.t_max = length;
    return runtime.media().transmittance(ray);
}

std::string describe(const StudyProbe& probe) {
    auto xyz = [](const Vec3& v) {
        char text[96];
        std::snprintf(text, sizeof text, "(%g, %g, %g)", v.x, v.y, v.z);
        return std::string(text);
    };
    return probe.kind == StudyProbe::Kind::Radiance
               ? "radiance from " + xyz(probe.a) + " along " + xyz(probe.b)
               : "transmittance from " + xyz(probe.a) + " to " + xyz(probe.b);
}

}  // namespace

StudyAxis parse_vary(const std::string& text) {
    const size_t eq = text.find('=');
    if (eq == std::string::npos || eq == 0) {
        throw Error(ErrorKind::Usage, "--vary expects KEY=V1,V2,..., got \"" + text + "\"");
    }
    StudyAxis axis;
    axis.key = text.substr(0, eq);
    for (const std::string& part : study_pointers(axis.key)) {
        if (part.empty() || part[0] != '/') {
            throw Error(ErrorKind::Usage, "--vary " + axis.key +
                                              ": KEY must be \"spp\" or a JSON pointer such as "
                                              "/render/volume/step_m");
        }
    }
    std::set<std::string> seen;
    for (const std::string& value : split_top_level(text.substr(eq + 1))) {
        if (value.empty()) {
            throw Error(ErrorKind::Usage,
                        "--vary " + axis.key + ": empty value in \"" + text.substr(eq + 1) + "\"");
        }
        if (!seen.insert(value).second) {
            throw Error(ErrorKind::Usage,
                        "--vary " + axis.key + ": value " + value + " is listed twice");
        }
        axis.values.push_back(value);
    }
    if (axis.key == "spp") {
        for (const std::string& v : axis.values) {
            const auto n = as_number(v);
            if (!n || *n < 1 || *n != std::floor(*n) || *n > (1 << 20)) {
                throw Error(ErrorKind::Usage, "--vary spp: " + v + " is not an integer >= 1");
            }
        }
    }
    return axis;
}

std::vector<std::string> study_pointers(const std::string& key) {
    std::vector<std::string> parts;
    size_t start = 0;
    while (true) {
        const size_t plus = key.find('+', start);
        const std::string part = key.substr(start, plus - start);
        parts.push_back(part == "spp" ? "/film/spp" : part);
        if (plus == std::string::npos)
            return parts;
        start = plus + 1;
    }
}

std::vector<std::vector<size_t>> expand_combinations(const std::vector<StudyAxis>& axes) {
    std::vector<std::vector<size_t>> out{std::vector<size_t>(axes.size(), 0)};
    for (const StudyAxis& a : axes) {
        if (a.values.empty())
            return {};
    }
    // Odometer: increment the last axis, carry leftwards.
    while (true) {
        std::vector<size_t> next = out.back();
        size_t i = axes.size();
        while (i > 0) {
            --i;
            if (++next[i] < axes[i].values.size())
                break;
            next[i] = 0;
            if (i == 0)
                return out;
        }
        if (axes.empty())
            return out;
        out.push_back(next);
    }
}

std::string most_accurate_value(const StudyAxis& axis) {
    KASUMI_CHECK(!axis.values.empty());
    bool numeric = true;
    for (const std::string& v : axis.values)
        numeric = numeric && as_number(v).has_value();
    if (numeric) {
        const bool smallest = names_a_step(axis.key);
        auto best = axis.values.begin();
        for (auto it = axis.values.begin(); it != axis.values.end(); ++it) {
            const double v = *as_number(*it), b = *as_number(*best);
            if (smallest ? v < b : v > b)
                best = it;
        }
        return *best;
    }
    for (const char* preferred : {"multiple", "ratio", "residual-ratio"}) {
        for (const std::string& v : axis.values) {
            if (as_word(v) == preferred)
                return v;
        }
    }
    return axis.values.back();
}

std::vector<std::string> expand_wildcards(const Json& doc, const std::string& pointer,
                                          const std::string& file) {
    if (pointer.find('*') == std::string::npos)
        return {pointer};
    const auto tokens = pointer_tokens(pointer);
    if (!tokens)
        throw_input_error(file + ": " + pointer + ": invalid JSON pointer");
    std::vector<std::string> out;
    expand_from(&doc, *tokens, 0, "", pointer, file, out);
    return out;
}

Json study_document(const std::string& scene_path, const std::vector<std::string>& sets) {
    return study_document_of(scene_path, settings_of(sets));
}

Json study_document_of(const std::string& scene_path, const std::vector<StudySetting>& settings) {
    SceneDocument doc = SceneDocument::read(scene_path);
    for (const StudySetting& s : settings) {
        for (const std::string& pointer : expand_wildcards(doc.json(), s.pointer, scene_path)) {
            const Override o{pointer, s.value};
            if (s.merge) {
                const Json* at = doc.find(pointer);
                if (at != nullptr && at->is_object()) {
                    Json merged = *at;
                    merged.merge_patch(override_value(o, scene_path));
                    doc.set(pointer, std::move(merged));
                    continue;
                }
            }
            doc.set(pointer, override_value(o, scene_path), "--set");
        }
    }
    return std::move(doc.json());
}

StudyResult run_study(const StudySpec& spec, const std::function<void(const std::string&)>& log) {
    if (spec.repeats < 1)
        throw Error(ErrorKind::Usage, "--repeats must be >= 1");
    std::set<std::string> keys;
    for (const StudyAxis& a : spec.axes) {
        for (const std::string& pointer : study_pointers(a.key)) {
            if (!keys.insert(pointer).second)
                throw Error(ErrorKind::Usage, "--vary: " + pointer + " is given twice");
        }
    }
    auto say = [&](const std::string& line) {
        if (log)
            log(line);
    };

    std::vector<StudySetting> base = settings_of(spec.sets);
    if (spec.width > 0 && spec.height > 0) {
        base.push_back({"/film/width", std::to_string(spec.width)});
        base.push_back({"/film/height", std::to_string(spec.height)});
    }
    if (spec.spp > 0)
        base.push_back({"/film/spp", std::to_string(spec.spp)});

    StudyResult result;
    result.scene = spec.scene_path;
    result.axes = spec.axes;
    result.error = spec.error;
    result.timing = spec.timing;
    const bool build_timed = spec.timing == StudyTiming::BuildRender;

    // Load and validate every configuration before rendering anything. Timed with the build,
    // only the parsed descriptions are kept (each repeat builds its runtime, so one
    // configuration's shadow maps or tables are in memory at a time).
    const auto combinations = expand_combinations(spec.axes);
    std::vector<SceneDesc> descs;
    std::vector<std::unique_ptr<SceneRuntime>> runtimes;
    int largest_spp = 1;
    for (const auto& combination : combinations) {
        std::vector<StudySetting> sets = base;
        StudyRow row;
        for (size_t a = 0; a < spec.axes.size(); ++a) {
            const std::string& value = spec.axes[a].values[combination[a]];
            for (const std::string& pointer : study_pointers(spec.axes[a].key))
                sets.push_back(axis_setting(pointer, value));
            row.values.push_back(value);
            row.label += (row.label.empty() ? "" : ", ") + spec.axes[a].key + "=" + as_word(value);
        }
        if (row.label.empty())
            row.label = "scene as given";
        descs.push_back(load_desc(spec.scene_path, sets));
        row.spp = descs.back().film.spp;
        if (!build_timed)
            runtimes.push_back(
                std::make_unique<SceneRuntime>(std::move(descs.back()), make_gi_method));
        largest_spp = std::max(largest_spp, row.spp);
        result.rows.push_back(row);
    }
    if (!build_timed)
        descs.clear();
    auto desc_of = [&](size_t c) -> const SceneDesc& {
        return build_timed ? descs[c] : runtimes[c]->desc();
    };
    result.width = spec.probe ? 1 : desc_of(0).film.width;
    result.height = spec.probe ? 1 : desc_of(0).film.height;

    // Reference.
    RgbPlane reference;
    if (spec.probe)
        result.probe = describe(*spec.probe);
    if (spec.probe && (spec.probe->exact || spec.probe->exact_beer_lambert)) {
        const StudyProbe& probe = *spec.probe;
        if (probe.exact) {
            reference = single_pixel(*probe.exact);
            result.reference.description = "exact value given";
        } else {
            const SceneRuntime runtime(desc_of(0), make_gi_method);
            reference = single_pixel(beer_lambert(runtime, probe.a, probe.b));
            result.reference.description =
                "exact Beer-Lambert exp(-tau), tau integrated analytically";
        }
        char text[128];
        std::snprintf(text, sizeof text, " (%.9g, %.9g, %.9g)", reference.pixels[0].r,
                      reference.pixels[0].g, reference.pixels[0].b);
        result.reference.description += text;
        result.reference.exact = true;
    } else if (!spec.reference_file.empty()) {
        if (spec.probe)
            throw Error(ErrorKind::Usage, "a probe study takes --exact, not a reference image");
        reference = rgb_plane(read_exr(spec.reference_file), spec.reference_file);
        if (reference.width != result.width || reference.height != result.height) {
            throw_input_error(spec.reference_file + ": reference is " +
                              std::to_string(reference.width) + "x" +
                              std::to_string(reference.height) + ", the study renders " +
                              std::to_string(result.width) + "x" + std::to_string(result.height));
        }
        result.reference.description = "file " + spec.reference_file;
    } else {
        std::vector<StudySetting> sets = base;
        std::vector<StudySetting> chosen;
        for (const StudyAxis& a : spec.axes) {
            if (a.key == "spp")
                continue;
            for (const std::string& pointer : study_pointers(a.key))
                chosen.push_back(axis_setting(pointer, most_accurate_value(a)));
        }
        for (const StudySetting& s : settings_of(spec.reference_sets))
            chosen.push_back(s);
        sets.insert(sets.end(), chosen.begin(), chosen.end());
        const int ref_spp =
            spec.reference_spp > 0 ? spec.reference_spp : std::max(256, 16 * largest_spp);
        const int half = std::max(1, ref_spp / 2);
        const uint64_t seed = desc_of(0).render.seed;
        RgbPlane halves[2];
        for (int h = 0; h < 2; ++h) {
            std::vector<StudySetting> half_sets = sets;
            half_sets.push_back({"/film/spp", std::to_string(half)});
            // Seeds apart from the studied renders' so reference and test noise are independent.
            half_sets.push_back({"/render/seed", std::to_string(seed + 1000003u * (h + 1))});
            const auto runtime = load_runtime(spec.scene_path, half_sets);
            Measurement m = measure(*runtime, spec, "reference");
            result.reference.seconds += m.seconds;
            halves[h] = std::move(m.plane);
            say("reference half " + std::to_string(h + 1) + "/2: " + std::to_string(half) +
                " spp, " + std::to_string(m.seconds) + " s");
        }
        reference = average(halves[0], halves[1]);
        result.reference.has_standard_error = true;
        result.reference.standard_error =
            reference_standard_error(halves[0], halves[1], spec.error);
        result.reference.description =
            std::to_string(2 * half) + " spp (two independent halves of " + std::to_string(half) +
            ")" + (chosen.empty() ? std::string() : ", " + join_sets(chosen));
    }

    // Timed renders, interleaved: each repeat visits every configuration, starting one further
    // along each time, so a drift in machine load touches all configurations alike.
    const size_t n = result.rows.size();
    for (int r = 0; r < spec.repeats; ++r) {
        for (size_t k = 0; k < n; ++k) {
            const size_t c = (k + static_cast<size_t>(r)) % n;
            StudyRow& row = result.rows[c];
            const Measurement m = build_timed ? build_and_measure(descs[c], spec, row.label)
                                              : measure(*runtimes[c], spec, row.label);
            row.seconds.push_back(m.seconds);
            if (row.seconds.size() == 1)
                row.error = image_error(m.plane, reference, spec.error);
            char line[160];
            std::snprintf(line, sizeof line, "[repeat %d/%d] %s: %.3g s, rel MSE %.3g", r + 1,
                          spec.repeats, row.label.c_str(), m.seconds, row.error.rel_mse);
            say(line);
        }
    }

    std::vector<double> times, errors;
    for (StudyRow& row : result.rows) {
        row.median_seconds = median(row.seconds);
        const double work = row.error.rel_mse * row.median_seconds;
        row.efficiency = work > 0.0 ? 1.0 / work : INFINITY;
        times.push_back(row.median_seconds);
        errors.push_back(row.error.rel_mse);
    }
    for (size_t i : pareto_front(times, errors))
        result.rows[i].pareto = true;
    return result;
}

}  // namespace kasumi
