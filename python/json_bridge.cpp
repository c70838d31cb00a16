#include "json_bridge.h"

namespace py = pybind11;

namespace kasumi::python {

std::string json_text(const py::handle& value) {
    return py::str(py::module_::import("json").attr("dumps")(value, py::arg("allow_nan") = false));
}

Json to_json(const py::handle& value, const std::string& what) {
    return parse_json_text(json_text(value), what, JsonComments::Refused);
}

py::object from_json(const Json& value) {
    return py::module_::import("json").attr("loads")(value.dump());
}

}  // namespace kasumi::python
