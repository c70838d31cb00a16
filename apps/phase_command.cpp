#include "apps/phase_command.h"

#include "apps/phase_args.h"
#include "core/error.h"
#include "phase/phase_json.h"
#include "phase/phase_validation.h"
#include "study/svg_plot.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <memory>
#include <optional>
#include <sstream>

namespace kasumi {

namespace {

[[noreturn]] void usage_error(const std::string& message) {
    throw Error(ErrorKind::Usage, "phase: " + message);
}

PhaseFunction build_model(const PhaseModelArgs& model) {
    return parse_phase(JsonNode(model.json, "command line"));
}

std::string number(double v) {
    std::ostringstream out;
    out << std::setprecision(10) << v;
    return out.str();
}

void add_eval(CLI::App& phase) {
    struct Options {
        std::unique_ptr<PhaseModelOptions> model;
        std::string theta_deg;
    };
    auto options = std::make_shared<Options>();
    CLI::App* cmd = phase.add_subcommand(
        "eval", "--model NAME [params] --theta-deg LIST: CSV theta_deg,value (1/sr, normalised)");
    options->model = std::make_unique<PhaseModelOptions>(*cmd);
    cmd->add_option("--theta-deg", options->theta_deg,
                    "scattering angles, degrees in [0, 180] (0 forward): a,b,c or A:B:N")
        ->required();
    cmd->callback([options] {
        const std::vector<double> angles = parse_angles(options->theta_deg);
        const PhaseFunction p = build_model(options->model->single());
        std::printf("theta_deg,value\n");
        for (const double t : angles)
            std::printf("%s,%s\n", number(t).c_str(),
                        number(eval_precise(p, std::cos(t * kPiD / 180.0))).c_str());
    });
}

void add_mie(CLI::App& phase) {
    struct Options {
        std::string x, radius_um, wavelength_nm, medium_index, m, theta_deg;
    };
    auto options = std::make_shared<Options>();
    CLI::App* cmd = phase.add_subcommand(
        "mie",
        "--x X | --radius-um R [--wavelength-nm L] [--medium-index N], --m RE,IM "
        "[--theta-deg LIST]: Lorenz-Mie efficiencies and amplitudes as JSON");
    const auto add = [cmd](const std::string& names, std::string& value, const std::string& help) {
        // The last of a repeated option counts.
        cmd->add_option(names, value, help)->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    };
    add("-x,--x", options->x, "size parameter 2π r n_medium / λ, in (0, 1e5]");
    add("--radius-um", options->radius_um, "sphere radius, µm");
    add("--wavelength-nm", options->wavelength_nm, "vacuum wavelength, nm (default 550)");
    add("--medium-index", options->medium_index, "refractive index of the medium (default 1)");
    add("-m,--m", options->m, "refractive index of the sphere RE[,IM] (m = n + ik, k >= 0)");
    add("--theta-deg", options->theta_deg, "angles of S1, S2: a,b,c or A:B:N, degrees");
    cmd->callback([options] {
        const Options& o = *options;
        std::optional<double> x, radius, wavelength, medium;
        std::optional<Complex> m;
        std::vector<double> angles;
        if (!o.x.empty())
            x = require_number("x", o.x);
        if (!o.radius_um.empty())
            radius = require_number("radius-um", o.radius_um);
        if (!o.wavelength_nm.empty())
            wavelength = require_number("wavelength-nm", o.wavelength_nm);
        if (!o.medium_index.empty())
            medium = require_number("medium-index", o.medium_index);
        if (!o.theta_deg.empty())
            angles = parse_angles(o.theta_deg);
        if (!o.m.empty()) {
            const std::vector<double> parts = parse_number_list("m", o.m);
            if (parts.size() > 2)
                usage_error("--m expects RE,IM");
            m = Complex(parts[0], parts.size() > 1 ? parts[1] : 0.0);
        }
        if (!m)
            usage_error("mie needs --m RE,IM");
        if (x && (radius || wavelength))
            usage_error("mie: give either --x or --radius-um/--wavelength-nm, not both");
        if (!x && !radius)
            usage_error("mie needs --x X or --radius-um R [--wavelength-nm L]");
        if (!(m->real() > 0.0))
            throw_input_error("mie: --m real part must be > 0");
        if (!(m->imag() >= 0.0))
            throw_input_error(
                "mie: --m imaginary part must be >= 0 (m = n + ik, Bohren & Huffman)");
        const double n_medium = medium.value_or(1.0);
        if (!(n_medium > 0.0))
            throw_input_error("mie: --medium-index must be > 0");
        double size = 0.0;
        if (x) {
            size = *x;
        } else {
            if (!(*radius > 0.0))
                throw_input_error("mie: --radius-um must be > 0");
            const double lambda = wavelength.value_or(550.0);
            if (!(lambda > 0.0))
                throw_input_error("mie: --wavelength-nm must be > 0");
            size = 2.0 * kPiD * *radius * n_medium / (lambda * 1e-3);
        }
        if (!(size > 0.0 && size <= 1e5))
            throw_input_error("mie: size parameter must be in (0, 1e5]");
        const Complex m_rel = *m / n_medium;
        const LorenzMie sphere(size, m_rel);
        const MieEfficiencies q = sphere.efficiencies();
        Json out = Json::object();
        out["x"] = size;
        out["m"] = {m_rel.real(), m_rel.imag()};
        out["qext"] = q.qext;
        out["qsca"] = q.qsca;
        out["qabs"] = q.qabs;
        out["qback"] = q.qback;
        out["g"] = q.g;
        out["n_terms"] = sphere.n_terms();
        out["convention"] = "Bohren & Huffman: m = n + ik, S1 perpendicular, S2 parallel";
        if (!angles.empty()) {
            Json theta = Json::array(), s1 = Json::array(), s2 = Json::array();
            for (const double t : angles) {
                Complex a, b;
                sphere.amplitudes(std::cos(t * kPiD / 180.0), a, b);
                theta.push_back(t);
                s1.push_back({a.real(), a.imag()});
                s2.push_back({b.real(), b.imag()});
            }
            out["theta_deg"] = theta;
            out["s1"] = s1;
            out["s2"] = s2;
        }
        std::printf("%s\n", out.dump(2).c_str());
    });
}

void add_validate(CLI::App& phase) {
    struct Options {
        std::unique_ptr<PhaseModelOptions> model;
        std::string samples, seed, significance, n_tests;
    };
    auto options = std::make_shared<Options>();
    CLI::App* cmd = phase.add_subcommand(
        "validate",
        "--model NAME [params] [--samples N] [--seed S] [--significance R] [--n-tests K]: "
        "property checks; exit 5 on failure");
    options->model = std::make_unique<PhaseModelOptions>(*cmd);
    cmd->add_option("--samples", options->samples,
                    "samples of the sampler checks, an integer in [1000, 1e9] (default 4e6)");
    cmd->add_option("--seed", options->seed, "random seed, a non-negative integer (default 1)");
    cmd->add_option("--significance", options->significance,
                    "false-failure rate of the whole run of --n-tests statistical checks, in "
                    "(0, 1) (default 1e-4)");
    cmd->add_option("--n-tests", options->n_tests,
                    "statistical checks sharing --significance (Sidak), e.g. one per model a "
                    "script validates (default 1)");
    cmd->callback([options] {
        ValidationOptions validation;
        if (!options->samples.empty()) {
            const double n = require_number("samples", options->samples);
            if (!(n >= 1000 && n <= 1e9) || n != std::floor(n))
                usage_error("--samples must be an integer in [1000, 1e9]");
            validation.samples = static_cast<int>(n);
        }
        if (!options->seed.empty()) {
            const double n = require_number("seed", options->seed);
            if (!(n >= 0) || n != std::floor(n))
                usage_error("--seed must be a non-negative integer");
            validation.seed = static_cast<uint64_t>(n);
        }
        if (!options->significance.empty()) {
            const double r = require_number("significance", options->significance);
            if (!(r > 0.0 && r < 1.0))
                usage_error("--significance must be in (0, 1)");
            validation.significance = r;
        }
        if (!options->n_tests.empty()) {
            const double n = require_number("n-tests", options->n_tests);
            if (!(n >= 1 && n <= 1e6) || n != std::floor(n))
                usage_error("--n-tests must be an integer in [1, 1e6]");
            validation.n_tests = static_cast<int>(n);
        }
        const PhaseFunction p = build_model(options->model->single());
        const std::vector<PhaseCheck> checks = validate_phase(p, validation);
        std::printf("decision rule: %s\n", decision_rule(validation).c_str());
        std::printf("%-16s %-6s %-22s %-22s %-12s %-12s %s\n", "check", "result", "value",
                    "expected", "tolerance", "p_value", "detail");
        bool all_passed = true;
        for (const PhaseCheck& c : checks) {
            const std::string p_value = c.p_value ? number(*c.p_value) : "-";
            std::printf("%-16s %-6s %-22s %-22s %-12s %-12s %s\n", c.name.c_str(),
                        c.passed ? "pass" : "FAIL", number(c.value).c_str(),
                        number(c.expected).c_str(), number(c.tolerance).c_str(), p_value.c_str(),
                        c.detail.c_str());
            all_passed = all_passed && c.passed;
        }
        std::fflush(stdout);
        if (!all_passed)
            throw Error(ErrorKind::Validation,
                        "phase validate: " + phase_model_name(p) + " failed at least one check");
    });
}

/// p(θ) of every model at 721 angles (1/4 degree), log-scaled over at most 8 decades.
LinePlot phase_plot(const std::vector<PhaseModelArgs>& models) {
    constexpr int n = 721;
    LinePlot plot;
    plot.x = {"scattering angle θ (degrees, 0 = forward)", AxisScale::Linear, 0.0, 180.0, 30.0};
    plot.y.label = "p(θ) [1/sr]";
    plot.y.max_decades = 8;
    for (const PhaseModelArgs& m : models) {
        const PhaseFunction p = build_model(m);
        PlotSeries series{m.label, {}, false};
        for (int i = 0; i < n; ++i) {
            series.points.push_back(
                {180.0 * i / (n - 1), eval_precise(p, std::cos(kPiD * i / (n - 1)))});
        }
        plot.series.push_back(std::move(series));
    }
    return plot;
}

void add_plot(CLI::App& phase) {
    struct Options {
        std::unique_ptr<PhaseModelOptions> model;
        std::string output;
    };
    auto options = std::make_shared<Options>();
    CLI::App* cmd = phase.add_subcommand(
        "plot", "--model A [params] [--model B ...] -o plot.svg: log-scale p(theta)");
    options->model = std::make_unique<PhaseModelOptions>(*cmd);
    cmd->add_option("-o,--output", options->output, "SVG file to write")
        ->required()
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    cmd->callback([options] {
        const std::vector<PhaseModelArgs> models = options->model->models();
        if (models.empty())
            usage_error("plot needs at least one --model");
        const std::string svg = svg_line_plot(phase_plot(models));
        std::ofstream file(options->output);
        if (!(file << svg))
            throw_output_error("phase plot: cannot write " + options->output);
    });
}

}  // namespace

void add_phase_command(CLI::App& root) {
    CLI::App* phase =
        root.add_subcommand("phase", "Evaluate, compute (Lorenz-Mie) and validate phase functions");
    phase->require_subcommand(1);
    add_eval(*phase);
    add_mie(*phase);
    add_validate(*phase);
    add_plot(*phase);
}

}  // namespace kasumi
