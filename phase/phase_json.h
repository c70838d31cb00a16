#pragma once
/// Reads a phase function from a scene's JSON: {"model": "isotropic" | "hg", ...}.
#include "core/json_node.h"
#include "phase/phase_function.h"

namespace kasumi {

/// Parses and validates a `phase` object; errors name the file and JSON path.
PhaseFunction parse_phase(const JsonNode& node);

/// The model's name as written in scene files.
std::string phase_model_name(const PhaseFunction& p);

}  // namespace kasumi
