#include "surface/shadows/polygon_region.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace kasumi {

double signed_area(const Ring& ring) {
    double twice = 0.0;
    for (size_t i = 0, n = ring.size(); i < n; ++i) {
        const DVec2& a = ring[i];
        const DVec2& b = ring[(i + 1) % n];
        twice += a.x * b.y - a.y * b.x;
    }
    return 0.5 * twice;
}

double area(const PolygonRegion& region) {
    double sum = 0.0;
    for (const Ring& ring : region.rings)
        sum += signed_area(ring);
    return sum;
}

namespace {

int ring_winding(const Ring& ring, const DVec2& p) {
    int w = 0;
    for (size_t i = 0, n = ring.size(); i < n; ++i) {
        const DVec2& a = ring[i];
        const DVec2& b = ring[(i + 1) % n];
        // Side of p from the edge a→b: > 0 left. Upward edges with p strictly left count +1,
        // downward ones with p strictly right −1 (half-open in y, so a vertex counts once).
        const double side = (b.x - a.x) * (p.y - a.y) - (p.x - a.x) * (b.y - a.y);
        if (a.y <= p.y) {
            if (b.y > p.y && side > 0.0)
                ++w;
        } else if (b.y <= p.y && side < 0.0) {
            --w;
        }
    }
    return w;
}

}  // namespace

int winding_number(const PolygonRegion& region, const DVec2& p) {
    int w = 0;
    for (const Ring& ring : region.rings)
        w += ring_winding(ring, p);
    return w;
}

double distance_to_boundary(const PolygonRegion& region, const DVec2& p) {
    double best = INFINITY;
    for (const Ring& ring : region.rings)
        for (size_t i = 0, n = ring.size(); i < n; ++i) {
            const DVec2 a = ring[i], e = ring[(i + 1) % n] - a;
            const double length2 = glm::dot(e, e);
            const double t =
                length2 > 0.0 ? std::clamp(glm::dot(p - a, e) / length2, 0.0, 1.0) : 0.0;
            best = std::min(best, glm::length(p - (a + t * e)));
        }
    return best;
}

PolygonRegion region_of(const ConvexPolygon& polygon) {
    PolygonRegion r;
    if (polygon.vertices.size() >= 3)
        r.rings.push_back(polygon.vertices);
    return r;
}

std::vector<PolygonRegion> polygons_with_holes(const PolygonRegion& region) {
    std::vector<size_t> outer, holes;
    for (size_t i = 0; i < region.rings.size(); ++i)
        (signed_area(region.rings[i]) > 0.0 ? outer : holes).push_back(i);
    // Smallest outer ring first: the first one that encloses a hole is its nearest.
    std::sort(outer.begin(), outer.end(), [&](size_t a, size_t b) {
        return signed_area(region.rings[a]) < signed_area(region.rings[b]);
    });
    std::vector<PolygonRegion> out(outer.size());
    for (size_t k = 0; k < outer.size(); ++k)
        out[k].rings.push_back(region.rings[outer[k]]);
    for (size_t h : holes) {
        const Ring& hole = region.rings[h];
        // A hole may touch its outer ring at vertices: test its edges' midpoints too, and take
        // the first outer ring that strictly encloses any of them.
        size_t owner = outer.size() - 1;  // the largest, should no test succeed (rounding)
        for (size_t k = 0; k < outer.size(); ++k) {
            const Ring& ring = region.rings[outer[k]];
            bool inside = false;
            for (size_t i = 0, n = hole.size(); i < n && !inside; ++i)
                inside = ring_winding(ring, hole[i]) != 0 ||
                         ring_winding(ring, 0.5 * (hole[i] + hole[(i + 1) % n])) != 0;
            if (inside) {
                owner = k;
                break;
            }
        }
        if (!outer.empty())
            out[owner].rings.push_back(hole);
    }
    return out;
}

}  // namespace kasumi
