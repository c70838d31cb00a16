#include "surface/shadows/shadow_projection.h"

#include "surface/shadows/welded_mesh.h"

#include <algorithm>

namespace kasumi {

namespace {

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

}  // namespace

DVec2 to_frame(const FaceFrame& frame, const DVec3& p) {
    const DVec3 d = p - frame.origin;
    return {glm::dot(d, frame.e_u), glm::dot(d, frame.e_v)};
}

Receiver make_receiver(const std::array<DVec3, 3>& v, const LightCentre& light) {
    Receiver r;
    DVec3 n = glm::cross(v[1] - v[0], v[2] - v[0]);
    const double twice_area = glm::length(n);
    r.size =
        std::max({glm::length(v[1] - v[0]), glm::length(v[2] - v[1]), glm::length(v[0] - v[2])});
    if (!(twice_area > 0.0)) {
        r.degenerate = true;
        r.faces_light = false;
        return r;
    }
    n /= twice_area;
    r.light_height = light_height(light, v[0], n);
    if (r.light_height < 0.0) {
        n = -n;
        r.light_height = -r.light_height;
    }
    FaceFrame& f = r.frame;
    f.origin = v[0];
    f.normal = n;
    f.e_u = glm::normalize(v[1] - v[0]);
    f.e_v = glm::cross(n, f.e_u);
    const double level = light.at_infinity ? r.light_height : r.light_height / r.size;
    r.faces_light = level > kOnLine;
    return r;
}

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

std::vector<PolygonOccluder> collect_occluders(
    const std::vector<Shape>& shapes, const LightCentre& light,
    std::vector<std::vector<std::array<DVec3, 3>>>& faces) {
    std::vector<PolygonOccluder> occluders;
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

std::vector<HalfPlane> shadow_on_plane(const PolygonOccluder& occluder, const Receiver& receiver,
                                       const LightCentre& light) {
    const FaceFrame& frame = receiver.frame;
    const double light_h = receiver.light_height, size = receiver.size;
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

}  // namespace kasumi
