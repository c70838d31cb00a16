#include "core/error.h"
#include "surface/shape.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <string>
#include <string_view>
#include <utility>

namespace kasumi {

namespace {

/// One line's tokens, split on blanks, with the location for error messages.
class ObjLine {
  public:
    ObjLine(const std::string& path, size_t number, std::string_view text)
        : m_path(path), m_number(number), m_rest(text) {}

    [[noreturn]] void fail(const std::string& what) const {
        throw_input_error(m_path + ":" + std::to_string(m_number) + ": " + what);
    }

    /// Next blank-separated token, or empty at the end of the line.
    std::string_view next() {
        size_t begin = 0;
        while (begin < m_rest.size() && is_blank(m_rest[begin]))
            ++begin;
        size_t end = begin;
        while (end < m_rest.size() && !is_blank(m_rest[end]))
            ++end;
        const std::string_view token = m_rest.substr(begin, end - begin);
        m_rest.remove_prefix(end);
        return token;
    }

    float number() {
        const std::string_view token = next();
        if (token.empty())
            fail("expected a number");
        return parse_float(token);
    }

    float parse_float(std::string_view token) const {
        float value = 0.0f;
        const char* first = token.data();
        if (!token.empty() && token.front() == '+')
            ++first;
        const auto [ptr, ec] = std::from_chars(first, token.data() + token.size(), value);
        if (ec != std::errc() || ptr != token.data() + token.size() || !std::isfinite(value))
            fail("invalid number \"" + std::string(token) + "\"");
        return value;
    }

    /// An OBJ index (1-based, or negative counting back from the last element so far) made
    /// 0-based and checked against `count` elements.
    uint32_t parse_index(std::string_view token, size_t count, const char* what) const {
        long long value = 0;
        const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
        if (ec != std::errc() || ptr != token.data() + token.size())
            fail(std::string("invalid ") + what + " index \"" + std::string(token) + "\"");
        const long long resolved = value < 0 ? static_cast<long long>(count) + value : value - 1;
        if (value == 0 || resolved < 0 || resolved >= static_cast<long long>(count))
            fail(std::string(what) + " index " + std::to_string(value) + " out of range (" +
                 std::to_string(count) + " defined so far)");
        return static_cast<uint32_t>(resolved);
    }

  private:
    static bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

    const std::string& m_path;
    size_t m_number;
    std::string_view m_rest;
};

/// A face corner: position index and normal index (-1 when the face gives none).
struct Corner {
    uint32_t position = 0;
    int64_t normal = -1;
};

Corner parse_corner(const ObjLine& line, std::string_view token, size_t positions, size_t normals) {
    Corner c;
    const size_t slash1 = token.find('/');
    c.position = line.parse_index(token.substr(0, slash1), positions, "vertex");
    if (slash1 == std::string_view::npos)
        return c;
    const std::string_view rest = token.substr(slash1 + 1);
    const size_t slash2 = rest.find('/');
    if (slash2 == std::string_view::npos)
        return c;  // v/vt: texture coordinates are ignored
    const std::string_view normal = rest.substr(slash2 + 1);
    if (normal.empty())
        line.fail("empty normal index in \"" + std::string(token) + "\"");
    c.normal = line.parse_index(normal, normals, "normal");
    return c;
}

}  // namespace

TriangleMesh load_obj(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw_input_error(path + ": cannot open file");

    std::vector<Vec3> positions;
    std::vector<Vec3> normals;
    // Triangles as corners; vertices are de-indexed after reading, since OBJ indexes positions
    // and normals separately while TriangleMesh shares one index per vertex.
    std::vector<std::array<Corner, 3>> corners;
    bool any_normal = false;

    std::string text;
    size_t number = 0;
    std::vector<Corner> polygon;
    while (std::getline(in, text)) {
        ++number;
        ObjLine line(path, number, text);
        const std::string_view keyword = line.next();
        if (keyword.empty() || keyword.front() == '#')
            continue;
        if (keyword == "v") {
            const float x = line.number();
            const float y = line.number();
            const float z = line.number();
            positions.emplace_back(x, y, z);  // an optional w (or vertex colour) is ignored
        } else if (keyword == "vn") {
            const float x = line.number();
            const float y = line.number();
            const float z = line.number();
            const Vec3 n(x, y, z);
            const float length = glm::length(n);
            if (!(length > 0.0f) || !std::isfinite(length))
                line.fail("normal has zero length");
            normals.push_back(n / length);
        } else if (keyword == "f") {
            polygon.clear();
            for (std::string_view token = line.next(); !token.empty(); token = line.next())
                polygon.push_back(parse_corner(line, token, positions.size(), normals.size()));
            if (polygon.size() < 3)
                line.fail("a face needs at least 3 vertices");
            for (const Corner& c : polygon)
                any_normal |= c.normal >= 0;
            // Fan triangulation: exact for convex polygons, which is what exporters write.
            for (size_t i = 1; i + 1 < polygon.size(); ++i)
                corners.push_back({polygon[0], polygon[i], polygon[i + 1]});
        }
        // vt, o, g, s, usemtl, mtllib, l, p and other statements carry nothing we use.
    }
    if (in.bad())
        throw_input_error(path + ": read error");
    if (corners.empty())
        throw_input_error(path + ": mesh has no faces");

    TriangleMesh mesh;
    std::map<std::pair<uint32_t, int64_t>, uint32_t> vertex_of;
    for (size_t f = 0; f < corners.size(); ++f) {
        std::array<uint32_t, 3> triangle{};
        for (int k = 0; k < 3; ++k) {
            const Corner& c = corners[f][k];
            // A corner without a normal in a mesh that has some: give it the face normal, on a
            // vertex of its own (keyed by face), so flat faces stay flat beside smooth ones.
            const int64_t key = c.normal >= 0 ? c.normal : -2 - static_cast<int64_t>(f);
            const auto [it, inserted] = vertex_of.try_emplace(
                {c.position, any_normal ? key : -1}, static_cast<uint32_t>(mesh.positions.size()));
            if (inserted) {
                mesh.positions.push_back(positions[c.position]);
                if (any_normal) {
                    if (c.normal >= 0) {
                        mesh.normals.push_back(normals[static_cast<size_t>(c.normal)]);
                    } else {
                        const Vec3& p0 = positions[corners[f][0].position];
                        const Vec3 face = glm::cross(positions[corners[f][1].position] - p0,
                                                     positions[corners[f][2].position] - p0);
                        const float length = glm::length(face);
                        mesh.normals.push_back(length > 0.0f ? face / length : Vec3(0, 0, 1));
                    }
                }
            }
            triangle[k] = it->second;
        }
        mesh.triangles.push_back(triangle);
    }
    return mesh;
}

}  // namespace kasumi
