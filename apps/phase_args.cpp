#include "apps/phase_args.h"

#include "core/error.h"
#include "phase/phase_json.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>

namespace kasumi {

namespace {

[[noreturn]] void usage_error(const std::string& message) {
    throw Error(ErrorKind::Usage, "phase: " + message);
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

/// --g 0.5 → 0.5, --m 1.33,0 → [1.33, 0], --model hg → "hg".
Json parameter_value(const std::string& name, const std::string& value) {
    if (const auto number = to_number(value))
        return *number;
    if (value.find(',') == std::string::npos)
        return value;
    Json array = Json::array();
    std::stringstream parts(value);
    std::string part;
    while (std::getline(parts, part, ','))
        array.push_back(require_number(name, part));
    return array;
}

/// "diameter_um" → "--diameter-um"; a one-letter key gets the short form too ("-g,--g").
std::string option_names(const std::string& key) {
    std::string name = key;
    std::replace(name.begin(), name.end(), '_', '-');
    return (name.size() == 1 ? "-" + name + "," : "") + "--" + name;
}

CLI::Option* repeatable(CLI::Option* option) {
    return option->type_size(1)->expected(1)->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
}

}  // namespace

PhaseModelOptions::PhaseModelOptions(CLI::App& command) : m_command(&command) {
    std::string models;
    for (const std::string& name : phase_model_names())
        models += (models.empty() ? "" : ", ") + name;
    m_model = repeatable(command.add_option("--model")->description("phase function: " + models));
    for (const std::string& key : phase_parameter_names()) {
        m_parameters.push_back(repeatable(
            command.add_option(option_names(key))
                ->description("the model's \"" + key + "\" (docs/phase.md); RE,IM for m")));
    }
}

std::vector<PhaseModelArgs> PhaseModelOptions::collect(bool one_model) const {
    std::vector<PhaseModelArgs> out;
    if (one_model)
        out.push_back({Json::object(), ""});
    std::map<const CLI::Option*, size_t> seen;  // occurrences so far: the index into results()
    for (const CLI::Option* option : m_command->parse_order()) {
        const size_t index = seen[option]++;
        const auto parameter = std::find(m_parameters.begin(), m_parameters.end(), option);
        if (option != m_model && parameter == m_parameters.end())
            continue;  // the subcommand's own options
        const std::string& value = option->results().at(index);
        if (option == m_model && !one_model) {
            out.push_back({Json{{"model", value}}, value});
            continue;
        }
        const std::string key =
            option == m_model
                ? "model"
                : phase_parameter_names()[static_cast<size_t>(parameter - m_parameters.begin())];
        const std::string name = option->get_lnames().front();
        if (out.empty())
            usage_error("model parameters must follow a --model");
        PhaseModelArgs& model = out.back();
        if (model.json.contains(key))
            usage_error("--" + name + " given twice for one model");
        model.json[key] = key == "model" ? Json(value) : parameter_value(name, value);
        model.label +=
            (model.label.empty() ? "" : " ") + (key == "model" ? value : name + "=" + value);
    }
    return out;
}

std::vector<PhaseModelArgs> PhaseModelOptions::models() const {
    return collect(false);
}

PhaseModelArgs PhaseModelOptions::single() const {
    PhaseModelArgs model = collect(true).front();
    if (!model.json.contains("model"))
        usage_error("--model NAME is required");
    return model;
}

double require_number(const std::string& name, const std::string& text) {
    const auto v = to_number(text);
    if (!v)
        usage_error("--" + name + " expects a number, got '" + text + "'");
    return *v;
}

std::vector<double> parse_number_list(const std::string& name, const std::string& text) {
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
    std::vector<double> angles = parse_number_list("theta-deg", text);
    for (const double t : angles)
        if (!(t >= 0.0 && t <= 180.0))
            throw_input_error("phase: --theta-deg values must be in [0, 180]");
    return angles;
}

}  // namespace kasumi
