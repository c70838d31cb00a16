#pragma once
/// A wavelength table given in a scene: a CSV file path (relative to the scene file; format in
/// core/csv_table.h) or rows inline, [[wavelength_nm, value], ...]. Errors name the scene file
/// and JSON pointer, then the CSV file and line.
#include "core/csv_table.h"
#include "core/json_node.h"

namespace kasumi {

/// True when `node` is a string or an array of rows: the forms read_wavelength_table takes.
bool is_wavelength_table(const JsonNode& node);

/// Reads the table. Its `source` names the scene file, the pointer and the CSV path, so a later
/// lookup outside its range reports where the table came from.
WavelengthTable read_wavelength_table(const JsonNode& node);

/// A path from a scene resolved against the scene file's folder (absolute paths unchanged).
std::string resolve_scene_path(const JsonNode& node, const std::string& path);

}  // namespace kasumi
