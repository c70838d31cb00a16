#include "surface/shadows/weiler_atherton.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>

namespace kasumi {

namespace {

double cross(const DVec2& a, const DVec2& b) {
    return a.x * b.y - a.y * b.x;
}

struct Box {
    DVec2 min, max;
};

Box box_of(const DVec2& a, const DVec2& b, double epsilon) {
    return {glm::min(a, b) - DVec2(epsilon), glm::max(a, b) + DVec2(epsilon)};
}

bool apart(const Box& a, const Box& b) {
    return a.max.x < b.min.x || b.max.x < a.min.x || a.max.y < b.min.y || b.max.y < a.min.y;
}

bool apart(const Box& a, const DVec2& p) {
    return p.x < a.min.x || p.x > a.max.x || p.y < a.min.y || p.y > a.max.y;
}

Box box_of(const PolygonRegion& r, double epsilon) {
    Box b{DVec2(INFINITY), DVec2(-INFINITY)};
    for (const Ring& ring : r.rings)
        for (const DVec2& p : ring) {
            b.min = glm::min(b.min, p - DVec2(epsilon));
            b.max = glm::max(b.max, p + DVec2(epsilon));
        }
    return b;
}

/// A vertex to insert into an edge at parameter t in (0, 1).
struct Cut {
    double t;
    DVec2 p;
};
using Cuts = std::vector<std::vector<std::vector<Cut>>>;  ///< [ring][edge]

Cuts no_cuts(const std::vector<Ring>& rings) {
    Cuts c(rings.size());
    for (size_t r = 0; r < rings.size(); ++r)
        c[r].resize(rings[r].size());
    return c;
}

/// The rings with each edge's cuts inserted in order; repeated vertices are merged and rings
/// left with fewer than three vertices dropped.
std::vector<Ring> with_cuts(const std::vector<Ring>& rings, Cuts& cuts) {
    std::vector<Ring> out;
    for (size_t r = 0; r < rings.size(); ++r) {
        Ring ring;
        const auto push = [&](const DVec2& p) {
            if (ring.empty() || ring.back() != p)
                ring.push_back(p);
        };
        for (size_t i = 0; i < rings[r].size(); ++i) {
            push(rings[r][i]);
            std::vector<Cut>& c = cuts[r][i];
            std::stable_sort(c.begin(), c.end(),
                             [](const Cut& a, const Cut& b) { return a.t < b.t; });
            for (const Cut& cut : c)
                push(cut.p);
        }
        while (ring.size() > 1 && ring.front() == ring.back())
            ring.pop_back();
        if (ring.size() >= 3)
            out.push_back(std::move(ring));
    }
    return out;
}

/// Where p projects onto the edge a→b: parameter t and distance (metres). `interior` is false
/// when the foot lies within epsilon of an end or beyond.
struct Foot {
    double t = 0.0, distance = INFINITY;
    bool interior = false;
};

Foot foot(const DVec2& p, const DVec2& a, const DVec2& b, double epsilon) {
    const DVec2 e = b - a;
    const double length2 = glm::dot(e, e);
    Foot f;
    if (!(length2 > 0.0))
        return f;
    const double length = std::sqrt(length2);
    f.t = glm::dot(p - a, e) / length2;
    f.interior = f.t * length > epsilon && (1.0 - f.t) * length > epsilon;
    f.distance = std::abs(cross(e, p - a)) / length;
    return f;
}

/// Step 1 for the clip's vertices: snapped to subject vertices, or moved onto subject edges
/// and inserted there.
void snap_clip_vertices(std::vector<Ring>& subject, std::vector<Ring>& clip, double epsilon) {
    Cuts cuts = no_cuts(subject);
    for (Ring& ring : clip) {
        for (DVec2& q : ring) {
            double best = epsilon;
            const DVec2* snap = nullptr;
            for (const Ring& s : subject)
                for (const DVec2& p : s) {
                    const double d = glm::length(p - q);
                    if (d <= best) {
                        best = d;
                        snap = &p;
                    }
                }
            if (snap != nullptr) {
                q = *snap;
                continue;
            }
            best = epsilon;
            size_t edge_ring = 0, edge = 0;
            Foot edge_foot;
            for (size_t r = 0; r < subject.size(); ++r)
                for (size_t i = 0, n = subject[r].size(); i < n; ++i) {
                    const DVec2& a = subject[r][i];
                    const DVec2& b = subject[r][(i + 1) % n];
                    if (apart(box_of(a, b, epsilon), q))
                        continue;
                    const Foot f = foot(q, a, b, epsilon);
                    if (f.interior && f.distance <= best) {
                        best = f.distance;
                        edge_ring = r;
                        edge = i;
                        edge_foot = f;
                    }
                }
            if (edge_foot.interior) {
                const Ring& s = subject[edge_ring];
                const DVec2& a = s[edge];
                const DVec2& b = s[(edge + 1) % s.size()];
                q = a + edge_foot.t * (b - a);
                cuts[edge_ring][edge].push_back({edge_foot.t, q});
            }
        }
    }
    subject = with_cuts(subject, cuts);
    Cuts none = no_cuts(clip);
    clip = with_cuts(clip, none);  // vertices snapped together are merged
}

/// Step 1 for the subject's vertices: inserted into the clip edges they lie on.
void insert_subject_vertices(const std::vector<Ring>& subject, std::vector<Ring>& clip,
                             double epsilon) {
    Cuts cuts = no_cuts(clip);
    for (size_t r = 0; r < clip.size(); ++r)
        for (size_t i = 0, n = clip[r].size(); i < n; ++i) {
            const DVec2& a = clip[r][i];
            const DVec2& b = clip[r][(i + 1) % n];
            const Box box = box_of(a, b, epsilon);
            for (const Ring& s : subject)
                for (const DVec2& p : s) {
                    if (apart(box, p))
                        continue;
                    const Foot f = foot(p, a, b, epsilon);
                    if (f.interior && f.distance <= epsilon)
                        cuts[r][i].push_back({f.t, p});
                }
        }
    clip = with_cuts(clip, cuts);
}

/// Step 1, proper crossings: edges whose ends lie strictly on opposite sides of each other's
/// lines (farther than epsilon: nearer ends were made shared vertices above).
size_t insert_crossings(std::vector<Ring>& subject, std::vector<Ring>& clip, double epsilon) {
    Cuts subject_cuts = no_cuts(subject), clip_cuts = no_cuts(clip);
    size_t count = 0;
    const auto opposite = [&](double d1, double d2) {
        return (d1 > epsilon && d2 < -epsilon) || (d1 < -epsilon && d2 > epsilon);
    };
    for (size_t rs = 0; rs < subject.size(); ++rs)
        for (size_t i = 0, n = subject[rs].size(); i < n; ++i) {
            const DVec2& a = subject[rs][i];
            const DVec2& b = subject[rs][(i + 1) % n];
            const Box box = box_of(a, b, 0.0);
            const double lab = glm::length(b - a);
            for (size_t rc = 0; rc < clip.size(); ++rc)
                for (size_t k = 0, m = clip[rc].size(); k < m; ++k) {
                    const DVec2& c = clip[rc][k];
                    const DVec2& d = clip[rc][(k + 1) % m];
                    if (apart(box, box_of(c, d, 0.0)))
                        continue;
                    const double d1 = cross(b - a, c - a) / lab, d2 = cross(b - a, d - a) / lab;
                    if (!opposite(d1, d2))
                        continue;
                    const double lcd = glm::length(d - c);
                    const double d3 = cross(d - c, a - c) / lcd, d4 = cross(d - c, b - c) / lcd;
                    if (!opposite(d3, d4))
                        continue;
                    const double t = d3 / (d3 - d4), s = d1 / (d1 - d2);
                    // From the nearer end: the rounding error scales with the distance to it.
                    const DVec2 x = t <= 0.5 ? a + t * (b - a) : b + (1.0 - t) * (a - b);
                    subject_cuts[rs][i].push_back({t, x});
                    clip_cuts[rc][k].push_back({s, x});
                    ++count;
                }
        }
    subject = with_cuts(subject, subject_cuts);
    clip = with_cuts(clip, clip_cuts);
    return count;
}

using EdgeKey = std::array<double, 4>;

EdgeKey key(const DVec2& a, const DVec2& b) {
    return {a.x, a.y, b.x, b.y};
}

enum class Side { Inside, Outside, Same, Opposite };

/// Step 2: the side of each edge of `rings` relative to `other` (whose edges are in `edges`).
std::vector<Side> classify(const std::vector<Ring>& rings, const PolygonRegion& other,
                           const std::map<EdgeKey, int>& edges) {
    std::vector<Side> sides;
    for (const Ring& ring : rings)
        for (size_t i = 0, n = ring.size(); i < n; ++i) {
            const DVec2& a = ring[i];
            const DVec2& b = ring[(i + 1) % n];
            if (edges.count(key(a, b)) != 0)
                sides.push_back(Side::Same);
            else if (edges.count(key(b, a)) != 0)
                sides.push_back(Side::Opposite);
            else
                sides.push_back(winding_number(other, 0.5 * (a + b)) != 0 ? Side::Inside
                                                                          : Side::Outside);
        }
    return sides;
}

std::map<EdgeKey, int> edge_set(const std::vector<Ring>& rings) {
    std::map<EdgeKey, int> edges;
    for (const Ring& ring : rings)
        for (size_t i = 0, n = ring.size(); i < n; ++i)
            ++edges[key(ring[i], ring[(i + 1) % n])];
    return edges;
}

struct Edge {
    DVec2 a, b;
};

/// Step 3: links directed edges into closed rings at their shared vertices, taking the
/// leftmost turn where several leave one vertex. An edge and its reverse cancel first (two
/// results' boundaries meeting along it).
std::vector<Ring> link(const std::vector<Edge>& input) {
    std::map<EdgeKey, int> count;
    for (const Edge& e : input)
        ++count[key(e.a, e.b)];
    std::vector<Edge> edges;
    for (const Edge& e : input) {
        int& forward = count[key(e.a, e.b)];
        auto backward = count.find(key(e.b, e.a));
        if (backward != count.end() && backward->second > 0 && forward > 0) {
            --forward;
            --backward->second;
            continue;
        }
        if (forward > 0) {
            --forward;
            edges.push_back(e);
        }
    }
    std::map<std::pair<double, double>, std::vector<size_t>> leaving;
    for (size_t i = 0; i < edges.size(); ++i)
        leaving[{edges[i].a.x, edges[i].a.y}].push_back(i);
    std::vector<bool> used(edges.size(), false);
    std::vector<Ring> rings;
    for (size_t first = 0; first < edges.size(); ++first) {
        if (used[first])
            continue;
        Ring ring{edges[first].a};
        used[first] = true;
        size_t current = first;
        while (edges[current].b != edges[first].a) {
            const DVec2 in = edges[current].b - edges[current].a;
            size_t next = edges.size();
            double best = -INFINITY;
            for (size_t j : leaving[{edges[current].b.x, edges[current].b.y}]) {
                if (used[j])
                    continue;
                const DVec2 out = edges[j].b - edges[j].a;
                const double turn = std::atan2(cross(in, out), glm::dot(in, out));
                if (turn > best) {
                    best = turn;
                    next = j;
                }
            }
            if (next == edges.size())
                break;  // an open chain: cannot happen for closed input rings
            ring.push_back(edges[next].a);
            used[next] = true;
            current = next;
        }
        if (ring.size() >= 3)
            rings.push_back(std::move(ring));
    }
    return rings;
}

struct Noded {
    std::vector<Ring> subject, clip;
    std::vector<Side> subject_sides, clip_sides;
    size_t intersections = 0;
};

Noded node(const PolygonRegion& subject, const PolygonRegion& clip, double epsilon) {
    Noded n{subject.rings, clip.rings, {}, {}, 0};
    snap_clip_vertices(n.subject, n.clip, epsilon);
    insert_subject_vertices(n.subject, n.clip, epsilon);
    n.intersections = insert_crossings(n.subject, n.clip, epsilon);
    n.subject_sides = classify(n.subject, PolygonRegion{n.clip}, edge_set(n.clip));
    n.clip_sides = classify(n.clip, PolygonRegion{n.subject}, edge_set(n.subject));
    return n;
}

/// The edges of `rings` whose side is one of `keep`, reversed when `reverse`.
void select(const std::vector<Ring>& rings, const std::vector<Side>& sides,
            std::initializer_list<Side> keep, bool reverse, std::vector<Edge>& out) {
    size_t e = 0;
    for (const Ring& ring : rings)
        for (size_t i = 0, n = ring.size(); i < n; ++i, ++e)
            if (std::find(keep.begin(), keep.end(), sides[e]) != keep.end())
                out.push_back(reverse ? Edge{ring[(i + 1) % n], ring[i]}
                                      : Edge{ring[i], ring[(i + 1) % n]});
}

}  // namespace

RegionClip weiler_atherton(const PolygonRegion& subject, const PolygonRegion& clip,
                           double epsilon) {
    RegionClip result;
    if (subject.rings.empty())
        return result;
    if (clip.rings.empty() || apart(box_of(subject, epsilon), box_of(clip, 0.0))) {
        result.outside = subject;
        return result;
    }
    const Noded n = node(subject, clip, epsilon);
    result.intersections = n.intersections;
    std::vector<Edge> inside, outside;
    // Clip edges lying on subject edges are Same or Opposite: the subject's copy stands for
    // them, so only the clip's Inside edges are taken.
    select(n.subject, n.subject_sides, {Side::Inside, Side::Same}, false, inside);
    select(n.clip, n.clip_sides, {Side::Inside}, false, inside);
    select(n.subject, n.subject_sides, {Side::Outside, Side::Opposite}, false, outside);
    select(n.clip, n.clip_sides, {Side::Inside}, true, outside);
    result.inside.rings = link(inside);
    result.outside.rings = link(outside);
    return result;
}

PolygonRegion unite(const PolygonRegion& a, const PolygonRegion& b, double epsilon) {
    if (a.rings.empty())
        return b;
    if (b.rings.empty() || apart(box_of(a, epsilon), box_of(b, 0.0))) {
        PolygonRegion r = a;
        r.rings.insert(r.rings.end(), b.rings.begin(), b.rings.end());
        return r;
    }
    const Noded n = node(a, b, epsilon);
    std::vector<Edge> edges;
    select(n.subject, n.subject_sides, {Side::Outside, Side::Same}, false, edges);
    select(n.clip, n.clip_sides, {Side::Outside}, false, edges);
    return PolygonRegion{link(edges)};
}

}  // namespace kasumi
