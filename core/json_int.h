#pragma once
/// Integer settings read from JSON with their range checked, one reader for every folder.
#include "core/json_node.h"

#include <cstdint>
#include <string>

namespace kasumi {

/// The integer at `node`, which must lie in [lo, hi] (else an input error naming the range).
inline int parse_int_in(const JsonNode& node, int64_t lo, int64_t hi) {
    const int64_t v = node.as_int();
    if (v < lo || v > hi)
        node.fail("must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return static_cast<int>(v);
}

}  // namespace kasumi
