#include "gi/gi_emitters.h"

#include "gi/patch_faces.h"

#include <algorithm>

namespace kasumi {

EmissiveTriangles::EmissiveTriangles(const SceneDesc& scene)
    : m_sampled_shape(scene.shapes.size(), false) {
    std::vector<float> weights;
    for (uint32_t s = 0; s < scene.shapes.size(); ++s) {
        const Rgb radiance = emission(scene.materials[scene.shapes[s].material]);
        if (!(luminance(radiance) > 0.0f))
            continue;
        for (const ShapeFace& face : shape_faces(scene.shapes[s], s)) {
            for (int k = 1; k + 1 < face.vertex_count; ++k) {
                Triangle t;
                t.p0 = face.vertices[0];
                t.e1 = face.vertices[k] - t.p0;
                t.e2 = face.vertices[k + 1] - t.p0;
                t.normal = face.normal;
                t.radiance = radiance;
                const float area = 0.5f * glm::length(glm::cross(t.e1, t.e2));
                if (!(area > 0.0f))
                    continue;
                m_triangles.push_back(t);
                weights.push_back(luminance(radiance) * area);
                m_sampled_shape[s] = true;
            }
        }
    }
    double total = 0.0;
    for (const float w : weights) {
        total += w;
        m_cdf.push_back(static_cast<float>(total));
    }
    m_total = static_cast<float>(total);
    for (float& c : m_cdf)
        c /= m_total;
    if (!m_cdf.empty())
        m_cdf.back() = 1.0f;
}

std::optional<EmitterSample> EmissiveTriangles::sample(float u_pick, Vec2 u) const {
    if (m_triangles.empty())
        return std::nullopt;
    const size_t i = std::min<size_t>(
        static_cast<size_t>(std::upper_bound(m_cdf.begin(), m_cdf.end(), u_pick) - m_cdf.begin()),
        m_triangles.size() - 1);
    const Triangle& t = m_triangles[i];
    // Uniform in the triangle: fold the unit square onto the lower-left half.
    float a = u.x, b = u.y;
    if (a + b > 1.0f) {
        a = 1.0f - a;
        b = 1.0f - b;
    }
    EmitterSample s;
    s.position = t.p0 + a * t.e1 + b * t.e2;
    s.normal = t.normal;
    s.radiance = t.radiance;
    s.pdf_area = pdf_area(t.radiance);
    return s;
}

float EmissiveTriangles::pdf_area(const Rgb& radiance) const {
    return m_total > 0.0f ? luminance(radiance) / m_total : 0.0f;
}

bool EmissiveTriangles::is_sampled(uint32_t shape) const {
    return shape < m_sampled_shape.size() && m_sampled_shape[shape];
}

}  // namespace kasumi
