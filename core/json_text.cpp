#include "core/json_text.h"

#include "core/error.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <streambuf>
#include <vector>

namespace kasumi {

namespace {

/// The text as a stream buffer that tells how far the parser has read: nlohmann::json reads a
/// stream one character at a time (sbumpc), so the offset is exact at every SAX event.
class CountingBuffer : public std::streambuf {
  public:
    explicit CountingBuffer(const std::string& text) {
        char* begin = const_cast<char*>(text.data());  // read only: no putback area is set
        setg(begin, begin, begin + text.size());
    }
    size_t offset() const { return static_cast<size_t>(gptr() - eback()); }
};

/// "line L, column C" of a byte offset into `text` (both counted from 1).
std::string position_text(const std::string& text, size_t offset) {
    offset = std::min(offset, text.size());
    const size_t line =
        1 + static_cast<size_t>(std::count(text.begin(), text.begin() + offset, '\n'));
    const size_t line_start = text.rfind('\n', offset == 0 ? 0 : offset - 1);
    const size_t column =
        offset + 1 - (line_start == std::string::npos || offset == 0 ? 0 : line_start + 1);
    return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

/// Builds the Json value from SAX events (as nlohmann's own DOM builder does) and refuses what
/// that builder lets through: a key given twice (it keeps the last one silently) and nesting
/// deeper than kMaxJsonDepth. A number out of double range and syntax errors arrive through
/// parse_error.
class LocatedDomBuilder : public nlohmann::json_sax<Json> {
  public:
    /// With `syntax_errors_throw` false, a syntax error ends the parse (sax_parse returns false)
    /// instead of throwing.
    LocatedDomBuilder(const std::string& text, const std::string& file,
                      const CountingBuffer& buffer, bool syntax_errors_throw = true)
        : m_text(text),
          m_file(file),
          m_buffer(buffer),
          m_syntax_errors_throw(syntax_errors_throw) {}

    Json& root() { return m_root; }

    bool null() override { return add(Json(nullptr)); }
    bool boolean(bool v) override { return add(Json(v)); }
    bool number_integer(number_integer_t v) override { return add(Json(v)); }
    bool number_unsigned(number_unsigned_t v) override { return add(Json(v)); }
    bool number_float(number_float_t v, const string_t&) override { return add(Json(v)); }
    bool string(string_t& v) override { return add(Json(std::move(v))); }
    bool binary(binary_t& v) override { return add(Json::binary(std::move(v))); }

    bool start_object(std::size_t) override { return open(Json::object()); }
    bool start_array(std::size_t) override { return open(Json::array()); }
    bool end_object() override { return close(); }
    bool end_array() override { return close(); }

    bool key(string_t& key) override {
        Json& object = *m_stack.back();
        if (object.contains(key)) {
            // The parser stands just past the key's closing quote; report its opening quote.
            fail(key_start(m_buffer.offset()), "duplicate key \"" + key + "\" in " +
                                                   pointer_of(false) +
                                                   " (each key may appear once in an object)");
        }
        m_key = &object[key];
        m_tokens.back() = json_pointer_escape(key);
        return true;
    }

    bool parse_error(std::size_t position, const std::string& last_token,
                     const nlohmann::detail::exception& e) override {
        if (e.id == 406) {
            // "number overflow": the position is just past the number token.
            const size_t start = position >= last_token.size() ? position - last_token.size() : 0;
            fail(start, "number " + last_token + " is out of range at " + pointer_of(true) +
                            " (a double holds magnitudes up to 1.8e308)");
        }
        if (!m_syntax_errors_throw)
            return false;
        // "[json.exception.parse_error.101] parse error at line L, column C: ..."; the library's
        // tag says nothing to the user.
        std::string what = e.what();
        const size_t tag_end = what.find("] ");
        if (!what.empty() && what.front() == '[' && tag_end != std::string::npos)
            what = what.substr(tag_end + 2);
        throw_input_error(m_file + ": invalid JSON: " + what);
    }

  private:
    [[noreturn]] void fail(size_t offset, const std::string& what) const {
        throw_input_error(m_file + ": invalid JSON: " + position_text(m_text, offset) + ": " +
                          what);
    }

    /// The offset of the opening quote of the string that ends just before `end`.
    size_t key_start(size_t end) const {
        for (size_t i = end >= 2 ? end - 2 : 0; i > 0; --i) {
            if (m_text[i] != '"')
                continue;
            size_t backslashes = 0;
            while (backslashes < i && m_text[i - 1 - backslashes] == '\\')
                ++backslashes;
            if (backslashes % 2 == 0)
                return i;
        }
        return 0;
    }

    /// The pointer of the innermost open container, or with `pending` of the value being read
    /// in it (an array's next element, an object's last key).
    std::string pointer_of(bool pending) const {
        std::string pointer;
        const size_t n = m_stack.size() - (pending || m_stack.empty() ? 0 : 1);
        for (size_t i = 0; i < n; ++i) {
            const Json& container = *m_stack[i];
            const bool inner = i + 1 < m_stack.size();  // holds the next open container
            pointer +=
                "/" + (container.is_array() ? std::to_string(container.size() - (inner ? 1 : 0))
                                            : m_tokens[i]);
        }
        return pointer.empty() ? "/" : pointer;
    }

    /// Places a value where the parser stands: the root, the next array element or the value
    /// of the last key.
    Json* place(Json value) {
        if (m_stack.empty()) {
            m_root = std::move(value);
            return &m_root;
        }
        Json& top = *m_stack.back();
        if (top.is_array()) {
            top.push_back(std::move(value));
            return &top.back();
        }
        *m_key = std::move(value);
        return m_key;
    }

    bool add(Json value) {
        place(std::move(value));
        return true;
    }

    bool open(Json container) {
        if (m_stack.size() >= static_cast<size_t>(kMaxJsonDepth)) {
            fail(m_buffer.offset() - 1,
                 "nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
        }
        // Pointers stay valid: a container's next sibling is placed only after it is closed.
        m_stack.push_back(place(std::move(container)));
        m_tokens.emplace_back();
        return true;
    }

    bool close() {
        m_stack.pop_back();
        m_tokens.pop_back();
        return true;
    }

    const std::string& m_text;
    const std::string& m_file;
    const CountingBuffer& m_buffer;
    Json m_root;
    std::vector<Json*> m_stack;         ///< the open arrays and objects, outermost first
    std::vector<std::string> m_tokens;  ///< per open object: the escaped key being read
    Json* m_key = nullptr;              ///< where the value of the last key goes
    bool m_syntax_errors_throw = true;
};

}  // namespace

Json parse_json_text(const std::string& text, const std::string& file, JsonComments comments) {
    CountingBuffer buffer(text);
    std::istream in(&buffer);
    LocatedDomBuilder builder(text, file, buffer);
    Json::sax_parse(in, &builder, Json::input_format_t::json, /*strict=*/true,
                    /*ignore_comments=*/comments == JsonComments::Allowed);
    return std::move(builder.root());
}

std::optional<Json> parse_json_if_json(const std::string& text, const std::string& what) {
    CountingBuffer buffer(text);
    std::istream in(&buffer);
    LocatedDomBuilder builder(text, what, buffer, /*syntax_errors_throw=*/false);
    if (!Json::sax_parse(in, &builder, Json::input_format_t::json, /*strict=*/true,
                         /*ignore_comments=*/false))
        return std::nullopt;
    return std::move(builder.root());
}

Json read_json_file(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw_input_error(path + ": is a directory, expected a JSON file");
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw_input_error(path + ": cannot open file: " + std::strerror(errno));
    // Read at most kMaxBytes + 1: a device or FIFO named as the scene (/dev/zero) would
    // otherwise be read until memory runs out. Large geometry lives in OBJ files, not here.
    constexpr size_t kMaxBytes = size_t{64} << 20;
    std::string text;
    char chunk[65536];
    while (in && text.size() <= kMaxBytes) {
        in.read(chunk, sizeof(chunk));
        text.append(chunk, static_cast<size_t>(in.gcount()));
    }
    if (in.bad())
        throw_input_error(path + ": read error");
    if (text.size() > kMaxBytes)
        throw_input_error(path + ": larger than 64 MiB, expected a JSON scene file");
    return parse_json_text(text, path);
}

std::string json_pointer_escape(const std::string& key) {
    std::string out;
    for (char c : key) {
        if (c == '~') {
            out += "~0";
        } else if (c == '/') {
            out += "~1";
        } else {
            out += c;
        }
    }
    return out;
}

}  // namespace kasumi
