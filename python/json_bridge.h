#pragma once
/// JSON values between Python objects and the library, through the text of Python's json
/// module: what json.dumps accepts (dict, list, tuple, str, int, float, bool, None) becomes the
/// Json the scene loader reads, and a Json becomes what json.loads returns.
#include "core/json_text.h"

#include <pybind11/pybind11.h>

#include <string>

namespace kasumi::python {

/// json.dumps(value, allow_nan=False): a TypeError for what JSON cannot hold, a ValueError for
/// NaN and infinities (JSON has none).
std::string json_text(const pybind11::handle& value);

/// The Json of a Python value (json_text, parsed); `what` names it in errors.
Json to_json(const pybind11::handle& value, const std::string& what);

/// The Python value of a Json (json.loads of its text): dicts, lists, str, int, float, bool,
/// None.
pybind11::object from_json(const Json& value);

}  // namespace kasumi::python
