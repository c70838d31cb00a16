#pragma once
/// Reads a phase function from a scene's JSON: {"model": NAME, parameters...}; see docs/phase.md
/// for every model's parameters, ranges and defaults.
#include "core/json_node.h"
#include "phase/phase_function.h"

#include <string>
#include <vector>

namespace kasumi {

/// Parses and validates a `phase` object; errors name the file and JSON path.
PhaseFunction parse_phase(const JsonNode& node);

/// The model's name as written in scene files.
std::string phase_model_name(const PhaseFunction& p);

/// Every model name parse_phase accepts.
const std::vector<std::string>& phase_model_names();

/// Every key parse_phase reads besides `model`, over all models (`kasumi phase` makes each an
/// option).
const std::vector<std::string>& phase_parameter_names();

}  // namespace kasumi
