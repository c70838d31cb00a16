#include "core/json_node.h"

#include "core/error.h"

#include <cmath>
#include <sstream>

namespace kasumi {

namespace {

std::string abbreviate(const Json& value) {
    std::string text = value.dump();
    if (text.size() > 60)
        text = text.substr(0, 57) + "...";
    return text;
}

std::string format_number(double v) {
    std::ostringstream out;
    out << v;
    return out.str();
}

}  // namespace

JsonNode::JsonNode(const Json& value, std::string file, std::string pointer)
    : m_value(&value), m_file(std::move(file)), m_pointer(std::move(pointer)) {}

void JsonNode::fail(const std::string& what) const {
    const std::string where = m_pointer.empty() ? "/" : m_pointer;
    throw_input_error(m_file + ": " + where + " = " + abbreviate(*m_value) + ": " + what);
}

JsonNode JsonNode::child(const std::string& key) const {
    if (!m_value->is_object())
        fail("expected an object");
    const auto it = m_value->find(key);
    if (it == m_value->end())
        fail("missing required key \"" + key + "\"");
    return JsonNode(*it, m_file, m_pointer + "/" + json_pointer_escape(key));
}

JsonNode JsonNode::child(size_t index) const {
    if (!m_value->is_array())
        fail("expected an array");
    if (index >= m_value->size())
        fail("index " + std::to_string(index) + " out of range");
    return JsonNode((*m_value)[index], m_file, m_pointer + "/" + std::to_string(index));
}

size_t JsonNode::size() const {
    return m_value->size();
}

double JsonNode::as_double() const {
    if (!m_value->is_number())
        fail("expected a number");
    const double v = m_value->get<double>();
    if (!std::isfinite(v))
        fail("expected a finite number");
    return v;
}

float JsonNode::as_float() const {
    const double v = as_double();
    if (std::abs(v) > 3.0e38)
        fail("number out of single-precision range");
    return static_cast<float>(v);
}

int64_t JsonNode::as_int() const {
    if (m_value->is_number_integer())
        return m_value->get<int64_t>();
    if (m_value->is_number_float()) {
        const double v = m_value->get<double>();
        if (std::isfinite(v) && v == std::floor(v) && std::abs(v) < 9.0e15)
            return static_cast<int64_t>(v);
    }
    fail("expected an integer");
}

bool JsonNode::as_bool() const {
    if (!m_value->is_boolean())
        fail("expected true or false");
    return m_value->get<bool>();
}

std::string JsonNode::as_string() const {
    if (!m_value->is_string())
        fail("expected a string");
    return m_value->get<std::string>();
}

Vec3 JsonNode::as_vec3() const {
    if (!m_value->is_array() || m_value->size() != 3)
        fail("expected an array of 3 numbers");
    return Vec3(child(0).as_float(), child(1).as_float(), child(2).as_float());
}

Vec3 JsonNode::as_point() const {
    const Vec3 p = as_vec3();
    for (int axis = 0; axis < 3; ++axis) {
        if (!(std::abs(p[axis]) <= kMaxCoordinateM))
            child(static_cast<size_t>(axis))
                .fail("coordinates must be within +-1e12 m (single precision breaks down beyond)");
    }
    return p;
}

Rgb JsonNode::as_rgb() const {
    if (m_value->is_number())
        return Rgb(as_float());
    if (!m_value->is_array() || m_value->size() != 3)
        fail("expected a number or an array [r, g, b]");
    return Rgb(child(0).as_float(), child(1).as_float(), child(2).as_float());
}

std::vector<JsonNode> JsonNode::elements() const {
    if (!m_value->is_array())
        fail("expected an array");
    std::vector<JsonNode> out;
    out.reserve(m_value->size());
    for (size_t i = 0; i < m_value->size(); ++i)
        out.push_back(child(i));
    return out;
}

void JsonNode::fail_range(const std::string& what, bool in_range_before_rounding) const {
    // A decimal inside the range may leave it as a float (0.99999999 -> 1, 1e-50 -> 0).
    if (in_range_before_rounding)
        fail(what + " (it rounds to the bound in single precision)");
    fail(what);
}

float JsonNode::positive() const {
    const float v = as_float();
    if (!(v > 0.0f))
        fail_range("must be > 0", as_double() > 0.0);
    return v;
}

float JsonNode::positive_length() const {
    const float v = positive();
    if (!(v <= kMaxCoordinateM))
        fail("must be <= 1e12 m (single precision breaks down beyond)");
    return v;
}

float JsonNode::non_negative() const {
    const float v = as_float();
    if (!(v >= 0.0f))
        fail("must be >= 0");
    return v;
}

Rgb JsonNode::non_negative_rgb() const {
    const Rgb c = as_rgb();
    if (!(c.r >= 0.0f && c.g >= 0.0f && c.b >= 0.0f))
        fail("must be >= 0 in every channel");
    return c;
}

float JsonNode::in_open(float lo, float hi) const {
    const float v = as_float();
    if (!(v > lo && v < hi))
        fail_range("must be in (" + format_number(lo) + ", " + format_number(hi) + ")",
                   as_double() > lo && as_double() < hi);
    return v;
}

float JsonNode::in_closed(float lo, float hi) const {
    const float v = as_float();
    if (!(v >= lo && v <= hi))
        fail_range("must be in [" + format_number(lo) + ", " + format_number(hi) + "]",
                   as_double() >= lo && as_double() <= hi);
    return v;
}

Vec3 JsonNode::unit_direction() const {
    // In double: the squared length of [1e20, 0, 0] overflows a float.
    const DVec3 v(as_vec3());
    const double length = glm::length(v);
    if (!(length > 0.0))
        fail("must be a non-zero vector");
    return Vec3(v / length);
}

JsonObjectReader::JsonObjectReader(const JsonNode& node) : m_node(node) {
    if (!node.is_object())
        node.fail("expected an object");
}

bool JsonObjectReader::has(const std::string& key) const {
    return m_node.value().contains(key);
}

std::optional<JsonNode> JsonObjectReader::optional(const std::string& key) {
    m_known.insert(key);
    if (!has(key))
        return std::nullopt;
    return m_node.child(key);
}

JsonNode JsonObjectReader::required(const std::string& key) {
    m_known.insert(key);
    return m_node.child(key);
}

void JsonObjectReader::finish() const {
    for (const auto& item : m_node.value().items()) {
        if (m_known.count(item.key()))
            continue;
        std::string expected;
        for (const auto& k : m_known)
            expected += (expected.empty() ? "" : ", ") + k;
        const JsonNode unknown(item.value(), m_node.file(),
                               m_node.pointer() + "/" + json_pointer_escape(item.key()));
        unknown.fail("unknown key \"" + item.key() + "\" (expected one of: " + expected + ")");
    }
}

}  // namespace kasumi
