#pragma once
/// String settings that name one of a fixed set of choices, one reader for every folder.
#include "core/json_node.h"

#include <initializer_list>
#include <string>
#include <utility>

namespace kasumi {

/// The value paired with the string at `node` in `choices`; any other string (or another type)
/// is an input error listing the names: `expected "a", "b" or "c"`.
template <class T>
T parse_choice(const JsonNode& node, std::initializer_list<std::pair<const char*, T>> choices) {
    const std::string name = node.as_string();
    std::string expected;
    size_t i = 0;
    for (const auto& [choice, value] : choices) {
        if (name == choice)
            return value;
        expected += i == 0 ? "" : (i + 1 == choices.size() ? " or " : ", ");
        expected += "\"" + std::string(choice) + "\"";
        ++i;
    }
    node.fail("expected " + expected);
}

}  // namespace kasumi
