#include "surface/scanline/scanline_surface.h"

#include "surface/shadows/sphere_shadow_rays.h"

#include <cmath>
#include <variant>

namespace kasumi {

ScanlineSurface::ScanlineSurface(const std::vector<Shape>& shapes, ScanlineImage visibility,
                                 const ScanlineCamera& camera, const SurfaceScene& scene)
    : m_visibility(std::move(visibility)),
      m_camera(camera),
      m_scene(&scene),
      m_spheres(sphere_scene(shapes)) {
    for (uint32_t s = 0; s < shapes.size(); ++s)
        if (std::holds_alternative<SphereShape>(shapes[s].geometry))
            m_sphere_shape.push_back(s);
}

ScanlineSurface::~ScanlineSurface() = default;

std::optional<ScanlineSurface::SpanPlane> ScanlineSurface::span_plane(uint32_t shape,
                                                                      uint32_t primitive,
                                                                      int y) const {
    SurfaceHit on;
    on.shape = shape;
    on.primitive = primitive;
    const std::optional<HitTriangle> triangle = m_scene->triangle(on);
    if (!triangle)
        return std::nullopt;
    const ScanlineCamera& c = m_camera;
    const DVec3 eye(c.eye), forward(c.forward), right(c.right), up(c.up);
    const DVec3 v0(triangle->positions[0]);
    const DVec3 e1 = DVec3(triangle->positions[1]) - v0, e2 = DVec3(triangle->positions[2]) - v0;
    const DVec3 s = eye - v0;
    const DVec3 q = glm::cross(s, e1);
    // Along scanline y the direction d(X) = d0 + X d1 is linear in X (ScanlineCamera), and so
    // are det(X), det·u and det·v; t = (q·e2)/det (per unit of d).
    const double half_height = c.half_width * c.height / c.width;
    SpanPlane plane;
    plane.shape = shape;
    plane.primitive = primitive;
    plane.y = y;
    plane.d0 =
        forward - c.half_width * right + (1.0 - 2.0 * (y + 0.5) / c.height) * half_height * up;
    plane.d1 = (2.0 * c.half_width / c.width) * right;
    const DVec3 minus_n = -glm::cross(e1, e2), u_axis = glm::cross(e2, s);
    plane.det = {glm::dot(minus_n, plane.d0), glm::dot(minus_n, plane.d1)};
    plane.det_u = {glm::dot(u_axis, plane.d0), glm::dot(u_axis, plane.d1)};
    plane.det_v = {glm::dot(q, plane.d0), glm::dot(q, plane.d1)};
    plane.det_t = glm::dot(q, e2);
    return plane;
}

std::optional<SurfaceHit> ScanlineSurface::hit_at(const SpanPlane& plane, int x,
                                                  const Ray& ray) const {
    const double X = x + 0.5;
    const double det = plane.det.x + X * plane.det.y;
    if (!(det != 0.0))
        return std::nullopt;
    const double t = plane.det_t / det * glm::length(plane.d0 + X * plane.d1);  // metres
    if (!(t > 0.0) || !std::isfinite(t))
        return std::nullopt;
    return m_scene->hit_on_triangle(ray, plane.shape, plane.primitive, static_cast<float>(t),
                                    static_cast<float>((plane.det_u.x + X * plane.det_u.y) / det),
                                    static_cast<float>((plane.det_v.x + X * plane.det_v.y) / det));
}

void ScanlineSurface::first_hits(int y, const int* x, const Ray* rays, size_t count,
                                 std::optional<SurfaceHit>* hits) const {
    // A span's plane equations are set up once and evaluated at each of its pixels.
    std::optional<SpanPlane> plane;
    for (size_t i = 0; i < count; ++i) {
        hits[i] = std::nullopt;
        const size_t pixel = size_t(y) * m_visibility.width + x[i];
        if (m_visibility.shape[pixel] >= 0) {
            const auto shape = static_cast<uint32_t>(m_visibility.shape[pixel]);
            const auto primitive = static_cast<uint32_t>(m_visibility.primitive[pixel]);
            if (!plane || plane->shape != shape || plane->primitive != primitive || plane->y != y)
                plane = span_plane(shape, primitive, y);
            if (plane)
                hits[i] = hit_at(*plane, x[i], rays[i]);
        }
        if (m_spheres == nullptr)
            continue;
        // Depth resolution against the spheres: a sphere hit short of the face is in front.
        Ray to_face = rays[i];
        if (hits[i])
            to_face.t_max = std::min(to_face.t_max, hits[i]->t);
        if (auto sphere = m_spheres->intersect(to_face)) {
            sphere->shape = m_sphere_shape[sphere->shape];
            hits[i] = sphere;
        }
    }
}

}  // namespace kasumi
