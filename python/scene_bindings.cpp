/// kasumi.Scene: a scene file read, overridden (`--set`), planned, rendered and probed by the
/// library's own functions.
#include "bindings.h"
#include "json_bridge.h"
#include "python/rendered_frame.h"

#include "gi/gi.h"
#include "render/probe_json.h"

#include <pybind11/stl.h>

#include <array>
#include <chrono>
#include <future>
#include <optional>
#include <thread>

namespace py = pybind11;

namespace kasumi::python {

namespace {

/// How often a render polls for Ctrl-C (PyErr_CheckSignals): the main thread waits on the
/// render in slices this long, holding the GIL only for the check.
constexpr std::chrono::milliseconds kSignalPoll{50};

/// A scene document and the overrides set on it, in order; every read sees the document with
/// the overrides applied exactly as `kasumi render --set` applies them.
class Scene {
  public:
    explicit Scene(SceneDocument document)
        : m_document(std::move(document)), m_source(m_document, {}) {}

    const std::string& file() const { return m_document.file(); }
    const SceneSource& source() const { return m_source; }

    /// `--set POINTER=TEXT`; an input error leaves the scene as it was.
    void set(const std::string& pointer, const py::handle& value) {
        std::vector<Override> overrides = m_overrides;
        overrides.push_back(parse_override(pointer + "=" + json_text(value)));
        m_source = SceneSource(m_document, overrides);
        m_overrides = std::move(overrides);
        m_runtime.reset();
    }

    /// The source with `extra` overrides after the scene's own (render's spp and seed).
    SceneSource source_with(const std::vector<Override>& extra) const {
        std::vector<Override> overrides = m_overrides;
        overrides.insert(overrides.end(), extra.begin(), extra.end());
        return SceneSource(m_document, overrides);
    }

    /// The runtime of frame 0, built on first use and kept until the next set() (probes).
    const SceneRuntime& runtime() {
        if (!m_runtime) {
            SceneDesc desc = m_source.scene(0);
            py::gil_scoped_release release;
            m_runtime = std::make_shared<const SceneRuntime>(std::move(desc), make_gi_method);
        }
        return *m_runtime;
    }

  private:
    SceneDocument m_document;
    std::vector<Override> m_overrides;
    SceneSource m_source;
    std::shared_ptr<const SceneRuntime> m_runtime;
};

Scene load_scene_file(const std::string& path) {
    raise_if_missing(path);
    return Scene(SceneDocument::read(path));
}

Vec3 to_vec3(const std::array<float, 3>& v, const char* what, bool nonzero) {
    const Vec3 p(v[0], v[1], v[2]);
    if (!is_finite(p))
        throw py::value_error(std::string(what) + " must be three finite numbers");
    if (nonzero && !(glm::length(p) > 0.0f))
        throw py::value_error(std::string(what) + " must be a non-zero vector");
    return p;
}

/// Renders on a worker thread with the GIL released while this thread polls for signals: a
/// KeyboardInterrupt (or any exception a signal handler raises) stops the render after the
/// current samples and is raised with the partial result as its `result` attribute.
py::object render(const Scene& scene, std::optional<int> spp, std::optional<int64_t> seed,
                  std::optional<int> threads, int64_t frame, bool progress) {
    std::vector<Override> extra;
    if (spp) {
        if (*spp < 1 || *spp > (1 << 20))
            throw py::value_error("spp must be in [1, 1048576], got " + std::to_string(*spp));
        extra.push_back(parse_override("/film/spp=" + std::to_string(*spp)));
    }
    if (seed) {
        if (*seed < 0)
            throw py::value_error("seed must be >= 0, got " + std::to_string(*seed));
        extra.push_back(parse_override("/render/seed=" + std::to_string(*seed)));
    }
    if (threads && (*threads < 0 || *threads > 1024))
        throw py::value_error("threads must be in [0, 1024] (0: all), got " +
                              std::to_string(*threads));
    if (frame < 0 || frame > int64_t{4294967295})
        throw py::value_error("frame must be in [0, 4294967295], got " + std::to_string(frame));
    const SceneSource source = scene.source_with(extra);

    RenderOptions options;
    options.threads = threads.value_or(0);
    options.progress = progress;
    std::atomic<bool> cancel{false};
    options.cancel = &cancel;
    std::shared_ptr<RenderedFrame> rendered;
    std::exception_ptr failure;
    std::optional<py::error_already_set> interrupt;
    {
        py::gil_scoped_release release;
        std::promise<void> done;
        std::future<void> finished = done.get_future();
        std::thread worker([&] {
            try {
                rendered = render_frame(source, frame, options);
            } catch (...) {
                failure = std::current_exception();
            }
            done.set_value();
        });
        while (finished.wait_for(kSignalPoll) != std::future_status::ready) {
            py::gil_scoped_acquire acquire;
            if (PyErr_CheckSignals() != 0) {
                interrupt.emplace();  // fetches and clears the raised exception
                cancel = true;
                break;
            }
        }
        worker.join();
    }
    if (failure)
        std::rethrow_exception(failure);
    py::object result = py::cast(rendered);
    if (interrupt) {
        interrupt->value().attr("result") = result;
        throw *interrupt;
    }
    return result;
}

}  // namespace

void bind_scene(py::module_& m) {
    py::class_<Scene>(m, "Scene",
                      "A scene file (docs/scene-format.md) with overrides, as `kasumi render "
                      "SCENE --set ...` reads it. Units: metres, lux, candela, cd/m², 1/m.")
        .def_static("load", &load_scene_file, py::arg("path"),
                    "Reads a scene file (JSON with comments). FileNotFoundError if it is missing, "
                    "SceneError if it is not a scene.")
        .def_static(
            "from_dict",
            [](const py::dict& d, const std::string& file) {
                return Scene(SceneDocument(to_json(d, file), file));
            },
            py::arg("d"), py::arg("file") = "<dict>",
            "A scene from a dict of the scene file's JSON; `file` names it in errors and its "
            "directory resolves relative file names (default: the working directory).")
        .def_property_readonly("file", &Scene::file)
        .def("set", &Scene::set, py::arg("pointer"), py::arg("value"),
             "Sets the value at a JSON pointer as `--set POINTER=VALUE` does: missing parents "
             "are created, \"-\" appends to an array, later sets win.")
        .def(
            "document", [](const Scene& s) { return from_json(s.source().document().json()); },
            "The scene's JSON with every set applied, as a dict.")
        .def(
            "plan",
            [](const Scene& s, int64_t frame) {
                return from_json(plan_to_json(make_plan(s.source().scene(frame))));
            },
            py::arg("frame") = 0, "The stages of frame `frame`, as `kasumi plan --json` prints.")
        .def("render", &render, py::arg("spp") = py::none(), py::arg("seed") = py::none(),
             py::arg("threads") = py::none(), py::arg("frame") = 0, py::arg("progress") = false,
             "Renders frame `frame` as `kasumi render` does (spp and seed override film.spp "
             "and render.seed; threads 0 or None: the scene's render.threads). The GIL is "
             "released; Ctrl-C raises KeyboardInterrupt whose `result` is the partial image.")
        .def(
            "probe_radiance",
            [](Scene& s, const std::array<float, 3>& origin, const std::array<float, 3>& direction,
               std::optional<int> spp) {
                const SceneRuntime& runtime = s.runtime();
                const Vec3 o = to_vec3(origin, "origin", false);
                const Vec3 d = to_vec3(direction, "direction", true);
                const int samples = spp.value_or(runtime.desc().film.spp);
                if (samples < 1 || samples > (1 << 24))
                    throw py::value_error("spp must be in [1, 16777216]");
                RadianceProbe p;
                {
                    py::gil_scoped_release release;
                    p = probe_radiance(runtime, o, d, samples);
                }
                return from_json(probe_json(p));
            },
            py::arg("origin"), py::arg("direction"), py::arg("spp") = py::none(),
            "Radiance (cd/m²) seen along one ray from `origin` (metres), as `kasumi probe "
            "radiance --json` reports it; spp defaults to film.spp.")
        .def(
            "probe_transmittance",
            [](Scene& s, const std::array<float, 3>& a, const std::array<float, 3>& b,
               std::optional<std::string> estimator_name_in, int samples) {
                const SceneRuntime& runtime = s.runtime();
                const Vec3 from = to_vec3(a, "a", false), to = to_vec3(b, "b", false);
                Estimator estimator = runtime.desc().render.volume.estimator;
                if (estimator_name_in) {
                    const auto e = estimator_from_name(*estimator_name_in);
                    if (!e)
                        throw py::value_error(
                            "estimator expects march, delta, ratio or residual-ratio, got \"" +
                            *estimator_name_in + "\"");
                    estimator = *e;
                }
                if (samples < 1 || samples > (1 << 24))
                    throw py::value_error("samples must be in [1, 16777216]");
                TransmittanceProbe p;
                {
                    py::gil_scoped_release release;
                    p = probe_transmittance(runtime, from, to, estimator, samples);
                }
                return from_json(probe_json(p, estimator));
            },
            py::arg("a"), py::arg("b"), py::arg("estimator") = py::none(),
            py::arg("samples") = 1000,
            "Transmittance of the media between points a and b (metres; surfaces ignored), as "
            "`kasumi probe transmittance` reports it; estimator defaults to the scene's.")
        .def(
            "probe_illuminance",
            [](Scene& s, const std::array<float, 3>& at, const std::array<float, 3>& normal,
               bool shadows, int samples) {
                const SceneRuntime& runtime = s.runtime();
                const Vec3 p_at = to_vec3(at, "at", false);
                const Vec3 n = glm::normalize(to_vec3(normal, "normal", true));
                if (samples < 1 || samples > (1 << 24))
                    throw py::value_error("samples must be in [1, 16777216]");
                IlluminanceProbe p;
                {
                    py::gil_scoped_release release;
                    p = probe_illuminance(runtime, p_at, n, shadows, samples);
                }
                return from_json(probe_json(p));
            },
            py::arg("at"), py::arg("normal"), py::arg("shadows") = true, py::arg("samples") = 4096,
            "Illuminance (lux) at a point (metres) on a surface facing `normal`, per light, as "
            "`kasumi probe illuminance` reports it (media left out).");
}

}  // namespace kasumi::python
