#include "surface/sphere_light_occluders.h"

#include "lights/cap_region.h"
#include "lights/polygon_light.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace kasumi {

namespace {

/// Silhouette caps of one occluder: a sphere has 1, a box 4 or 6, a quad 4.
constexpr int kMaxCapsPerOccluder = 6;

/// The hemisphere of directions on the side of the plane through p, u and v that holds
/// `inside` (a point of the convex occluder off that plane). False when p is on the line uv.
bool edge_hemisphere(const DVec3& p, const DVec3& u, const DVec3& v, const DVec3& inside,
                     SphericalCap& cap) {
    DVec3 axis = glm::cross(u - p, v - p);
    const double length = glm::length(axis);
    const double scale = glm::length(u - p) * glm::length(v - p);
    if (!(length > 1e-12 * scale))
        return false;
    axis /= length;
    if (glm::dot(axis, inside - p) < 0.0)
        axis = -axis;
    cap = SphericalCap{axis, 0.0, 1.0};
    return true;
}

}  // namespace

SphereLightOccluders::SphereLightOccluders(const std::vector<Shape>& shapes) {
    m_occluders.reserve(shapes.size());
    for (const Shape& shape : shapes) {
        Occluder o;
        DVec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
        const auto extend = [&](const Vec3& v) {
            lo = glm::min(lo, DVec3(v));
            hi = glm::max(hi, DVec3(v));
        };
        if (const auto* s = std::get_if<SphereShape>(&shape.geometry)) {
            o.kind = Kind::Sphere;
            o.center = DVec3(s->center);
            o.radius = s->radius;
            m_occluders.push_back(o);
            continue;
        }
        if (const auto* b = std::get_if<BoxShape>(&shape.geometry)) {
            o.kind = Kind::Box;
            extend(b->min);
            extend(b->max);
        } else if (const auto* q = std::get_if<QuadShape>(&shape.geometry)) {
            o.kind = Kind::Quad;
            for (int k = 0; k < 4; ++k) {
                o.quad[k] = DVec3(q->vertices[k]);
                extend(q->vertices[k]);
            }
        } else if (const auto* m = std::get_if<MeshShape>(&shape.geometry)) {
            for (const Vec3& v : m->mesh.positions)
                extend(v);
            if (m->mesh.positions.empty())
                lo = hi = DVec3(0.0);
        }
        o.lo = lo;
        o.hi = hi;
        o.center = 0.5 * (lo + hi);
        o.radius = 0.5 * glm::length(hi - lo);
        if (o.kind == Kind::Quad) {
            // The vertex centroid lies inside a convex quad (the box centre may not): the
            // edge planes are oriented toward it.
            o.center = 0.25 * (o.quad[0] + o.quad[1] + o.quad[2] + o.quad[3]);
            o.radius = 0.0;
            for (const DVec3& v : o.quad)
                o.radius = std::max(o.radius, glm::length(v - o.center));
        }
        m_occluders.push_back(o);
    }
}

std::optional<double> SphereLightOccluders::visible_projected_solid_angle(const SphereLight& light,
                                                                          const Vec3& p_in,
                                                                          const Vec3& n_in,
                                                                          uint32_t receiver) const {
    const DVec3 p(p_in), n(n_in);
    const DVec3 to_light = DVec3(light.center) - p;
    const double d = glm::length(to_light);
    const double radius = light.radius;
    if (!(d > radius))
        return 0.0;
    const DVec3 axis = to_light / d;
    const double sin_sigma = radius / d;
    const double cos_sigma = std::sqrt(std::max(0.0, 1.0 - sin_sigma * sin_sigma));
    const double n_axis = glm::dot(n, axis);
    if (!(n_axis > -sin_sigma))
        return 0.0;  // wholly below the horizon of n
    // The light's cone, and the hemisphere above n when the cone reaches below it (then every
    // region is clipped to it, so the integrand n · ω stays the clamped cosine).
    const SphericalCap base[2] = {SphericalCap{axis, cos_sigma, sin_sigma},
                                  SphericalCap{n, 0.0, 1.0}};
    const size_t base_count = n_axis > sin_sigma ? 1 : 2;
    const double unshadowed = base_count == 1 ? kPiD * sin_sigma * sin_sigma * n_axis
                                              : cap_intersection_projected_solid_angle(base, 2, n);
    if (!std::isfinite(unshadowed))
        return std::nullopt;
    // Every direction of the cone meets the light between these distances (the nearest point,
    // on the axis, and the rim, where the cone grazes the sphere).
    const double nearest = d - radius;
    const double farthest = std::sqrt((d - radius) * (d + radius));

    return visible_part(base, base_count, unshadowed, p, n, axis, cos_sigma, sin_sigma, nearest,
                        farthest, nullptr, 0.0, receiver);
}

std::optional<double> SphereLightOccluders::visible_projected_solid_angle(const PolygonLight& light,
                                                                          const Vec3& p_in,
                                                                          const Vec3& n_in,
                                                                          uint32_t receiver) const {
    const DVec3 p(p_in), n(n_in);
    const size_t count = light.vertices.size();
    if (count < 3 || count > kMaxPolygonVertices)
        return std::nullopt;
    const DVec3 normal(light.normal);
    const DVec3 v0(light.vertices[0]);
    const double height = glm::dot(normal, p - v0);  // > 0 in front
    if (height == 0.0 || (height < 0.0 && !light.two_sided))
        return 0.0;  // in the light's plane, or behind a one-sided light
    // The polygon seen from p: the intersection of the hemispheres bounded by the great circles
    // through p and its edges, each oriented toward the vertex centroid (inside the convex
    // polygon, off every edge plane since p is off the polygon's plane).
    DVec3 centroid(0.0);
    for (const Vec3& v : light.vertices)
        centroid += DVec3(v);
    centroid /= static_cast<double>(count);
    SphericalCap base[kMaxPolygonVertices + 1];
    size_t base_count = 0;
    double farthest = 0.0, bound_radius = 0.0;
    bool below = false;
    for (size_t i = 0; i < count; ++i) {
        const DVec3 u(light.vertices[i]), v(light.vertices[(i + 1) % count]);
        if (!edge_hemisphere(p, u, v, centroid, base[base_count++]))
            return std::nullopt;
        farthest = std::max(farthest, glm::length(u - p));
        bound_radius = std::max(bound_radius, glm::length(u - centroid));
        below = below || glm::dot(n, u - p) < 0.0;
    }
    // Clipped to the hemisphere above n when a vertex lies below it.
    if (below)
        base[base_count++] = SphericalCap{n, 0.0, 1.0};
    const double unshadowed = cap_intersection_projected_solid_angle(base, base_count, n);
    if (!std::isfinite(unshadowed))
        return std::nullopt;
    if (!(unshadowed > 0.0))
        return 0.0;
    // A cone around the polygon for culling: the bounding sphere's (centroid, bound_radius).
    const DVec3 to_centroid = centroid - p;
    const double dc = glm::length(to_centroid);
    const DVec3 axis = to_centroid / dc;
    const double sin_sigma = dc > bound_radius ? bound_radius / dc : 1.0;
    const double cos_sigma = std::sqrt(std::max(0.0, 1.0 - sin_sigma * sin_sigma));
    // Occluders are classified by the side of the light's plane they lie on (p's side: in
    // front).
    const DVec3 side = height > 0.0 ? normal : -normal;
    return visible_part(base, base_count, unshadowed, p, n, axis, cos_sigma, sin_sigma,
                        std::abs(height), farthest, &side, glm::dot(side, v0), receiver);
}

std::optional<double> SphereLightOccluders::visible_part(
    const SphericalCap* base, size_t base_count, double unshadowed, const DVec3& p, const DVec3& n,
    const DVec3& axis, double cos_sigma, double sin_sigma, double nearest, double farthest,
    const DVec3* plane, double plane_offset, uint32_t receiver) const {
    // One spare slot: an occluder's caps are built there before it is known to overlap.
    SphericalCap occluder_caps[kMaxOccluders + 1][kMaxCapsPerOccluder];
    int cap_count[kMaxOccluders + 1] = {};
    double single[kMaxOccluders] = {};  ///< measure of (base ∩ occluder k)
    SphericalCap caps[kMaxPolygonVertices + 1 + kMaxOccluders * kMaxCapsPerOccluder];
    int occluders = 0;
    for (size_t k = 0; k < m_occluders.size(); ++k) {
        const Occluder& o = m_occluders[k];
        if (k == receiver && o.kind != Kind::Mesh)
            continue;
        // A face plane with p outside it that every direction of the cone leaves away from
        // (the smallest component of the cone's directions along its normal m is
        // (m·a) cos σ − √(1 − (m·a)²) sin σ) separates the cone from a box or a quad.
        const auto leaves = [&](double m_axis) {
            return m_axis * cos_sigma -
                       std::sqrt(std::max(0.0, 1.0 - m_axis * m_axis)) * sin_sigma >=
                   0.0;
        };
        if (o.kind == Kind::Box) {
            bool separated = false;
            for (int i = 0; i < 3 && !separated; ++i)
                separated =
                    (p[i] > o.hi[i] && leaves(axis[i])) || (p[i] < o.lo[i] && leaves(-axis[i]));
            if (separated)
                continue;
        } else if (o.kind == Kind::Quad) {
            const DVec3 m =
                glm::normalize(glm::cross(o.quad[1] - o.quad[0], o.quad[2] - o.quad[0]));
            const double h = glm::dot(m, p - o.quad[0]);
            if ((h > 0.0 && leaves(glm::dot(m, axis))) || (h < 0.0 && leaves(-glm::dot(m, axis))))
                continue;
        }
        const DVec3 to_center = o.center - p;
        const double dist = glm::length(to_center);
        if (dist > o.radius) {
            // Cone against the bounding sphere's cone: disjoint when the axes are farther
            // apart than the two half-angles, i.e. (σ + β < π) when the cosine of the angle
            // between them is at most cos(σ + β) = cos σ cos β − sin σ sin β.
            const double sin_beta = o.radius / dist;
            const double cos_beta = std::sqrt(std::max(0.0, 1.0 - sin_beta * sin_beta));
            const double cos_apart = glm::dot(axis, to_center) / dist;
            if (cos_apart <= cos_sigma * cos_beta - sin_sigma * sin_beta)
                continue;
            if (plane == nullptr && dist - o.radius >= farthest)
                continue;  // wholly beyond the visible side of the light
        }
        if (o.kind == Kind::Mesh)
            return std::nullopt;
        // In front of the light: nearer than it along every direction of the region. Sphere
        // lights: the occluder's farthest point from p within d − R; polygon lights: the whole
        // occluder on p's side of the light's plane (a ray from p meets the plane once, at the
        // light). Behind: beyond √(d² − R²), or wholly on the far side of the plane.
        bool in_front = false;
        if (plane != nullptr) {
            const double s = glm::dot(*plane, o.center) - plane_offset;
            double extent = o.radius;
            if (o.kind == Kind::Box)
                extent = glm::dot(glm::abs(*plane), 0.5 * (o.hi - o.lo));
            double s_lo = s - extent, s_hi = s + extent;
            if (o.kind == Kind::Quad) {
                s_lo = std::numeric_limits<double>::infinity();
                s_hi = -s_lo;
                for (const DVec3& v : o.quad) {
                    s_lo = std::min(s_lo, glm::dot(*plane, v) - plane_offset);
                    s_hi = std::max(s_hi, glm::dot(*plane, v) - plane_offset);
                }
            }
            if (s_hi <= 0.0)
                continue;
            in_front = s_lo > 0.0;
        }
        // The occluder's nearest and farthest points from p (bounds for quads).
        double s_min = dist - o.radius, s_max = dist + o.radius;
        if (plane != nullptr) {
            s_min = -std::numeric_limits<double>::infinity();
        } else if (o.kind == Kind::Box) {
            const DVec3 nearest_point = glm::clamp(p, o.lo, o.hi);
            s_min = glm::length(nearest_point - p);
            const DVec3 far_corner(p.x < o.center.x ? o.hi.x : o.lo.x,
                                   p.y < o.center.y ? o.hi.y : o.lo.y,
                                   p.z < o.center.z ? o.hi.z : o.lo.z);
            s_max = glm::length(far_corner - p);
        } else if (o.kind == Kind::Quad) {
            s_max = 0.0;
            for (const DVec3& v : o.quad)
                s_max = std::max(s_max, glm::length(v - p));
        }
        if (s_min >= farthest)
            continue;
        SphericalCap* occ = occluder_caps[occluders];
        int& count = cap_count[occluders];
        count = 0;
        if (o.kind == Kind::Sphere) {
            if (!(dist > o.radius))
                return std::nullopt;
            const double sin_beta = o.radius / dist;
            occ[count++] = SphericalCap{
                to_center / dist, std::sqrt(std::max(0.0, 1.0 - sin_beta * sin_beta)), sin_beta};
        } else if (o.kind == Kind::Box) {
            // Face (axis i, side s) faces p when p is beyond its plane; a silhouette edge joins
            // a face that faces p and one that does not.
            bool front[3][2];
            bool any_front = false;
            for (int i = 0; i < 3; ++i) {
                front[i][0] = p[i] < o.lo[i];
                front[i][1] = p[i] > o.hi[i];
                any_front = any_front || front[i][0] || front[i][1];
            }
            if (!any_front)
                return std::nullopt;  // p inside or on the box
            for (int e = 0; e < 3; ++e) {
                const int i = (e + 1) % 3, j = (e + 2) % 3;
                for (int si = 0; si < 2; ++si)
                    for (int sj = 0; sj < 2; ++sj) {
                        if (front[i][si] == front[j][sj])
                            continue;
                        DVec3 u, v;
                        u[i] = v[i] = si ? o.hi[i] : o.lo[i];
                        u[j] = v[j] = sj ? o.hi[j] : o.lo[j];
                        u[e] = o.lo[e];
                        v[e] = o.hi[e];
                        if (count == kMaxCapsPerOccluder ||
                            !edge_hemisphere(p, u, v, o.center, occ[count++]))
                            return std::nullopt;
                    }
            }
        } else {
            const DVec3 normal = glm::cross(o.quad[1] - o.quad[0], o.quad[2] - o.quad[0]);
            const double height = glm::dot(normal, p - o.quad[0]);
            if (std::abs(height) <= 1e-12 * glm::length(normal) * (dist + o.radius))
                continue;  // p in the quad's plane: it subtends no solid angle
            for (int v = 0; v < 4; ++v)
                if (!edge_hemisphere(p, o.quad[v], o.quad[(v + 1) % 4], o.center, occ[count++]))
                    return std::nullopt;
        }
        // The part of the (clipped) cone the occluder covers; none: it hides nothing.
        size_t n_caps = 0;
        for (size_t b = 0; b < base_count; ++b)
            caps[n_caps++] = base[b];
        for (int c = 0; c < count; ++c)
            caps[n_caps++] = occ[c];
        const double covered = cap_intersection_projected_solid_angle(caps, n_caps, n);
        if (!std::isfinite(covered))
            return std::nullopt;
        if (!(covered > 0.0))
            continue;
        if (plane == nullptr)
            in_front = s_max <= nearest;
        if (!in_front || occluders == kMaxOccluders)
            return std::nullopt;
        single[occluders++] = covered;
    }

    // Inclusion-exclusion over the occluders: the measure of (cone ∩ ∪ O_k); the single terms
    // are known, the intersections of two or more are computed here.
    double hidden = 0.0;
    for (int k = 0; k < occluders; ++k)
        hidden += single[k];
    for (unsigned mask = 1; mask < (1u << occluders); ++mask) {
        int members = 0;
        for (int k = 0; k < occluders; ++k)
            members += (mask >> k) & 1u;
        if (members < 2)
            continue;
        size_t n_caps = 0;
        for (size_t b = 0; b < base_count; ++b)
            caps[n_caps++] = base[b];
        for (int k = 0; k < occluders; ++k)
            if (mask & (1u << k))
                for (int c = 0; c < cap_count[k]; ++c)
                    caps[n_caps++] = occluder_caps[k][c];
        const double term = cap_intersection_projected_solid_angle(caps, n_caps, n);
        if (!std::isfinite(term))
            return std::nullopt;
        hidden += (members % 2 == 1) ? term : -term;
    }
    return std::clamp(unshadowed - hidden, 0.0, std::max(unshadowed, 0.0));
}

}  // namespace kasumi
