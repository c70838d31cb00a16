#pragma once
/// The values on `kasumi phase`'s command line: phase-function models given as options (the
/// scene-file keys with `-` for `_`: `--model hg --g 0.5`, `--diameter-um 10`, `--m 1.33,0`),
/// numbers and lists of numbers. Malformed values are usage errors (exit 2).
#include "core/json_node.h"

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace kasumi {

/// One model as written on the command line.
struct PhaseModelArgs {
    Json json;          ///< the scene-file `phase` object: {"model": "hg", "g": 0.5}
    std::string label;  ///< "hg g=0.5", the options in command-line order
};

/// Adds `--model` and one option per phase_parameter_names() key to `command`, each repeatable,
/// and reads them back after parsing.
class PhaseModelOptions {
  public:
    explicit PhaseModelOptions(CLI::App& command);

    /// The models in command-line order: each `--model` starts one and the parameters after it
    /// belong to it. A value is a number, a list "a,b" (an array of numbers) or else a string.
    /// Usage error when a parameter precedes every --model or repeats within one model.
    std::vector<PhaseModelArgs> models() const;

    /// The one model of `eval` and `validate`, its options in any order: a usage error unless
    /// --model was given once.
    PhaseModelArgs single() const;

  private:
    /// The models in command-line order, or (one_model) every option into a single model.
    std::vector<PhaseModelArgs> collect(bool one_model) const;

    CLI::App* m_command = nullptr;
    CLI::Option* m_model = nullptr;
    std::vector<CLI::Option*> m_parameters;  ///< parallel to phase_parameter_names()
};

/// `text` as a number (std::stod, the whole text), or a usage error naming --`name`.
double require_number(const std::string& name, const std::string& text);

/// "a,b,c" or "A:B:N" (N evenly spaced values from A to B inclusive); usage error naming
/// --`name` if malformed or empty.
std::vector<double> parse_number_list(const std::string& name, const std::string& text);

/// A --theta-deg list: usage error if malformed, input error (exit 3) outside [0, 180].
std::vector<double> parse_angles(const std::string& text);

}  // namespace kasumi
