#include "lights/polygon_light.h"

namespace kasumi {

namespace {

/// Newell's normal, Σ v_i × v_{i+1}: twice the vector area, for any planar polygon.
DVec3 vector_area2(const std::vector<Vec3>& v) {
    DVec3 sum(0.0);
    for (size_t i = 0; i < v.size(); ++i)
        sum += glm::cross(DVec3(v[i]), DVec3(v[(i + 1) % v.size()]));
    return sum;
}

/// Vertices relative to the receiver; a plane cuts a convex polygon in at most two edges, so
/// clipping adds at most one vertex. Fixed-size: the closed form runs per shading point.
struct ClippedPolygon {
    DVec3 r[kMaxPolygonVertices + 1];
    size_t count = 0;
};

/// Sutherland-Hodgman clip of a polygon (relative to p) to the half-space n·r ≥ 0; the order of
/// the vertices is kept, so the orientation is too.
ClippedPolygon clip_to_upper_half_space(const std::vector<Vec3>& vertices, const DVec3& p,
                                        const DVec3& n) {
    ClippedPolygon out;
    const size_t count = vertices.size();
    for (size_t i = 0; i < count; ++i) {
        const DVec3 a = DVec3(vertices[i]) - p;
        const DVec3 b = DVec3(vertices[(i + 1) % count]) - p;
        const double da = glm::dot(n, a), db = glm::dot(n, b);
        if (da >= 0.0 && out.count <= kMaxPolygonVertices)
            out.r[out.count++] = a;
        if ((da >= 0.0) != (db >= 0.0) && out.count <= kMaxPolygonVertices) {
            const double t = da / (da - db);
            out.r[out.count++] = a + t * (b - a);
        }
    }
    return out;
}

}  // namespace

std::string polygon_problem(const std::vector<Vec3>& vertices) {
    const size_t count = vertices.size();
    if (count < 3)
        return "a polygon needs at least 3 vertices";
    if (count > kMaxPolygonVertices)
        return "a polygon light has at most " + std::to_string(kMaxPolygonVertices) + " vertices";
    double size = 0.0;
    for (const Vec3& v : vertices)
        size = std::max(size, glm::length(DVec3(v - vertices[0])));
    for (size_t i = 0; i < count; ++i) {
        if (!(glm::length(DVec3(vertices[(i + 1) % count] - vertices[i])) > 1e-6 * size))
            return "vertices " + std::to_string(i) + " and " + std::to_string((i + 1) % count) +
                   " coincide";
    }
    const DVec3 area2 = vector_area2(vertices);
    const double len = glm::length(area2);
    if (!(len > 1e-10 * size * size))
        return "the polygon has zero area (degenerate)";
    const DVec3 normal = area2 / len;
    for (size_t i = 0; i < count; ++i) {
        if (std::abs(glm::dot(DVec3(vertices[i] - vertices[0]), normal)) > 1e-4 * size)
            return "vertex " + std::to_string(i) + " is off the polygon's plane (not planar)";
        const DVec3 e0 = DVec3(vertices[(i + 1) % count] - vertices[i]);
        const DVec3 e1 = DVec3(vertices[(i + 2) % count] - vertices[(i + 1) % count]);
        if (glm::dot(glm::cross(e0, e1), normal) < -1e-9 * size * size)
            return "the polygon is not convex at vertex " + std::to_string((i + 1) % count);
    }
    return "";
}

PolygonLight make_polygon_light(std::vector<Vec3> vertices, const Rgb& luminance, bool two_sided) {
    PolygonLight light;
    light.vertices = std::move(vertices);
    light.luminance = luminance;
    light.two_sided = two_sided;
    const DVec3 area2 = vector_area2(light.vertices);
    light.normal = Vec3(glm::normalize(area2));
    light.area = static_cast<float>(0.5 * glm::length(area2));
    double cumulative = 0.0;
    const DVec3 v0(light.vertices[0]);
    for (size_t i = 1; i + 1 < light.vertices.size(); ++i) {
        cumulative += 0.5 * glm::length(glm::cross(DVec3(light.vertices[i]) - v0,
                                                   DVec3(light.vertices[i + 1]) - v0));
        light.fan_cdf.push_back(static_cast<float>(cumulative));
    }
    for (float& c : light.fan_cdf)
        c /= static_cast<float>(cumulative);
    light.fan_cdf.back() = 1.0f;
    return light;
}

Rgb unshadowed_irradiance(const PolygonLight& light, const Vec3& p, const Vec3& n) {
    const DVec3 q(p), nd(n), normal(light.normal);
    const double side = glm::dot(q - DVec3(light.vertices[0]), normal);
    if (side == 0.0 || (side < 0.0 && !light.two_sided))
        return Rgb(0.0f);
    const ClippedPolygon clipped = clip_to_upper_half_space(light.vertices, q, nd);
    const size_t count = clipped.count;
    if (count < 3)
        return Rgb(0.0f);
    // Stored vertices wind counter-clockwise seen from the front; from the back they appear
    // clockwise, which flips the sign of every term.
    const double orientation = side > 0.0 ? 1.0 : -1.0;
    double sum = 0.0;
    for (size_t i = 0; i < count; ++i) {
        const DVec3& a = clipped.r[i];
        const DVec3& b = clipped.r[(i + 1) % count];
        const DVec3 c = glm::cross(b, a);
        const double len = glm::length(c);
        if (!(len > 0.0))
            continue;
        // atan2 keeps the angle accurate for nearly parallel and nearly opposite edges alike.
        const double theta = std::atan2(len, glm::dot(a, b));
        sum += theta * glm::dot(c, nd) / len;
    }
    const double e = 0.5 * orientation * sum;
    return light.luminance * static_cast<float>(std::max(e, 0.0));
}

namespace {

/// The point of the polygon for u: a parallelogram v0 + u.x (v1 − v0) + u.y (v3 − v0), which
/// is uniform in area and keeps stratified u stratified; any other polygon a fan triangle
/// picked by area, then Shirley's square-root warp inside it.
Vec3 polygon_point(const PolygonLight& light, Vec2 u) {
    const auto& v = light.vertices;
    if (v.size() == 4) {
        const Vec3 gap = (v[0] + v[2]) - (v[1] + v[3]);
        const Vec3 diagonal = v[2] - v[0];
        if (glm::dot(gap, gap) <= 1e-10f * glm::dot(diagonal, diagonal))
            return v[0] + u.x * (v[1] - v[0]) + u.y * (v[3] - v[0]);
    }
    // Pick a fan triangle by area, then reuse u.x rescaled within its CDF interval.
    size_t tri = 0;
    while (tri + 1 < light.fan_cdf.size() && u.x >= light.fan_cdf[tri])
        ++tri;
    const float lo = tri == 0 ? 0.0f : light.fan_cdf[tri - 1];
    const float width = light.fan_cdf[tri] - lo;
    const float ux = width > 0.0f ? std::clamp((u.x - lo) / width, 0.0f, 1.0f) : 0.5f;
    // Uniform point in a triangle (Shirley's square-root warp).
    const float su = std::sqrt(ux);
    const float b1 = 1.0f - su, b2 = u.y * su;
    const Vec3& v0 = light.vertices[0];
    return v0 + b1 * (light.vertices[tri + 1] - v0) + b2 * (light.vertices[tri + 2] - v0);
}

}  // namespace

IncidentLight sample_incident(const PolygonLight& light, const Vec3& p, Vec2 u) {
    const Vec3 x = polygon_point(light, u);
    IncidentLight in;
    in.light_position = x;
    const Vec3 to = x - p;
    const float r2 = glm::dot(to, to);
    if (!(r2 > 1e-12f))
        return in;
    in.distance = std::sqrt(r2);
    in.wi = to / in.distance;
    const float cos_light = -glm::dot(in.wi, light.normal);  // > 0 when p is in front
    if (cos_light > 0.0f || (light.two_sided && cos_light < 0.0f))
        in.irradiance = light.luminance * (std::abs(cos_light) * light.area / r2);
    return in;
}

float polygon_flux_lm(const PolygonLight& light) {
    return kPi * luminance(light.luminance) * light.area * (light.two_sided ? 2.0f : 1.0f);
}

}  // namespace kasumi
