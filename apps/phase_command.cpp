#include "apps/phase_command.h"

#include "core/error.h"
#include "phase/phase_json.h"
#include "phase/phase_validation.h"

#include <cstdio>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>

namespace kasumi {

namespace {

[[noreturn]] void usage_error(const std::string& message) {
    throw Error(ErrorKind::Usage, "phase: " + message);
}

/// `--name value` / `--name=value` pairs in command-line order.
using Options = std::vector<std::pair<std::string, std::string>>;

Options parse_pairs(const std::vector<std::string>& args) {
    Options out;
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a.rfind("--", 0) != 0 && !(a.size() == 2 && a[0] == '-'))
            usage_error("unexpected argument '" + a + "'");
        std::string name = a.substr(a[1] == '-' ? 2 : 1);
        std::string value;
        const auto eq = name.find('=');
        if (eq != std::string::npos) {
            value = name.substr(eq + 1);
            name = name.substr(0, eq);
        } else {
            if (i + 1 >= args.size())
                usage_error("option --" + name + " needs a value");
            value = args[++i];
        }
        out.emplace_back(name, value);
    }
    return out;
}

std::optional<double> to_number(const std::string& text) {
    try {
        size_t used = 0;
        const double v = std::stod(text, &used);
        if (used == text.size())
            return v;
    } catch (const std::exception&) {
    }
    return std::nullopt;
}

double require_number(const std::string& name, const std::string& text) {
    const auto v = to_number(text);
    if (!v)
        usage_error("--" + name + " expects a number, got '" + text + "'");
    return *v;
}

/// Scene-file JSON for one model: --g 0.5 → "g": 0.5, --m 1.33,0 → "m": [1.33, 0].
Json model_json(const Options& options) {
    Json json = Json::object();
    for (const auto& [name, value] : options) {
        std::string key = name;
        std::replace(key.begin(), key.end(), '-', '_');
        if (json.contains(key))
            usage_error("--" + name + " given twice for one model");
        if (const auto number = to_number(value)) {
            json[key] = *number;
        } else if (value.find(',') != std::string::npos) {
            Json array = Json::array();
            std::stringstream parts(value);
            std::string part;
            while (std::getline(parts, part, ','))
                array.push_back(require_number(name, part));
            json[key] = array;
        } else {
            json[key] = value;
        }
    }
    if (!json.contains("model"))
        usage_error("--model NAME is required");
    return json;
}

PhaseFunction build_model(const Options& options) {
    const Json json = model_json(options);
    return parse_phase(JsonNode(json, "command line"));
}

/// "a,b,c" or "A:B:N" (N evenly spaced values from A to B inclusive).
std::vector<double> parse_list(const std::string& name, const std::string& text) {
    std::vector<double> out;
    if (text.find(':') != std::string::npos) {
        std::stringstream parts(text);
        std::string a, b, n;
        if (!std::getline(parts, a, ':') || !std::getline(parts, b, ':') ||
            !std::getline(parts, n, ':'))
            usage_error("--" + name + " expects A:B:N");
        const double lo = require_number(name, a), hi = require_number(name, b);
        const double count = require_number(name, n);
        if (!(count >= 1.0) || count != std::floor(count) || count > 1e7)
            usage_error("--" + name + ": N must be a positive integer");
        const int c = static_cast<int>(count);
        for (int i = 0; i < c; ++i)
            out.push_back(c == 1 ? lo : lo + (hi - lo) * i / (c - 1));
    } else {
        std::stringstream parts(text);
        std::string part;
        while (std::getline(parts, part, ','))
            out.push_back(require_number(name, part));
    }
    if (out.empty())
        usage_error("--" + name + " is empty");
    return out;
}

std::vector<double> parse_angles(const std::string& text) {
    std::vector<double> angles = parse_list("theta-deg", text);
    for (const double t : angles)
        if (!(t >= 0.0 && t <= 180.0))
            throw_input_error("phase: --theta-deg values must be in [0, 180]");
    return angles;
}

/// Splits off the options a subcommand itself owns; the rest describe the model.
Options take(Options& options, const std::vector<std::string>& names, Options& taken) {
    Options rest;
    for (auto& o : options) {
        if (std::find(names.begin(), names.end(), o.first) != names.end())
            taken.push_back(o);
        else
            rest.push_back(o);
    }
    return rest;
}

std::optional<std::string> find(const Options& options, const std::string& name) {
    std::optional<std::string> found;
    for (const auto& o : options)
        if (o.first == name) {
            if (found)
                usage_error("--" + name + " given twice");
            found = o.second;
        }
    return found;
}

std::string number(double v) {
    std::ostringstream out;
    out << std::setprecision(10) << v;
    return out.str();
}

void run_eval(const std::vector<std::string>& args) {
    Options all = parse_pairs(args), own;
    const Options model = take(all, {"theta-deg"}, own);
    const auto theta = find(own, "theta-deg");
    if (!theta)
        usage_error("eval needs --theta-deg LIST");
    const std::vector<double> angles = parse_angles(*theta);
    const PhaseFunction p = build_model(model);
    std::printf("theta_deg,value\n");
    for (const double t : angles)
        std::printf("%s,%s\n", number(t).c_str(),
                    number(eval_precise(p, std::cos(t * kPiD / 180.0))).c_str());
}

void run_mie(const std::vector<std::string>& args) {
    const Options all = parse_pairs(args);
    std::optional<double> x, radius, wavelength, medium;
    std::optional<Complex> m;
    std::vector<double> angles;
    for (const auto& [name, value] : all) {
        if (name == "x")
            x = require_number(name, value);
        else if (name == "radius-um")
            radius = require_number(name, value);
        else if (name == "wavelength-nm")
            wavelength = require_number(name, value);
        else if (name == "medium-index")
            medium = require_number(name, value);
        else if (name == "theta-deg")
            angles = parse_angles(value);
        else if (name == "m") {
            const std::vector<double> parts = parse_list("m", value);
            if (parts.size() > 2)
                usage_error("--m expects RE,IM");
            m = Complex(parts[0], parts.size() > 1 ? parts[1] : 0.0);
        } else
            usage_error("mie: unknown option --" + name);
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
        throw_input_error("mie: --m imaginary part must be >= 0 (m = n + ik, Bohren & Huffman)");
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
}

void run_validate(const std::vector<std::string>& args) {
    Options all = parse_pairs(args), own;
    const Options model = take(all, {"samples", "seed"}, own);
    ValidationOptions options;
    if (const auto s = find(own, "samples")) {
        const double n = require_number("samples", *s);
        if (!(n >= 1000 && n <= 1e9) || n != std::floor(n))
            usage_error("--samples must be an integer in [1000, 1e9]");
        options.samples = static_cast<int>(n);
    }
    if (const auto s = find(own, "seed")) {
        const double n = require_number("seed", *s);
        if (!(n >= 0) || n != std::floor(n))
            usage_error("--seed must be a non-negative integer");
        options.seed = static_cast<uint64_t>(n);
    }
    const PhaseFunction p = build_model(model);
    const std::vector<PhaseCheck> checks = validate_phase(p, options);
    std::printf("%-16s %-6s %-22s %-22s %-12s %s\n", "check", "result", "value", "expected",
                "tolerance", "detail");
    bool all_passed = true;
    for (const PhaseCheck& c : checks) {
        std::printf("%-16s %-6s %-22s %-22s %-12s %s\n", c.name.c_str(), c.passed ? "pass" : "FAIL",
                    number(c.value).c_str(), number(c.expected).c_str(),
                    number(c.tolerance).c_str(), c.detail.c_str());
        all_passed = all_passed && c.passed;
    }
    std::fflush(stdout);
    if (!all_passed)
        throw Error(ErrorKind::Validation,
                    "phase validate: " + phase_model_name(p) + " failed at least one check");
}

std::string svg_escape(const std::string& s) {
    std::string out;
    for (const char c : s) {
        if (c == '<')
            out += "&lt;";
        else if (c == '>')
            out += "&gt;";
        else if (c == '&')
            out += "&amp;";
        else
            out += c;
    }
    return out;
}

void run_plot(const std::vector<std::string>& args) {
    const Options all = parse_pairs(args);
    std::optional<std::string> output;
    std::vector<Options> models;
    for (const auto& o : all) {
        if (o.first == "o" || o.first == "output") {
            output = o.second;
        } else if (o.first == "model") {
            models.push_back({o});
        } else {
            if (models.empty())
                usage_error("plot: model parameters must follow a --model");
            models.back().push_back(o);
        }
    }
    if (!output)
        usage_error("plot needs -o plot.svg");
    if (models.empty())
        usage_error("plot needs at least one --model");
    const int n = 721;
    std::vector<std::vector<double>> curves;
    std::vector<std::string> labels;
    double lo = INFINITY, hi = 0.0;
    for (const Options& m : models) {
        const PhaseFunction p = build_model(m);
        std::string label;
        for (const auto& [name, value] : m)
            label += (label.empty() ? "" : " ") + (name == "model" ? value : name + "=" + value);
        labels.push_back(label);
        std::vector<double> values(n);
        for (int i = 0; i < n; ++i) {
            values[static_cast<size_t>(i)] = eval_precise(p, std::cos(kPiD * i / (n - 1)));
            if (values[static_cast<size_t>(i)] > 0.0)
                lo = std::min(lo, values[static_cast<size_t>(i)]);
            hi = std::max(hi, values[static_cast<size_t>(i)]);
        }
        curves.push_back(values);
    }
    const double top = std::pow(10.0, std::ceil(std::log10(hi)));
    const double bottom = std::max(std::pow(10.0, std::floor(std::log10(lo))), top * 1e-8);
    const double w = 800, h = 500, left = 80, right = 20, up = 20, down = 60;
    const auto px = [&](double theta_deg) { return left + (w - left - right) * theta_deg / 180.0; };
    const auto py = [&](double v) {
        const double t = (std::log10(std::max(v, bottom)) - std::log10(bottom)) /
                         (std::log10(top) - std::log10(bottom));
        return h - down - (h - up - down) * t;
    };
    std::ostringstream svg;
    svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << w << "\" height=\"" << h
        << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
        << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    for (double d = std::log10(bottom); d <= std::log10(top) + 1e-9; d += 1.0) {
        const double y = py(std::pow(10.0, d));
        svg << "<line x1=\"" << left << "\" x2=\"" << w - right << "\" y1=\"" << y << "\" y2=\""
            << y << "\" stroke=\"#ddd\"/>\n<text x=\"" << left - 8 << "\" y=\"" << y + 4
            << "\" text-anchor=\"end\">1e" << static_cast<int>(std::round(d)) << "</text>\n";
    }
    for (int t = 0; t <= 180; t += 30)
        svg << "<line x1=\"" << px(t) << "\" x2=\"" << px(t) << "\" y1=\"" << up << "\" y2=\""
            << h - down << "\" stroke=\"#ddd\"/>\n<text x=\"" << px(t) << "\" y=\"" << h - down + 18
            << "\" text-anchor=\"middle\">" << t << "</text>\n";
    svg << "<text x=\"" << (left + w - right) / 2 << "\" y=\"" << h - 15
        << "\" text-anchor=\"middle\">scattering angle θ (degrees, 0 = forward)</text>\n"
        << "<text x=\"18\" y=\"" << (up + h - down) / 2 << "\" transform=\"rotate(-90 18 "
        << (up + h - down) / 2 << ")\" text-anchor=\"middle\">p(θ) [1/sr]</text>\n";
    const char* colours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf"};
    for (size_t c = 0; c < curves.size(); ++c) {
        svg << "<polyline fill=\"none\" stroke-width=\"1.5\" stroke=\"" << colours[c % 6]
            << "\" points=\"";
        for (int i = 0; i < n; ++i)
            svg << px(180.0 * i / (n - 1)) << ',' << py(curves[c][static_cast<size_t>(i)]) << ' ';
        svg << "\"/>\n<text x=\"" << w - right - 10 << "\" y=\"" << up + 16 + 16 * c
            << "\" text-anchor=\"end\" fill=\"" << colours[c % 6] << "\">" << svg_escape(labels[c])
            << "</text>\n";
    }
    svg << "</svg>\n";
    std::ofstream file(*output);
    if (!(file << svg.str()))
        throw_output_error("phase plot: cannot write " + *output);
}

void add(CLI::App& phase, const std::string& name, const std::string& description,
         void (*run)(const std::vector<std::string>&)) {
    CLI::App* sub = phase.add_subcommand(name, description);
    sub->allow_extras();
    sub->callback([sub, run] { run(sub->remaining()); });
}

}  // namespace

void add_phase_command(CLI::App& root) {
    CLI::App* phase =
        root.add_subcommand("phase", "Evaluate, compute (Lorenz-Mie) and validate phase functions");
    phase->require_subcommand(1);
    add(*phase, "eval",
        "--model NAME [params] --theta-deg LIST: CSV theta_deg,value (1/sr, normalised)", run_eval);
    add(*phase, "mie",
        "--x X | --radius-um R [--wavelength-nm L] [--medium-index N], --m RE,IM "
        "[--theta-deg LIST]: Lorenz-Mie efficiencies and amplitudes as JSON",
        run_mie);
    add(*phase, "validate",
        "--model NAME [params] [--samples N] [--seed S]: property checks; exit 5 on failure",
        run_validate);
    add(*phase, "plot", "--model A [params] [--model B ...] -o plot.svg: log-scale p(theta)",
        run_plot);
}

}  // namespace kasumi
