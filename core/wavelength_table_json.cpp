#include "core/wavelength_table_json.h"

#include "core/error.h"

#include <filesystem>

namespace kasumi {

bool is_wavelength_table(const JsonNode& node) {
    return node.is_string() ||
           (node.is_array() && node.size() > 0 && node.child(size_t{0}).is_array());
}

std::string resolve_scene_path(const JsonNode& node, const std::string& path) {
    std::filesystem::path p(path);
    if (p.is_relative())
        p = std::filesystem::path(node.file()).parent_path() / p;
    return p.lexically_normal().string();
}

WavelengthTable read_wavelength_table(const JsonNode& node) {
    const std::string where = node.file() + ": " + (node.pointer().empty() ? "/" : node.pointer());
    if (node.is_string()) {
        const std::string path = resolve_scene_path(node, node.as_string());
        WavelengthTable t;
        try {
            t = read_wavelength_csv(path);
        } catch (const Error& e) {
            node.fail(e.what());
        }
        t.source = where + " (" + path + ")";
        return t;
    }
    if (!node.is_array())
        node.fail("expected a CSV file path or [[wavelength_nm, value], ...]");
    std::vector<double> nm, value;
    for (const JsonNode& row : node.elements()) {
        if (!row.is_array() || row.size() != 2)
            row.fail("expected [wavelength_nm, value]");
        const double w = row.child(size_t{0}).as_double();
        const double v = row.child(size_t{1}).as_double();
        if (!(w > 0.0))
            row.fail("wavelength must be > 0 nm");
        if (!nm.empty() && !(w > nm.back()))
            row.fail("wavelengths must strictly increase");
        if (!(v >= 0.0))
            row.fail("value must be >= 0");
        nm.push_back(w);
        value.push_back(v);
    }
    if (nm.size() < 2)
        node.fail("a table needs at least two rows [wavelength_nm, value]");
    return make_wavelength_table(nm, value, where);
}

}  // namespace kasumi
