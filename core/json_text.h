#pragma once
/// JSON text read into a Json value with located errors: a syntax error, a number beyond double
/// range (1e999), an object holding a key twice or nesting deeper than kMaxJsonDepth levels
/// each throw an input error naming the file, the line and column and, where there is one, the
/// JSON pointer of the value.
#include <nlohmann/json.hpp>

#include <optional>
#include <string>

namespace kasumi {

using Json = nlohmann::json;

/// Deepest nesting of arrays and objects accepted in a JSON text. Scenes nest about six levels;
/// walking or printing a value recurses once per level, and 100000 levels overflowed the stack.
constexpr int kMaxJsonDepth = 256;

/// Whether // and /* */ comments are allowed (scene files) or not (--set values).
enum class JsonComments { Allowed, Refused };

/// Parses JSON text; errors read "<file>: invalid JSON: line L, column C: <what>" (the column
/// counts bytes from 1).
Json parse_json_text(const std::string& text, const std::string& file,
                     JsonComments comments = JsonComments::Allowed);

/// Text that may or may not be JSON (a --set value, comments refused): its value, or nullopt
/// when it is not JSON at all. JSON that is refused (a number beyond double range, a key given
/// twice, deep nesting) is an input error as in parse_json_text, `what` naming the text.
std::optional<Json> parse_json_if_json(const std::string& text, const std::string& what);

/// Reads and parses a JSON file (comments allowed); at most 64 MiB.
Json read_json_file(const std::string& path);

/// Escapes a key for use in a JSON pointer (RFC 6901: ~ → ~0, / → ~1).
std::string json_pointer_escape(const std::string& key);

}  // namespace kasumi
