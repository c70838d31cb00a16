#pragma once
/// `kasumi study`: renders a scene at every combination of varied settings, times each render
/// (median of repeats, interleaved across configurations) and measures its error against a
/// reference image. docs/study.md describes the method and the shipped studies.
#include "core/json_node.h"
#include "core/math.h"
#include "study/study_metrics.h"

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace kasumi {

/// One varied setting: a JSON pointer into the scene (or "spp", read as /film/spp), or several
/// joined by '+' that all take the same value (e.g. "/lights/0/samples+/lights/1/samples"),
/// and the values it takes, each as the text of a JSON value (a bare word is a string). A '*'
/// token stands for every element of the array (or member of the object) at that place
/// ("/lights/*/samples": every light). A value that is a JSON object, for a pointer naming an
/// object in the scene, is merged into it (JSON merge patch, RFC 7396: members replace or add,
/// null removes) instead of replacing it, so one axis can switch several keys together.
struct StudyAxis {
    std::string key;
    std::vector<std::string> values;
};

/// Parses "KEY=V1,V2,..." (commas inside [] {} or quotes do not split). Throws ErrorKind::Usage
/// if a part of the key is neither "spp" nor a JSON pointer, a value is empty, or a value repeats.
StudyAxis parse_vary(const std::string& text);

/// The JSON pointers a study key sets ("spp" -> "/film/spp"; '+' separates several).
std::vector<std::string> study_pointers(const std::string& key);

/// Every combination of the axes' values, as one value index per axis; the last axis varies
/// fastest. No axes: one empty combination.
std::vector<std::vector<size_t>> expand_combinations(const std::vector<StudyAxis>& axes);

/// The value of `axis` taken to be the most accurate, for the automatic reference: the
/// smallest number for keys naming a step, tolerance or error, the largest number otherwise
/// (spp, samples, depth, resolution); for words, "multiple" over "single" and, among
/// transmittance estimators, "ratio" (unbiased, lower variance than delta tracking, no
/// dependence on a minorant); otherwise the last value listed.
std::string most_accurate_value(const StudyAxis& axis);

/// A probe studied instead of an image: every configuration measures the same quantity along
/// one ray (a 1x1 "image"), `spp` being its number of samples, and the error is taken against
/// the exact value when one is known (docs/study.md).
struct StudyProbe {
    enum class Kind { Radiance, Transmittance };
    Kind kind = Kind::Transmittance;
    Vec3 a{0.0f};  ///< radiance: ray origin; transmittance: segment start (metres)
    Vec3 b{0.0f};  ///< radiance: ray direction; transmittance: segment end (metres)
    /// The exact value, e.g. a closed form the user knows (cd/m² or transmittance).
    std::optional<Rgb> exact;
    /// Transmittance only: the exact value is Beer-Lambert exp(-tau) with tau integrated
    /// analytically through homogeneous media (ErrorKind::Usage if the scene has other media).
    bool exact_beer_lambert = false;
};

/// One setting applied to the scene document: /pointer=VALUE ('*' tokens allowed), replacing
/// the value, or with `merge` merging a JSON object value into an existing object.
struct StudySetting {
    std::string pointer;
    std::string value;
    bool merge = false;
};

/// What a configuration's time measures.
enum class StudyTiming {
    Render,       ///< render_image only (scene load, BVH and precomputed tables excluded)
    BuildRender,  ///< the scene runtime's set-up (BVH, shadow maps and volumes, media, sky and
                  ///< GI tables) plus render_image, rebuilt for every repeat; the file's
                  ///< parsing and reading stay excluded
};

struct StudySpec {
    std::string scene_path;
    std::vector<StudyAxis> axes;
    std::vector<std::string> sets;  ///< --set overrides applied to every render, /pointer=VALUE
    int width = 0, height = 0;      ///< 0: the scene's film size
    int spp = 0;                    ///< 0: the scene's film.spp (an "spp" axis overrides it)
    int repeats = 3;                ///< timed renders per configuration, median reported
    int threads = 0;                ///< 0: all hardware threads
    std::string reference_file;     ///< empty: automatic reference
    int reference_spp = 0;          ///< automatic reference spp; 0: max(256, 16 x largest spp)
    std::vector<std::string> reference_sets;  ///< extra /pointer=VALUE for the reference only
    ErrorSettings error;
    std::optional<StudyProbe> probe;  ///< set: study this probe instead of rendered images
    StudyTiming timing = StudyTiming::Render;
};

/// One configuration's measurements.
struct StudyRow {
    std::vector<std::string> values;  ///< per axis
    std::string label;                ///< "key=value, key=value"
    int spp = 0;
    std::vector<double> seconds;  ///< render time of every repeat (load and BVH excluded)
    double median_seconds = 0.0;
    ImageError error;
    bool pareto = false;  ///< on the Pareto front of (median time, relative MSE)
    /// Monte Carlo efficiency 1 / (rel_mse * time): higher buys more accuracy per second.
    double efficiency = 0.0;
};

struct StudyReference {
    std::string description;  ///< how it was made (settings, spp) or the file
    bool has_standard_error = false;
    ImageError standard_error;  ///< from two independent half-spp renders (automatic only)
    double seconds = 0.0;       ///< time to render it
    bool exact = false;         ///< the exact value of a probe, not an estimate
};

struct StudyResult {
    std::string scene;
    /// What was measured: empty for rendered images, else the probe ("transmittance from
    /// (x, y, z) to (x, y, z)").
    std::string probe;
    int width = 0, height = 0;
    std::vector<StudyAxis> axes;
    std::vector<StudyRow> rows;  ///< in expand_combinations order
    StudyReference reference;
    ErrorSettings error;
    StudyTiming timing = StudyTiming::Render;
};

/// Runs the study. `log` (may be empty) receives one line per finished render. Every
/// configuration is loaded and validated before the first render, so a bad value fails fast
/// with the scene's file and JSON pointer (ErrorKind::Input).
StudyResult run_study(const StudySpec& spec,
                      const std::function<void(const std::string&)>& log = {});

/// Scene document for one configuration: `sets` then the axis values applied to the file;
/// missing parent objects along each pointer are created and '*' tokens expanded.
Json study_document(const std::string& scene_path, const std::vector<std::string>& sets);

/// As above with settings applied in order; each '*' is expanded against the document as it
/// stands when that setting is applied. ErrorKind::Input (naming the file and pointer) if a
/// '*' meets something that is not an array or object, or the array is empty.
Json study_document_of(const std::string& scene_path, const std::vector<StudySetting>& settings);

/// The pointers `pointer` names in `doc`: '*' tokens replaced by every index of the array (or
/// key of the object) at that place; a pointer without '*' is returned as is.
std::vector<std::string> expand_wildcards(const Json& doc, const std::string& pointer,
                                          const std::string& file);

}  // namespace kasumi
