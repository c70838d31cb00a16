#include "core/csv_table.h"

#include "core/error.h"
#include "core/text_file.h"

#include <cmath>
#include <cstdlib>
#include <sstream>

namespace kasumi {

namespace {

std::string trim(const std::string& s) {
    const size_t b = s.find_first_not_of(" \t\r");
    if (b == std::string::npos)
        return "";
    const size_t e = s.find_last_not_of(" \t\r");
    return s.substr(b, e - b + 1);
}

/// The whole field as a finite number, or false.
bool parse_number(const std::string& field, double& out) {
    if (field.empty())
        return false;
    char* end = nullptr;
    out = std::strtod(field.c_str(), &end);
    return end == field.c_str() + field.size() && std::isfinite(out);
}

std::string format_nm(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

}  // namespace

double WavelengthTable::at(double lambda_nm) const {
    if (!covers(lambda_nm))
        throw_input_error(source + ": no value at " + format_nm(lambda_nm) +
                          " nm: the table covers " + format_nm(nm.front()) + " to " +
                          format_nm(nm.back()) + " nm (values outside it are not extrapolated)");
    // Binary search for the segment [i - 1, i] holding lambda_nm.
    size_t lo = 0, hi = nm.size() - 1;
    while (hi - lo > 1) {
        const size_t mid = (lo + hi) / 2;
        (nm[mid] <= lambda_nm ? lo : hi) = mid;
    }
    if (lambda_nm == nm[lo])
        return value[lo];
    if (lambda_nm == nm[hi])
        return value[hi];
    const double f = (lambda_nm - nm[lo]) / (nm[hi] - nm[lo]);
    return value[lo] + f * (value[hi] - value[lo]);
}

double WavelengthTable::integral() const {
    double sum = 0.0;
    for (size_t i = 1; i < nm.size(); ++i)
        sum += 0.5 * (value[i - 1] + value[i]) * (nm[i] - nm[i - 1]);
    return sum;
}

WavelengthTable parse_wavelength_csv(const std::string& text, const std::string& file) {
    WavelengthTable t;
    t.source = file;
    std::istringstream in(text);
    std::string line;
    int line_no = 0;
    bool header_allowed = true;
    while (std::getline(in, line)) {
        ++line_no;
        const size_t hash = line.find('#');
        const std::string body = trim(hash == std::string::npos ? line : line.substr(0, hash));
        if (body.empty())
            continue;
        const std::string where = file + ":" + std::to_string(line_no) + ": ";
        const size_t comma = body.find(',');
        const std::string f0 = trim(body.substr(0, comma));
        const std::string f1 = comma == std::string::npos ? "" : trim(body.substr(comma + 1));
        double w = 0.0, v = 0.0;
        const bool ok0 = parse_number(f0, w), ok1 = parse_number(f1, v);
        if (comma == std::string::npos || f1.find(',') != std::string::npos || !ok0 || !ok1) {
            if (header_allowed && comma != std::string::npos && f1.find(',') == std::string::npos &&
                !ok0 && !ok1 && !f0.empty()) {
                header_allowed = false;  // a column header such as "wavelength_nm,value"
                continue;
            }
            throw_input_error(where + "expected two numbers \"wavelength_nm,value\", got \"" +
                              body + "\"");
        }
        header_allowed = false;
        if (!(w > 0.0))
            throw_input_error(where + "wavelength must be > 0 nm, got " + f0);
        if (!t.nm.empty() && !(w > t.nm.back()))
            throw_input_error(where + "wavelengths must strictly increase: " + f0 + " nm after " +
                              format_nm(t.nm.back()) + " nm");
        if (!(v >= 0.0))
            throw_input_error(where + "value must be >= 0, got " + f1);
        t.nm.push_back(w);
        t.value.push_back(v);
    }
    if (t.nm.size() < 2)
        throw_input_error(file +
                          ": a table needs at least two rows \"wavelength_nm,value\", found " +
                          std::to_string(t.nm.size()));
    return t;
}

WavelengthTable read_wavelength_csv(const std::string& path) {
    return parse_wavelength_csv(read_text_file(path, "the table file"), path);
}

WavelengthTable make_wavelength_table(const std::vector<double>& nm,
                                      const std::vector<double>& value, const std::string& source) {
    WavelengthTable t;
    t.source = source;
    if (nm.size() != value.size() || nm.size() < 2)
        throw_input_error(source + ": a table needs at least two rows [wavelength_nm, value]");
    for (size_t i = 0; i < nm.size(); ++i) {
        if (!(nm[i] > 0.0) || !std::isfinite(nm[i]))
            throw_input_error(source + ": row " + std::to_string(i) +
                              ": wavelength must be > 0 nm");
        if (i > 0 && !(nm[i] > nm[i - 1]))
            throw_input_error(source + ": row " + std::to_string(i) +
                              ": wavelengths must strictly increase");
        if (!(value[i] >= 0.0) || !std::isfinite(value[i]))
            throw_input_error(source + ": row " + std::to_string(i) + ": value must be >= 0");
    }
    t.nm = nm;
    t.value = value;
    return t;
}

}  // namespace kasumi
