#include "core/error.h"
#include "lights/ies_profile.h"

#include <cmath>
#include <fstream>
#include <sstream>

namespace kasumi {

namespace {

/// Numbers after TILT=NONE, each with the line it came from; LM-63 lets them wrap freely.
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

/// Expands the stored horizontal half-plane(s) to C in [0°, 360°] by the file's symmetry
/// (LM-63-2002 §5.11, type C): last angle 0 rotationally symmetric, 90 symmetric in each
/// quadrant, 180 bilaterally symmetric about the 0–180° plane, 360 no symmetry.
void expand_symmetry(IesProfile& p, const std::vector<float>& h, const std::vector<float>& cd) {
    const size_t nv = p.vertical_deg.size();
    const auto column = [&](size_t i) { return cd.begin() + static_cast<long>(i * nv); };
    std::vector<std::pair<float, size_t>> cols;  // (C, source column)
    const float last = h.back();
    if (h.size() == 1) {
        cols = {{0.0f, 0}, {360.0f, 0}};
    } else if (last == 360.0f) {
        for (size_t i = 0; i < h.size(); ++i)
            cols.emplace_back(h[i], i);
    } else {
        // Mirror the stored range [0, last] until it covers 360°.
        for (size_t i = 0; i < h.size(); ++i)
            cols.emplace_back(h[i], i);
        for (size_t i = h.size() - 1; i-- > 0;)
            cols.emplace_back(2.0f * last - h[i], i);
        if (last == 90.0f) {
            for (size_t i = 1; i < h.size(); ++i)
                cols.emplace_back(180.0f + h[i], i);
            for (size_t i = h.size() - 1; i-- > 0;)
                cols.emplace_back(360.0f - h[i], i);
        }
    }
    for (const auto& [c, src] : cols) {
        p.horizontal_deg.push_back(c);
        p.candela.insert(p.candela.end(), column(src), column(src) + static_cast<long>(nv));
    }
}

}  // namespace

IesProfile parse_ies(const std::string& text, const std::string& file) {
    std::istringstream in(text);
    IesProfile p;
    p.file = file;
    std::string line;
    int line_no = 0;
    const auto fail_at = [&](const std::string& what) {
        throw_input_error(file + ":" + std::to_string(line_no) + ": " + what);
    };
    if (!std::getline(in, line))
        fail_at("empty file (expected IESNA:LM-63-1995 or IESNA:LM-63-2002)");
    ++line_no;
    const std::string header = trim(line);
    if (header == "IESNA:LM-63-1995") {
        p.format = "LM-63-1995";
    } else if (header == "IESNA:LM-63-2002") {
        p.format = "LM-63-2002";
    } else {
        fail_at("unsupported header \"" + header.substr(0, 40) +
                "\" (expected IESNA:LM-63-1995 or IESNA:LM-63-2002)");
    }
    for (;;) {
        if (!std::getline(in, line))
            fail_at("file ends before the TILT= line");
        ++line_no;
        const std::string t = trim(line);
        if (t.rfind("TILT=", 0) == 0) {
            if (t != "TILT=NONE")
                fail_at("\"" + t.substr(0, 40) + "\" is not supported (only TILT=NONE)");
            break;
        }
        if (!t.empty() && t.front() != '[')
            fail_at("expected a [KEYWORD] line or TILT=, got \"" + t.substr(0, 40) + "\"");
    }

    NumberStream numbers(in, file, line_no);
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
    const double ballast_lamp = numbers.next("the ballast-lamp photometric factor");
    if (!(ballast > 0.0) || !(ballast_lamp > 0.0))
        numbers.fail("the ballast factors must be > 0");
    numbers.next("the input watts");

    p.vertical_deg = read_angles(numbers, n_vertical, "vertical angles");
    const float v0 = p.vertical_deg.front(), v1 = p.vertical_deg.back();
    if (!((v0 == 0.0f || v0 == 90.0f) && (v1 == 90.0f || v1 == 180.0f)))
        numbers.fail("type C vertical angles must run from 0 or 90 to 90 or 180, got " +
                     NumberStream::format(v0) + " to " + NumberStream::format(v1));
    const std::vector<float> h = read_angles(numbers, n_horizontal, "horizontal angles");
    const float h1 = h.back();
    if (h.front() != 0.0f || !(h1 == 0.0f || h1 == 90.0f || h1 == 180.0f || h1 == 360.0f))
        numbers.fail(
            "type C horizontal angles must start at 0 and end at 0, 90, 180 or 360 "
            "(other symmetries are not supported), got " +
            NumberStream::format(h.front()) + " to " + NumberStream::format(h1));

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
    expand_symmetry(p, h, cd);
    return p;
}

IesProfile read_ies(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw_input_error(path + ": cannot open IES file");
    std::ostringstream text;
    text << in.rdbuf();
    return parse_ies(text.str(), path);
}

}  // namespace kasumi
