/// kasumi.phase: every phase model by its scene-file name and parameters, evaluated, sampled
/// and validated on NumPy arrays by the library's own functions.
#include "bindings.h"
#include "json_bridge.h"

#include "core/json_node.h"
#include "phase/phase_json.h"
#include "phase/phase_quadrature.h"
#include "phase/phase_validation.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <type_traits>

namespace py = pybind11;

namespace kasumi::python {

namespace {

/// A phase function with the model name it was made from.
struct Phase {
    PhaseFunction model;
    std::string name;
};

/// {"model": ..., params} -> Phase through parse_phase, so errors are the scene loader's:
/// "<source>: <pointer>/g = 1.2: must be in (-1, 1)".
Phase make_phase(const py::dict& description, const std::string& source,
                 const std::string& pointer) {
    const Json json = to_json(description, source);
    Phase p{parse_phase(JsonNode(json, source, pointer)), ""};
    p.name = phase_model_name(p.model);
    return p;
}

/// An output array for `in`: `out` when given (same shape, dtype T, C-contiguous, so repeated
/// calls skip the allocation and its page faults), else a new one.
template <typename T>
py::array_t<T> output_for(const py::array& in, const py::object& out) {
    if (out.is_none())
        return py::array_t<T>(std::vector<py::ssize_t>(in.shape(), in.shape() + in.ndim()));
    if (!py::isinstance<py::array_t<T>>(out))
        throw py::type_error(std::string("out must be a ") +
                             (std::is_same_v<T, float> ? "float32" : "float64") +
                             " array (the dtype of the result)");
    auto a = out.cast<py::array_t<T>>();
    if (!(a.flags() & py::array::c_style) || !a.writeable() || a.ndim() != in.ndim() ||
        !std::equal(in.shape(), in.shape() + in.ndim(), a.shape()))
        throw py::value_error("out must be a writeable C-contiguous array of mu's shape");
    return a;
}

/// out[i] = f(in[i]) over arrays of any shape, with the GIL released for long ones.
template <typename T, typename F>
py::array_t<T> map_array(const py::array_t<T, py::array::c_style | py::array::forcecast>& in,
                         const py::object& out_in, F f) {
    py::array_t<T> out = output_for<T>(in, out_in);
    const T* src = in.data();
    T* dst = out.mutable_data();
    const py::ssize_t n = in.size();
    const auto loop = [&] {
        for (py::ssize_t i = 0; i < n; ++i)
            dst[i] = f(src[i]);
    };
    if (n >= kReleaseGilFrom) {
        py::gil_scoped_release release;
        loop();
    } else {
        loop();
    }
    return out;
}

py::array as_array(const py::object& mu_in) {
    py::array mu = py::array::ensure(mu_in);
    if (!mu)
        throw py::type_error("mu must be a number or an array of numbers");
    return mu;
}

/// float32 input: the renderer's float path; anything else: the double-precision path. The
/// model is resolved once per call (std::visit outside the loop), not per element.
py::array evaluate(const Phase& p, const py::object& mu_in, const py::object& out) {
    const py::array mu = as_array(mu_in);
    return std::visit(
        [&](const auto& model) -> py::array {
            if (py::isinstance<py::array_t<float>>(mu))
                return map_array<float>(mu, out, [&](float m) { return eval(model, m); });
            return map_array<double>(mu, out, [&](double m) { return eval_precise(model, m); });
        },
        p.model);
}
/// Every model samples exactly (pdf == eval; validate_phase checks it), as pdf_precise says.
py::array density(const Phase& p, const py::object& mu_in, const py::object& out) {
    const py::array mu = as_array(mu_in);
    return std::visit(
        [&](const auto& model) -> py::array {
            if (py::isinstance<py::array_t<float>>(mu))
                return map_array<float>(mu, out, [&](float m) { return pdf(model, m); });
            return map_array<double>(mu, out, [&](double m) { return eval_precise(model, m); });
        },
        p.model);
}

/// Samples for u1, u2 in [0, 1) (broadcast to one shape): mu = cos θ of each sampled direction
/// and its pdf per steradian, from the library's sample() about wo = +z. θ is recovered as
/// atan2(sin, cos) in double from the float direction, which keeps 1 - mu of narrow peaks.
py::tuple draw(const Phase& p, const py::object& u1_in, const py::object& u2_in) {
    py::object np = py::module_::import("numpy");
    py::tuple both = np.attr("broadcast_arrays")(u1_in, u2_in);
    const auto u1 = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(
        np.attr("ascontiguousarray")(both[0]));
    const auto u2 = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(
        np.attr("ascontiguousarray")(both[1]));
    const std::vector<py::ssize_t> shape(u1.shape(), u1.shape() + u1.ndim());
    py::array_t<double> mu(shape), pdf_out(shape);
    const float* a = u1.data();
    const float* b = u2.data();
    double* m = mu.mutable_data();
    double* d = pdf_out.mutable_data();
    const py::ssize_t n = u1.size();
    const auto loop = [&] {
        const Vec3 wo(0.0f, 0.0f, 1.0f);
        for (py::ssize_t i = 0; i < n; ++i) {
            const PhaseSample s = sample(p.model, wo, Vec2(a[i], b[i]));
            // Propagation -wi about wo = +z: cos θ = -wi.z.
            const double sin_theta = std::hypot(double(s.wi.x), double(s.wi.y));
            m[i] = std::cos(std::atan2(sin_theta, -double(s.wi.z)));
            d[i] = s.pdf;
        }
    };
    if (n >= kReleaseGilFrom) {
        py::gil_scoped_release release;
        loop();
    } else {
        loop();
    }
    return py::make_tuple(mu, pdf_out);
}

ValidationOptions options_from(std::optional<int> samples, std::optional<uint64_t> seed,
                               std::optional<double> significance, std::optional<int> n_tests) {
    ValidationOptions o;
    if (samples) {
        if (*samples < 1000)
            throw py::value_error("samples must be >= 1000");
        o.samples = *samples;
    }
    if (seed)
        o.seed = *seed;
    if (significance) {
        if (!(*significance > 0.0 && *significance < 1.0))
            throw py::value_error("significance must be in (0, 1)");
        o.significance = *significance;
    }
    if (n_tests) {
        if (*n_tests < 1)
            throw py::value_error("n_tests must be >= 1");
        o.n_tests = *n_tests;
    }
    return o;
}

py::dict validate(const Phase& p, const ValidationOptions& o) {
    std::vector<PhaseCheck> checks;
    {
        py::gil_scoped_release release;
        checks = validate_phase(p.model, o);
    }
    py::list list;
    bool passed = true;
    for (const PhaseCheck& c : checks) {
        py::dict d;
        d["name"] = c.name;
        d["passed"] = c.passed;
        d["value"] = c.value;
        d["expected"] = c.expected;
        d["tolerance"] = c.tolerance;
        d["detail"] = c.detail;
        d["p_value"] = c.p_value ? py::object(py::float_(*c.p_value)) : py::object(py::none());
        d["alpha"] = c.alpha ? py::object(py::float_(*c.alpha)) : py::object(py::none());
        list.append(d);
        passed = passed && c.passed;
    }
    py::dict out;
    out["model"] = p.name;
    out["passed"] = passed;
    out["decision_rule"] = decision_rule(o);
    out["significance"] = o.significance;
    out["n_tests"] = o.n_tests;
    out["alpha"] = per_check_alpha(o);
    out["samples"] = o.samples;
    out["seed"] = o.seed;
    out["checks"] = list;
    return out;
}

Phase as_phase(const py::object& model) {
    if (py::isinstance<Phase>(model))
        return model.cast<Phase>();
    if (py::isinstance<py::dict>(model))
        return make_phase(model.cast<py::dict>(), "phase", "");
    throw py::type_error("expected a kasumi.phase.Phase or a dict like {\"model\": \"hg\", ...}");
}

double one(double) {
    return 1.0;
}
double identity(double mu) {
    return mu;
}

}  // namespace

void bind_phase(py::module_& m) {
    py::class_<Phase>(m, "Phase",
                      "A phase function p(mu), mu = cos θ (+1 forward), per steradian, "
                      "normalised to 1 over the sphere. Make one with kasumi.phase.make().")
        .def_property_readonly(
            "model", [](const Phase& p) { return p.name; }, "The model's name in scene files")
        .def("eval", &evaluate, py::arg("mu"), py::kw_only(), py::arg("out") = py::none(),
             "p(mu) in 1/sr on an array of any shape. float32 in: the renderer's float path, "
             "float32 out; anything else: the double-precision path, float64 out. `out`: an "
             "array of mu's shape and the result's dtype to write into.")
        .def("pdf", &density, py::arg("mu"), py::kw_only(), py::arg("out") = py::none(),
             "The sampling density per steradian (equal to eval for every model), same dtypes "
             "as eval.")
        .def("sample", &draw, py::arg("u1"), py::arg("u2"),
             "(mu, pdf) arrays for uniform numbers u1, u2 in [0, 1) (broadcast together); pdf "
             "per steradian.")
        .def(
            "mean_cosine", [](const Phase& p) { return double(mean_cosine(p.model)); },
            "The library's mean cosine g = 2π ∫ mu p(mu) dmu (closed form or the table's).")
        .def(
            "normalisation",
            [](const Phase& p) {
                py::gil_scoped_release release;
                return integrate_phase(p.model, one);
            },
            "2π ∫ p(mu) dmu by the library's adaptive quadrature (1 for every correct model).")
        .def(
            "mean_cosine_quadrature",
            [](const Phase& p) {
                py::gil_scoped_release release;
                return integrate_phase(p.model, identity);
            },
            "2π ∫ mu p(mu) dmu by the library's adaptive quadrature.")
        .def("__repr__", [](const Phase& p) {
            return "<kasumi.phase.Phase " + p.name +
                   ", g = " + std::to_string(mean_cosine(p.model)) + ">";
        });

    m.def("make", &make_phase, py::arg("description"), py::arg("source") = "phase",
          py::arg("pointer") = "",
          "A phase function from its scene-file object, e.g. {\"model\": \"hg\", \"g\": 0.8}. "
          "Invalid input raises kasumi.SceneError with the loader's message, located at "
          "`source`: `pointer`.");
    m.def("models", &phase_model_names, "Every model name make() accepts.");
    m.def(
        "validate",
        [](const py::object& model, std::optional<int> samples, std::optional<uint64_t> seed,
           std::optional<double> significance, std::optional<int> n_tests) {
            return validate(as_phase(model), options_from(samples, seed, significance, n_tests));
        },
        py::arg("model"), py::kw_only(), py::arg("samples") = py::none(),
        py::arg("seed") = py::none(), py::arg("significance") = py::none(),
        py::arg("n_tests") = py::none(),
        "The checks of `kasumi phase validate` as a dict: passed, decision_rule, alpha (per "
        "statistical check: 1 - (1 - significance)^(1/n_tests)) and checks, each with name, "
        "passed, value, expected, tolerance, detail, p_value and alpha (None for deterministic "
        "checks). Defaults are the CLI's: 4e6 samples, seed 1, significance 1e-4, n_tests 1.");
    m.def(
        "chi_square_power",
        [](const py::object& reference, const py::object& alternative, std::optional<int> samples,
           std::optional<double> significance, std::optional<int> n_tests) {
            const Phase r = as_phase(reference), a = as_phase(alternative);
            const ValidationOptions o = options_from(samples, std::nullopt, significance, n_tests);
            py::gil_scoped_release release;
            return chi_square_power(r.model, a.model, o);
        },
        py::arg("reference"), py::arg("alternative"), py::kw_only(),
        py::arg("samples") = py::none(), py::arg("significance") = py::none(),
        py::arg("n_tests") = py::none(),
        "Probability that validate's chi-square test rejects `reference` when the sampler "
        "follows `alternative`.");
    m.def(
        "_cpp_eval_seconds",
        [](const Phase& p,
           const py::array_t<double, py::array::c_style | py::array::forcecast>& mu) {
            // The yardstick of bench/python_phase_eval.py: the same eval_precise loop over a
            // C++ vector, no NumPy, no Python; the volatile read keeps the loop.
            const std::vector<double> in(mu.data(), mu.data() + mu.size());
            std::vector<double> out(in.size());
            py::gil_scoped_release release;
            const auto start = std::chrono::steady_clock::now();
            for (size_t i = 0; i < in.size(); ++i)
                out[i] = eval_precise(p.model, in[i]);
            const double seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            volatile double sink = out.empty() ? 0.0 : out[out.size() / 2];
            (void)sink;
            return seconds;
        },
        py::arg("phase"), py::arg("mu"), "Benchmark support: seconds of the C++ eval loop.");
    m.def("chi_square_q", &upper_incomplete_gamma_q, py::arg("a"), py::arg("x"),
          "Regularised upper incomplete gamma Q(a, x): the chi-square tail P(χ²_k > s) = "
          "Q(k/2, s/2).");
}

}  // namespace kasumi::python
