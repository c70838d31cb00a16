#include "surface/shadows/shadow_polygons.h"

#include "surface/shadows/welded_mesh.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>

namespace kasumi {

namespace {

/// Relative tolerances, as fractions of the receiving face's size: vertices closer than this
/// to a cut line count as on it, and occluders closer than this to the receiver's plane (or
/// to the light's level, for a point light) are cut off there.
constexpr double kOnLine = 1e-9;
constexpr double kSlab = 1e-6;

/// A triangle's bounding sphere as seen from the light: for a point light the cone from the
/// light around it (unit axis, cosine and sine of the half-angle; a light inside the sphere
/// gives a cone of half-angle π that culls nothing), for a parallel light the sphere's
/// centre and radius (compared in the plane across the light's direction).
struct LightView {
    DVec3 centre{0.0};
    double radius = 0.0;
    DVec3 axis{0.0, 0.0, 1.0};
    double half_angle = 0.0;
};

LightView light_view(const std::array<DVec3, 3>& v, const LightCentre& light) {
    LightView view;
    view.centre = (v[0] + v[1] + v[2]) / 3.0;
    for (const DVec3& p : v)
        view.radius = std::max(view.radius, glm::length(p - view.centre));
    if (!light.at_infinity) {
        const DVec3 d = view.centre - DVec3(light.position);
        const double distance = glm::length(d);
        view.axis = distance > 0.0 ? d / distance : DVec3(0.0, 0.0, 1.0);
        view.half_angle =
            distance > view.radius ? std::asin(view.radius / distance) : 3.141592653589793;
    }
    return view;
}

/// False when no ray from the light can meet both triangles (their light views are apart);
/// the 1e-9 margin keeps touching views together.
bool may_overlap(const LightView& a, const LightView& b, const LightCentre& light) {
    if (light.at_infinity) {
        const DVec3 w(light.direction);
        DVec3 d = b.centre - a.centre;
        d -= glm::dot(d, w) * w;
        return glm::length(d) <= (a.radius + b.radius) * (1.0 + 1e-9);
    }
    const double sum = a.half_angle + b.half_angle;
    if (sum >= 3.141592653589793)
        return true;
    const double angle = std::acos(std::clamp(glm::dot(a.axis, b.axis), -1.0, 1.0));
    return angle <= sum * (1.0 + 1e-9) + 1e-12;
}

struct Occluder {
    std::array<DVec3, 3> vertices;
    uint32_t shape = 0;
    uint32_t primitive = 0;
    LightView view;
};

using Polygon3 = std::vector<DVec3>;

/// The part of `polygon` where height(p) >= 0 (Sutherland–Hodgman against one plane).
template <typename Height>
Polygon3 clip_below(const Polygon3& polygon, Height height) {
    Polygon3 out;
    const size_t n = polygon.size();
    for (size_t i = 0; i < n; ++i) {
        const DVec3& a = polygon[i];
        const DVec3& b = polygon[(i + 1) % n];
        const double ha = height(a), hb = height(b);
        if (ha >= 0.0)
            out.push_back(a);
        if ((ha >= 0.0) != (hb >= 0.0))
            out.push_back(a + (ha / (ha - hb)) * (b - a));
    }
    return out;
}

std::vector<Occluder> collect_occluders(const std::vector<Shape>& shapes, const LightCentre& light,
                                        std::vector<std::vector<std::array<DVec3, 3>>>& faces) {
    std::vector<Occluder> occluders;
    faces.resize(shapes.size());
    for (size_t s = 0; s < shapes.size(); ++s) {
        const auto mesh = welded_mesh(shapes[s]);
        if (!mesh)
            continue;
        const bool closed = is_closed(*mesh);
        for (size_t i = 0; i < mesh->triangles.size(); ++i) {
            const auto& t = mesh->triangles[i];
            const std::array<DVec3, 3> v = {DVec3(mesh->positions[t[0]]),
                                            DVec3(mesh->positions[t[1]]),
                                            DVec3(mesh->positions[t[2]])};
            faces[s].push_back(v);
            // A closed solid is entered through a light-facing triangle by every ray from the
            // light that meets it; the others shadow nothing more.
            const DVec3 n = glm::cross(v[1] - v[0], v[2] - v[0]);
            if (closed && !(light_height(light, v[0], n) > 0.0))
                continue;
            occluders.push_back(
                {v, static_cast<uint32_t>(s), static_cast<uint32_t>(i), light_view(v, light)});
        }
    }
    return occluders;
}

/// The edge lines, in the receiver's frame, of the shadow that `occluder` casts on the plane of
/// `frame` (light at height `light_h` > 0 above it); empty when it casts none there.
std::vector<HalfPlane> shadow_edges(const Occluder& occluder, const FaceFrame& frame,
                                    const LightCentre& light, double light_h, double size) {
    const auto height = [&](const DVec3& p) { return glm::dot(frame.normal, p - frame.origin); };
    const double low = kSlab * size;
    Polygon3 p(occluder.vertices.begin(), occluder.vertices.end());
    double top = -kInfinity;
    for (const DVec3& v : p)
        top = std::max(top, height(v));
    if (top <= low)
        return {};
    p = clip_below(p, [&](const DVec3& v) { return height(v) - low; });
    if (!light.at_infinity) {
        const double high = light_h * (1.0 - kSlab);
        p = clip_below(p, [&](const DVec3& v) { return high - height(v); });
    }
    if (p.size() < 3)
        return {};
    DVec3 centroid(0.0);
    for (const DVec3& v : p)
        centroid += v;
    centroid /= static_cast<double>(p.size());
    // An occluder edge-on to the light casts a shadow of no area.
    const DVec3 n_t = glm::cross(occluder.vertices[1] - occluder.vertices[0],
                                 occluder.vertices[2] - occluder.vertices[0]);
    const double n_length = glm::length(n_t);
    const DVec3 l_pos(light.position), l_dir(light.direction);
    const double edge_on = light.at_infinity ? glm::dot(n_t, l_dir) / n_length
                                             : glm::dot(n_t, l_pos - occluder.vertices[0]) /
                                                   (n_length * glm::length(l_pos - centroid));
    if (!(std::abs(edge_on) > kOnLine))
        return {};
    std::vector<HalfPlane> edges;
    for (size_t k = 0; k < p.size(); ++k) {
        const DVec3& a = p[k];
        const DVec3& b = p[(k + 1) % p.size()];
        // The plane through the light and the edge a b: normal n, containing `on_plane`.
        const DVec3 n =
            light.at_infinity ? glm::cross(b - a, l_dir) : glm::cross(a - l_pos, b - l_pos);
        const DVec3 on_plane = light.at_infinity ? a : l_pos;
        double inside = glm::dot(n, centroid - on_plane);
        if (inside == 0.0)
            continue;  // a zero-length edge left by the slab clip
        const double sign = inside > 0.0 ? 1.0 : -1.0;
        const DVec2 normal(sign * glm::dot(n, frame.e_u), sign * glm::dot(n, frame.e_v));
        const double offset = sign * glm::dot(n, frame.origin - on_plane);
        const double length = glm::length(normal);
        // The edge plane cannot be parallel to the receiver (the slab keeps the occluder below
        // the light's level), except through rounding: then it bounds all or nothing.
        if (!(length > 1e-12 * glm::length(n))) {
            if (offset < 0.0)
                return {};
            continue;
        }
        edges.push_back({normal / length, offset / length});
    }
    return edges;
}

FaceDetail clip_face(const std::array<DVec3, 3>& v, uint32_t shape, uint32_t primitive,
                     const std::vector<Occluder>& occluders, const LightCentre& light,
                     size_t& clipped_pairs) {
    FaceDetail detail;
    DVec3 n = glm::cross(v[1] - v[0], v[2] - v[0]);
    const double twice_area = glm::length(n);
    const double size =
        std::max({glm::length(v[1] - v[0]), glm::length(v[2] - v[1]), glm::length(v[0] - v[2])});
    if (!(twice_area > 0.0)) {
        detail.faces_light = false;
        return detail;
    }
    n /= twice_area;
    double light_h = light_height(light, v[0], n);
    if (light_h < 0.0) {
        n = -n;
        light_h = -light_h;
    }
    FaceFrame& f = detail.frame;
    f.origin = v[0];
    f.normal = n;
    f.e_u = glm::normalize(v[1] - v[0]);
    f.e_v = glm::cross(n, f.e_u);
    for (const DVec3& p : v)
        detail.face.vertices.push_back(to_frame(f, p));
    if (area(detail.face) < 0.0)
        std::reverse(detail.face.vertices.begin(), detail.face.vertices.end());
    const double level = light.at_infinity ? light_h : light_h / size;
    if (!(level > kOnLine)) {
        detail.faces_light = false;
        detail.shadowed.push_back(detail.face);
        return detail;
    }
    const double tolerance = kOnLine * size;
    detail.lit.push_back(detail.face);
    std::vector<ConvexPolygon> next;
    const LightView view = light_view(v, light);
    for (const Occluder& o : occluders) {
        if ((o.shape == shape && o.primitive == primitive) || !may_overlap(view, o.view, light))
            continue;
        const std::vector<HalfPlane> edges = shadow_edges(o, f, light, light_h, size);
        if (edges.empty())
            continue;
        // The shadow meets the face at all? (Its part inside every edge line.)
        ConvexPolygon probe = detail.face;
        for (const HalfPlane& h : edges) {
            probe = split(probe, h, tolerance).inside;
            if (probe.vertices.empty())
                break;
        }
        if (probe.vertices.empty() || !(area(probe) > 0.0))
            continue;
        ++clipped_pairs;
        next.clear();
        // Only pieces whose bounding rectangle meets the shadow's (within the face) can be cut.
        DVec2 lo = probe.vertices.front(), hi = lo;
        for (const DVec2& p : probe.vertices) {
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
        lo -= DVec2(tolerance);
        hi += DVec2(tolerance);
        for (ConvexPolygon& piece : detail.lit) {
            DVec2 piece_lo = piece.vertices.front(), piece_hi = piece_lo;
            for (const DVec2& p : piece.vertices) {
                piece_lo = glm::min(piece_lo, p);
                piece_hi = glm::max(piece_hi, p);
            }
            const bool apart =
                piece_hi.x < lo.x || piece_lo.x > hi.x || piece_hi.y < lo.y || piece_lo.y > hi.y;
            if (apart) {
                next.push_back(std::move(piece));
                continue;
            }
            ConvexPolygon inside = piece;
            for (const HalfPlane& h : edges) {
                PolygonSplit s = split(inside, h, tolerance);
                if (!s.outside.vertices.empty())
                    next.push_back(std::move(s.outside));
                inside = std::move(s.inside);
                if (inside.vertices.empty())
                    break;
            }
            if (!inside.vertices.empty())
                detail.shadowed.push_back(std::move(inside));
        }
        detail.lit.swap(next);
    }
    return detail;
}

}  // namespace

DVec2 to_frame(const FaceFrame& frame, const DVec3& p) {
    const DVec3 d = p - frame.origin;
    return {glm::dot(d, frame.e_u), glm::dot(d, frame.e_v)};
}

ShadowPolygons build_shadow_polygons(const std::vector<Shape>& shapes, const LightCentre& light) {
    std::vector<std::vector<std::array<DVec3, 3>>> triangles;
    const std::vector<Occluder> occluders = collect_occluders(shapes, light, triangles);
    ShadowPolygons out;
    out.faces.resize(shapes.size());
    struct Job {
        uint32_t shape, primitive;
    };
    std::vector<Job> jobs;
    for (size_t s = 0; s < triangles.size(); ++s) {
        out.faces[s].resize(triangles[s].size());
        for (size_t i = 0; i < triangles[s].size(); ++i)
            jobs.push_back({static_cast<uint32_t>(s), static_cast<uint32_t>(i)});
    }
    std::vector<size_t> pairs(jobs.size(), 0);
    tbb::parallel_for(size_t(0), jobs.size(), [&](size_t j) {
        const Job& job = jobs[j];
        out.faces[job.shape][job.primitive] =
            clip_face(triangles[job.shape][job.primitive], job.shape, job.primitive, occluders,
                      light, pairs[j]);
    });
    for (size_t p : pairs)
        out.clipped_pairs += p;
    return out;
}

}  // namespace kasumi
