#pragma once
/// Tables of a quantity against wavelength, read from CSV files: one `wavelength_nm,value` row per
/// line, `#` starts a comment (whole line or the rest of a line), blank lines are skipped, and a
/// first row whose two fields are not numbers is a column header. Wavelengths must strictly
/// increase; values must be finite and >= 0. Between rows the table is linear in wavelength;
/// outside its range it is an error, never a clamped value.
#include <string>
#include <vector>

namespace kasumi {

struct WavelengthTable {
    std::vector<double> nm;     ///< strictly increasing, nm
    std::vector<double> value;  ///< same length, >= 0
    std::string source;         ///< where the table came from, for error messages

    double min_nm() const { return nm.front(); }
    double max_nm() const { return nm.back(); }
    bool covers(double lambda_nm) const {
        return !nm.empty() && lambda_nm >= nm.front() && lambda_nm <= nm.back();
    }
    /// Linear interpolation; exact at the rows. Throws an input error naming `source`, the
    /// wavelength and the table's range when lambda_nm is outside it.
    double at(double lambda_nm) const;
    /// Integral over the table's range by the trapezoid rule (exact for the linear table).
    double integral() const;
};

/// Parses CSV text; errors read "<file>:<line>: <what was expected>" (input errors, exit 3).
WavelengthTable parse_wavelength_csv(const std::string& text, const std::string& file);

/// Reads and parses a CSV file.
WavelengthTable read_wavelength_csv(const std::string& path);

/// A table from rows (wavelength_nm, value) already in memory; the same checks as the parser,
/// errors prefixed with `source`.
WavelengthTable make_wavelength_table(const std::vector<double>& nm,
                                      const std::vector<double>& value, const std::string& source);

}  // namespace kasumi
