#include "surface/shadows/convex_polygon.h"

#include "surface/shadows/polygon_region.h"

#include <glm/geometric.hpp>

namespace kasumi {

double area(const ConvexPolygon& polygon) {
    return signed_area(polygon.vertices);
}

PolygonSplit split(const ConvexPolygon& polygon, const HalfPlane& h, double tolerance) {
    const std::vector<DVec2>& v = polygon.vertices;
    const size_t n = v.size();
    std::vector<double> d(n);
    bool any_in = false, any_out = false;
    for (size_t i = 0; i < n; ++i) {
        d[i] = signed_distance(h, v[i]);
        if (std::abs(d[i]) <= tolerance)
            d[i] = 0.0;
        any_in = any_in || d[i] > 0.0;
        any_out = any_out || d[i] < 0.0;
    }
    PolygonSplit s;
    if (!any_out) {
        s.inside = polygon;
        return s;
    }
    if (!any_in) {
        s.outside = polygon;
        return s;
    }
    for (size_t i = 0; i < n; ++i) {
        const size_t j = (i + 1) % n;
        if (d[i] >= 0.0)
            s.inside.vertices.push_back(v[i]);
        if (d[i] <= 0.0)
            s.outside.vertices.push_back(v[i]);
        // A strict sign change: the one new vertex, shared by both sides. Interpolating from
        // the vertex with the smaller |d| keeps the point closest to the exact crossing.
        if ((d[i] > 0.0 && d[j] < 0.0) || (d[i] < 0.0 && d[j] > 0.0)) {
            const double t = d[i] / (d[i] - d[j]);
            const DVec2 x = t <= 0.5 ? v[i] + t * (v[j] - v[i]) : v[j] + (1.0 - t) * (v[i] - v[j]);
            s.inside.vertices.push_back(x);
            s.outside.vertices.push_back(x);
        }
    }
    return s;
}

bool contains(const ConvexPolygon& polygon, const DVec2& p, double tolerance) {
    const std::vector<DVec2>& v = polygon.vertices;
    for (size_t i = 0, n = v.size(); i < n; ++i) {
        const DVec2 edge = v[(i + 1) % n] - v[i];
        const double length = glm::length(edge);
        if (!(length > 0.0))
            continue;
        // Cross product: positive to the left of a counter-clockwise edge (inside).
        const DVec2 r = p - v[i];
        if ((edge.x * r.y - edge.y * r.x) / length < -tolerance)
            return false;
    }
    return true;
}

}  // namespace kasumi
