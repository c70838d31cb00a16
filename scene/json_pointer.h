#pragma once
/// JSON pointers (RFC 6901), the one implementation behind --set, animate, quality presets and
/// study --vary: "/lights/0/samples" names key "lights", element 0, key "samples"; "~1" stands
/// for '/' and "~0" for '~' inside a token; "-" names the element past an array's end.
#include "core/json_text.h"

#include <optional>
#include <string>
#include <vector>

namespace kasumi {

/// The unescaped tokens of `pointer` ("" -> none), or nullopt unless it is "" or starts with
/// '/' and every '~' is followed by '0' or '1'.
std::optional<std::vector<std::string>> pointer_tokens(const std::string& pointer);

/// A pointer from unescaped tokens (the inverse of pointer_tokens).
std::string pointer_from_tokens(const std::vector<std::string>& tokens);

/// The index an array token names: decimal digits without a leading zero (RFC 6901); nullopt
/// for anything else, "-" included.
std::optional<size_t> array_index(const std::string& token);

/// The value `tokens` name in `root`, or null when there is none.
const Json* find_value(const Json& root, const std::vector<std::string>& tokens);

/// Writes `value` at `tokens` in `root` like `mkdir -p`: missing objects along the way are
/// created (an array where the next token is "-"), an existing value is replaced, "-" as the last
/// token appends to an array. Returns an empty string, or why nothing was written: an array index
/// that is not one or lies past the end, or a step into a value that is not an object or array.
std::string write_value(Json& root, const std::vector<std::string>& tokens, Json value);

}  // namespace kasumi
