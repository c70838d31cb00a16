#include "core/error.h"
#include "core/text_file.h"
#include "lights/ies_profile.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

namespace kasumi {

namespace {

/// Numbers after the TILT= line (or in a tilt file), each with the line it came from; LM-63 lets
/// them wrap freely. Delimiters are spaces, commas and line ends (LM-63-2002 §3.0, "Delimiter").
class NumberStream {
  public:
    NumberStream(std::istream& in, std::string file, int line)
        : m_in(in), m_file(std::move(file)), m_line(line) {}

    [[noreturn]] void fail(const std::string& what) const {
        throw_input_error(m_file + ":" + std::to_string(m_line) + ": " + what);
    }

    double next(const char* what) {
        while (m_tokens.empty()) {
            std::string text;
            if (!std::getline(m_in, text))
                fail(std::string("file ends before ") + what);
            ++m_line;
            std::replace(text.begin(), text.end(), ',', ' ');
            std::istringstream words(text);
            std::string word;
            while (words >> word)
                m_tokens.push_back(word);
            std::reverse(m_tokens.begin(), m_tokens.end());
        }
        const std::string word = m_tokens.back();
        m_tokens.pop_back();
        char* end = nullptr;
        const double v = std::strtod(word.c_str(), &end);
        if (end == word.c_str() || *end != '\0' || !std::isfinite(v))
            fail(std::string("expected a number for ") + what + ", got \"" + word + "\"");
        return v;
    }

    int next_count(const char* what, int lo, int hi) {
        const double v = next(what);
        if (v != std::floor(v) || v < lo || v > hi) {
            fail(std::string(what) + " must be an integer in [" + std::to_string(lo) + ", " +
                 std::to_string(hi) + "], got " + format(v));
        }
        return static_cast<int>(v);
    }

    /// True when only blank lines remain.
    bool at_end() {
        if (!m_tokens.empty())
            return false;
        std::string text;
        while (std::getline(m_in, text)) {
            ++m_line;
            if (text.find_first_not_of(" \t\r\x1a") != std::string::npos)
                return false;
        }
        return true;
    }

    static std::string format(double v) {
        std::ostringstream out;
        out << v;
        return out.str();
    }

  private:
    std::istream& m_in;
    std::string m_file;
    int m_line;
    std::vector<std::string> m_tokens;  // reversed words of the current line
};

std::string trim(const std::string& s) {
    const size_t a = s.find_first_not_of(" \t\r");
    if (a == std::string::npos)
        return "";
    return s.substr(a, s.find_last_not_of(" \t\r") - a + 1);
}

std::string upper_without_spaces(const std::string& s) {
    std::string out;
    for (const char c : s) {
        if (!std::isspace(static_cast<unsigned char>(c)))
            out.push_back(static_cast<char>(std::toupper(static_cast<unsigned char>(c))));
    }
    return out;
}

/// The revision a file's first line names, or "" when it is not a format line (LM-63-1986 files
/// have none: their first line is already a free-form label line). The identifiers are those of
/// each revision's first line: `IESNA91` (LM-63-1991), `IESNA:LM-63-1995`, `IESNA:LM-63-2002`
/// and `IES:LM-63-2019`; spaces and letter case are not significant.
std::string revision_of(const std::string& first_line) {
    const std::string id = upper_without_spaces(first_line);
    if (id == "IESNA91")
        return "LM-63-1991";
    if (id == "IESNA:LM-63-1995")
        return "LM-63-1995";
    if (id == "IESNA:LM-63-2002")
        return "LM-63-2002";
    if (id == "IES:LM-63-2019")
        return "LM-63-2019";
    return "";
}

/// The text after "TILT=" when the line is a TILT line ("TILT", optional spaces, "="), else
/// nullopt.
std::optional<std::string> tilt_value(const std::string& line) {
    std::string head;
    size_t i = 0;
    for (; i < line.size() && line[i] != '='; ++i) {
        if (!std::isspace(static_cast<unsigned char>(line[i])))
            head.push_back(static_cast<char>(std::toupper(static_cast<unsigned char>(line[i]))));
    }
    if (i == line.size() || head != "TILT")
        return std::nullopt;
    return trim(line.substr(i + 1));
}

std::vector<float> read_angles(NumberStream& numbers, int count, const char* what) {
    std::vector<float> angles(static_cast<size_t>(count));
    for (float& a : angles) {
        a = static_cast<float>(numbers.next(what));
        if (&a != &angles.front() && !(a > *(&a - 1)))
            numbers.fail(std::string(what) + " must increase, got " + NumberStream::format(a) +
                         " after " + NumberStream::format(*(&a - 1)));
    }
    return angles;
}

/// The tilt block (LM-63-2002, TILT=INCLUDE or the file TILT=<filename> names): <lamp-to-luminaire
/// geometry> (1, 2 or 3), <number of pairs of angles and multiplying factors>, <angles>,
/// <multiplying factors>.
IesTilt read_tilt(NumberStream& numbers, std::string source) {
    IesTilt tilt;
    tilt.source = std::move(source);
    tilt.geometry = numbers.next_count("the lamp-to-luminaire geometry (1, 2 or 3)", 1, 3);
    const int n = numbers.next_count("the number of tilt angles", 1, 100000);
    tilt.angle_deg = read_angles(numbers, n, "tilt angles");
    if (tilt.angle_deg.front() < 0.0f || tilt.angle_deg.back() > 180.0f)
        numbers.fail("tilt angles must lie in [0, 180] degrees, got " +
                     NumberStream::format(tilt.angle_deg.front()) + " to " +
                     NumberStream::format(tilt.angle_deg.back()));
    tilt.multiplier.resize(static_cast<size_t>(n));
    for (float& m : tilt.multiplier) {
        const double v = numbers.next("tilt multiplying factors");
        if (!(v >= 0.0) || v > 1e30)
            numbers.fail("tilt multiplying factors must be in [0, 1e30], got " +
                         NumberStream::format(v));
        m = static_cast<float>(v);
    }
    return tilt;
}

/// The horizontal symmetry of a type C table, from its first and last horizontal angles
/// (<horizontal angles> of LM-63-1995 and LM-63-2002): a single angle, rotationally symmetric;
/// 0–90°, symmetric in each quadrant; 0–180°, bilaterally symmetric about the 0–180° plane;
/// 90–270°, bilaterally symmetric about the 90–270° plane; 0 to more than 180° and at most 360°,
/// no lateral symmetry (a table ending below 360° closes the circle between its last angle and
/// 360° = 0°).
enum class Symmetry { Rotational, Quadrant, Bilateral0To180, Bilateral90To270, None };

Symmetry symmetry_of(const std::vector<float>& h, NumberStream& numbers) {
    const float first = h.front(), last = h.back();
    if (h.size() == 1 && (first == 0.0f || first == 90.0f))
        return Symmetry::Rotational;
    if (first == 0.0f && last == 90.0f)
        return Symmetry::Quadrant;
    if (first == 0.0f && last == 180.0f)
        return Symmetry::Bilateral0To180;
    if (first == 90.0f && last == 270.0f)
        return Symmetry::Bilateral90To270;
    if (first == 0.0f && last > 180.0f && last <= 360.0f)
        return Symmetry::None;
    numbers.fail(
        "type C horizontal angles must be 0 alone, 0 to 90, 0 to 180, 90 to 270 or 0 to "
        "more than 180 and at most 360 (the LM-63 symmetries), got " +
        NumberStream::format(first) + " to " + NumberStream::format(last));
}

/// The stored horizontal angle whose column holds the intensity at C (degrees, in [0, 360]),
/// folding C by the table's symmetry. For Symmetry::None, angles past the last stored one are
/// returned as is (they lie between the last column and 360° = column 0).
float fold(Symmetry symmetry, float c) {
    switch (symmetry) {
        case Symmetry::Rotational:
            return 0.0f;
        case Symmetry::Quadrant:
            if (c > 180.0f)
                c = 360.0f - c;
            return c > 90.0f ? 180.0f - c : c;
        case Symmetry::Bilateral0To180:
            return c > 180.0f ? 360.0f - c : c;
        case Symmetry::Bilateral90To270:
            // Mirror in the 90–270° plane: C -> 180° − C (mod 360°).
            if (c < 90.0f)
                return 180.0f - c;
            return c > 270.0f ? 540.0f - c : c;
        case Symmetry::None:
            return c;
    }
    return c;
}

/// Expands the stored horizontal angles to C in [0°, 360°] by the file's symmetry. The expanded
/// angles are every image of a stored angle under the symmetry, plus 0° and 360°; each column is
/// the stored table at the folded angle, interpolated linearly between stored columns. Folding is
/// piecewise a reflection, so bilinear interpolation in the expanded table equals interpolation in
/// the stored one at the folded angle.
void expand_symmetry(IesProfile& p, const std::vector<float>& h, const std::vector<float>& cd,
                     Symmetry symmetry) {
    const size_t nv = p.vertical_deg.size();
    std::vector<float> angles{0.0f, 360.0f};
    if (symmetry != Symmetry::Rotational) {
        for (const float a : h) {
            for (const float image :
                 {a, 180.0f - a, 180.0f + a, 360.0f - a, 540.0f - a, a - 180.0f}) {
                const float c = image < 0.0f ? image + 360.0f : image;
                if (c >= 0.0f && c <= 360.0f && std::abs(fold(symmetry, c) - a) < 1e-3f)
                    angles.push_back(c);
            }
        }
    }
    std::sort(angles.begin(), angles.end());
    angles.erase(
        std::unique(angles.begin(), angles.end(), [](float a, float b) { return b - a < 1e-4f; }),
        angles.end());
    angles.back() = 360.0f;
    const auto column = [&](size_t i) { return cd.begin() + static_cast<long>(i * nv); };
    for (const float c : angles) {
        const float f = fold(symmetry, c);
        size_t i0 = 0, i1 = 0;
        float w = 0.0f;
        if (symmetry == Symmetry::None && f > h.back()) {
            // Between the last measured plane and 360° = 0°.
            i0 = h.size() - 1;
            i1 = 0;
            w = (f - h.back()) / (360.0f - h.back());
        } else if (h.size() > 1) {
            const auto it = std::upper_bound(h.begin() + 1, h.end() - 1, f);
            i0 = static_cast<size_t>(it - h.begin()) - 1;
            i1 = i0 + 1;
            w = std::clamp((f - h[i0]) / (h[i1] - h[i0]), 0.0f, 1.0f);
        }
        p.horizontal_deg.push_back(c);
        for (size_t v = 0; v < nv; ++v) {
            const float a = column(i0)[static_cast<long>(v)], b = column(i1)[static_cast<long>(v)];
            p.candela.push_back(w == 0.0f ? a : a + w * (b - a));
        }
    }
}

}  // namespace

IesProfile parse_ies(const std::string& text, const std::string& file) {
    // A UTF-8 byte order mark, as some editors write, is not part of the first line.
    std::istringstream in(text.rfind("\xEF\xBB\xBF", 0) == 0 ? text.substr(3) : text);
    IesProfile p;
    p.file = file;
    std::string line;
    int line_no = 0;
    const auto fail_at = [&](const std::string& what) {
        throw_input_error(file + ":" + std::to_string(line_no) + ": " + what);
    };
    const char* const kFormats =
        "IESNA91, IESNA:LM-63-1995, IESNA:LM-63-2002, IES:LM-63-2019, or LM-63-1986 label lines";
    if (!std::getline(in, line))
        fail_at(std::string("empty file (expected an IES LM-63 file: ") + kFormats + ")");
    ++line_no;
    // The format line (LM-63-1991 on). LM-63-1986 has none: its label lines start at once, so a
    // first line that is no known identifier is a label line, unless it looks like an identifier
    // of a revision we do not know.
    p.format = revision_of(line);
    bool have_line = p.format.empty();
    if (p.format.empty()) {
        const std::string id = upper_without_spaces(line);
        if (id.rfind("IESNA", 0) == 0 || id.rfind("IES:", 0) == 0)
            fail_at("unsupported format line \"" + trim(line).substr(0, 40) + "\" (expected " +
                    kFormats + ")");
        p.format = "LM-63-1986";
    }
    // Label lines until TILT=. LM-63-1986 label lines are free-form text, and so are LM-63-1991
    // files in practice; from LM-63-1995 on every label line starts with a [KEYWORD].
    const bool keywords_only = p.format != "LM-63-1986" && p.format != "LM-63-1991";
    std::optional<std::string> tilt;
    for (;;) {
        if (!have_line) {
            if (!std::getline(in, line))
                fail_at("file ends before the TILT= line (" + p.format + ")");
            ++line_no;
        }
        have_line = false;
        tilt = tilt_value(line);
        if (tilt)
            break;
        const std::string t = trim(line);
        if (keywords_only && !t.empty() && t.front() != '[')
            fail_at("expected a [KEYWORD] line or TILT= in an " + p.format + " file, got \"" +
                    t.substr(0, 40) + "\"");
    }
    // TILT=NONE, TILT=INCLUDE (the tilt block follows) or TILT=<filename> (the tilt block is in
    // that file, relative to this one).
    const std::string tilt_upper = upper_without_spaces(*tilt);
    NumberStream numbers(in, file, line_no);
    if (tilt_upper == "INCLUDE") {
        p.tilt = read_tilt(numbers, "INCLUDE");
    } else if (tilt->empty()) {
        fail_at("TILT= names nothing (expected NONE, INCLUDE or a file name)");
    } else if (tilt_upper != "NONE") {
        std::filesystem::path tilt_path(*tilt);
        if (tilt_path.is_relative())
            tilt_path = std::filesystem::path(file).parent_path() / tilt_path;
        const std::string tilt_file = tilt_path.lexically_normal().string();
        std::ifstream tilt_in(tilt_file, std::ios::binary);
        if (!tilt_in)
            fail_at("cannot open the tilt file " + tilt_file);
        NumberStream tilt_numbers(tilt_in, tilt_file, 0);
        p.tilt = read_tilt(tilt_numbers, tilt_file);
        if (!tilt_numbers.at_end())
            tilt_numbers.fail("unexpected data after the tilt multiplying factors");
    }

    const int lamps = numbers.next_count("the number of lamps", 1, 1000000);
    const double lumens_per_lamp = numbers.next("lumens per lamp");
    const double multiplier = numbers.next("the candela multiplier");
    if (!(multiplier > 0.0))
        numbers.fail("the candela multiplier must be > 0");
    const int n_vertical = numbers.next_count("the number of vertical angles", 2, 100000);
    const int n_horizontal = numbers.next_count("the number of horizontal angles", 1, 100000);
    const int type = numbers.next_count("the photometric type", 1, 3);
    if (type != 1)
        numbers.fail("photometric type " + std::to_string(type) + " (" + (type == 2 ? "B" : "A") +
                     ") is not supported (only type C, 1)");
    numbers.next_count("the units type", 1, 2);
    for (const char* what : {"the luminous width", "the luminous length", "the luminous height"})
        numbers.next(what);
    const double ballast = numbers.next("the ballast factor");
    // The second field is the ballast-lamp photometric factor of the older revisions, "future
    // use" (1) in LM-63-2002 (applied: conforming files hold 1) and the file generation type in
    // LM-63-2019 (a code such as 1.00001, not a factor: it is not applied).
    const double second_factor =
        numbers.next(p.format == "LM-63-2019" ? "the file generation type"
                                              : "the ballast-lamp photometric factor");
    const double ballast_lamp = p.format == "LM-63-2019" ? 1.0 : second_factor;
    if (!(ballast > 0.0) || !(ballast_lamp > 0.0))
        numbers.fail("the ballast factors must be > 0");
    numbers.next("the input watts");

    p.vertical_deg = read_angles(numbers, n_vertical, "vertical angles");
    const float v0 = p.vertical_deg.front(), v1 = p.vertical_deg.back();
    if (!((v0 == 0.0f || v0 == 90.0f) && (v1 == 90.0f || v1 == 180.0f)))
        numbers.fail("type C vertical angles must run from 0 or 90 to 90 or 180, got " +
                     NumberStream::format(v0) + " to " + NumberStream::format(v1));
    const std::vector<float> h = read_angles(numbers, n_horizontal, "horizontal angles");
    const Symmetry symmetry = symmetry_of(h, numbers);

    const double scale = multiplier * ballast * ballast_lamp;
    // Grown as values are read, not sized from the header: a corrupt count (up to 1e10 values)
    // then ends in "file ends before candela values", not in an allocation failure.
    const size_t n_values = static_cast<size_t>(n_vertical) * static_cast<size_t>(n_horizontal);
    std::vector<float> cd;
    while (cd.size() < n_values) {
        const double v = numbers.next("candela values");
        if (v < 0.0)
            numbers.fail("candela values must be >= 0, got " + NumberStream::format(v));
        const float c = static_cast<float>(v * scale);
        if (!std::isfinite(c))
            numbers.fail("candela value " + NumberStream::format(v) + " times the multiplier " +
                         "and ballast factors overflows single precision");
        cd.push_back(c);
        p.max_candela = std::max(p.max_candela, c);
    }
    if (!numbers.at_end())
        numbers.fail("unexpected data after the " + std::to_string(cd.size()) +
                     " candela values (check the angle counts)");
    p.file_lumens = lumens_per_lamp > 0.0 ? lamps * lumens_per_lamp : -1.0;
    expand_symmetry(p, h, cd, symmetry);
    return p;
}

IesProfile read_ies(const std::string& path) {
    return parse_ies(read_text_file(path, "IES file"), path);
}

}  // namespace kasumi
