#pragma once
/// Located access to a JSON document: every value knows its file and JSON pointer, so each
/// input error reads "scene.json: /media/0/phase/g = 1.2: must be in (-1, 1)".
#include "core/color.h"
#include "core/json_text.h"
#include "core/math.h"

#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace kasumi {

/// Largest scene coordinate or length, metres. Beyond it single precision breaks down: a
/// squared distance (2 * 1e12)^2 * 3 and a cube of a coordinate difference stay finite in
/// float (< 3.4e38), and Embree rejects rays with coordinates above ~1.8e19.
constexpr double kMaxCoordinateM = 1e12;

/// One value inside a JSON document, with the document's file name and the value's pointer.
/// Does not own the document: keep the root alive while nodes are in use.
class JsonNode {
  public:
    JsonNode(const Json& value, std::string file, std::string pointer = "");

    const Json& value() const { return *m_value; }
    const std::string& file() const { return m_file; }
    /// JSON pointer of this value ("" for the root).
    const std::string& pointer() const { return m_pointer; }

    /// Throws an input error naming file, pointer and (abbreviated) value.
    [[noreturn]] void fail(const std::string& what) const;

    JsonNode child(const std::string& key) const;  ///< requires an object holding key
    JsonNode child(size_t index) const;            ///< requires an array
    size_t size() const;                           ///< array or object size

    bool is_null() const { return m_value->is_null(); }
    bool is_number() const { return m_value->is_number(); }
    bool is_string() const { return m_value->is_string(); }
    bool is_array() const { return m_value->is_array(); }
    bool is_object() const { return m_value->is_object(); }

    double as_double() const;  ///< finite number
    float as_float() const;
    int64_t as_int() const;  ///< integral number
    bool as_bool() const;
    std::string as_string() const;
    Vec3 as_vec3() const;  ///< [x, y, z]
    /// A point [x, y, z] in metres with every |coordinate| <= kMaxCoordinateM.
    Vec3 as_point() const;
    Rgb as_rgb() const;                      ///< scalar s (→ s,s,s) or [r, g, b]
    std::vector<JsonNode> elements() const;  ///< array elements

    /// Range checks that fail with the reason spelled out.
    float positive() const;         ///< > 0
    float positive_length() const;  ///< a length in metres in (0, kMaxCoordinateM]
    float non_negative() const;     ///< >= 0
    Rgb non_negative_rgb() const;
    float in_open(float lo, float hi) const;    ///< in (lo, hi)
    float in_closed(float lo, float hi) const;  ///< in [lo, hi]
    Vec3 unit_direction() const;                ///< non-zero vector, returned normalised

  private:
    /// fail(what), noting when only rounding to float moved the value out of range.
    [[noreturn]] void fail_range(const std::string& what, bool in_range_before_rounding) const;

    const Json* m_value;
    std::string m_file;
    std::string m_pointer;
};

/// Reads an object's keys and reports the ones nobody asked for: call finish() after reading.
class JsonObjectReader {
  public:
    explicit JsonObjectReader(const JsonNode& node);

    const JsonNode& node() const { return m_node; }
    bool has(const std::string& key) const;
    std::optional<JsonNode> optional(const std::string& key);
    JsonNode required(const std::string& key);

    /// Fails if the object holds a key that was never read, listing the keys that were.
    void finish() const;

  private:
    JsonNode m_node;
    std::set<std::string> m_known;
};

}  // namespace kasumi
