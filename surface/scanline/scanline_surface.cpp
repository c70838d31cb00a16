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

std::optional<SurfaceHit> ScanlineSurface::face_hit(int x, int y, const Ray& ray) const {
    const size_t pixel = size_t(y) * m_visibility.width + x;
    if (m_visibility.shape[pixel] < 0)
        return std::nullopt;
    SurfaceHit on;
    on.shape = static_cast<uint32_t>(m_visibility.shape[pixel]);
    on.primitive = static_cast<uint32_t>(m_visibility.primitive[pixel]);
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
    const DVec3 d0 =
        forward - c.half_width * right + (1.0 - 2.0 * (y + 0.5) / c.height) * half_height * up;
    const DVec3 d1 = (2.0 * c.half_width / c.width) * right;
    const DVec3 minus_n = -glm::cross(e1, e2), u_axis = glm::cross(e2, s);
    const double det0 = glm::dot(minus_n, d0), det1 = glm::dot(minus_n, d1);
    const double u0 = glm::dot(u_axis, d0), u1 = glm::dot(u_axis, d1);
    const double v0_num = glm::dot(q, d0), v1_num = glm::dot(q, d1);
    const double X = x + 0.5;
    const double det = det0 + X * det1;
    if (!(det != 0.0))
        return std::nullopt;
    const double t_unit_d = glm::dot(q, e2) / det;
    const double t = t_unit_d * glm::length(d0 + X * d1);  // metres along the unit ray
    if (!(t > 0.0) || !std::isfinite(t))
        return std::nullopt;
    return m_scene->hit_on_triangle(ray, on.shape, on.primitive, static_cast<float>(t),
                                    static_cast<float>((u0 + X * u1) / det),
                                    static_cast<float>((v0_num + X * v1_num) / det));
}

void ScanlineSurface::first_hits(int y, const int* x, const Ray* rays, size_t count,
                                 std::optional<SurfaceHit>* hits) const {
    for (size_t i = 0; i < count; ++i) {
        hits[i] = face_hit(x[i], y, rays[i]);
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
