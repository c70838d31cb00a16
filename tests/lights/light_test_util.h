#pragma once
/// Brute-force references for light tests: midpoint quadrature of the illuminance integrals,
/// written from their definitions (not from the closed forms they check), and a pooled
/// chi-square p-value.
#include "core/json_node.h"
#include "lights/light_json.h"
#include "lights/sphere_light.h"
#include "phase/phase_quadrature.h"

#include <functional>
#include <string>
#include <vector>

namespace kasumi::test {

/// Parses one light from JSON text as entry 0 of a scene at `file`.
inline Light parse_light_text(const std::string& text, const std::string& file = "lights.json") {
    static Json doc;  // JsonNode refers into the document
    doc = parse_json_text(text, file);
    return parse_light(JsonNode(doc, file, "/lights/0"), 0);
}

/// Whether the segment from p to target is unoccluded.
using Visibility = std::function<bool(const Vec3& p, const Vec3& target)>;

/// E = ∫_A L cos θ cos θ' V / r² dA over a convex polygon (fan triangles, each mapped from the
/// unit square by x = v0 + u (v1 − v0) + u v (v2 − v1), Jacobian 2 A_tri u), midpoint rule on
/// n × n cells. cos θ at the receiver is clamped at 0 (the horizon); cos θ' is the emission
/// cosine, negative behind the front unless two_sided; V is `visible(p, x)` toward each cell's
/// point x (1 when empty).
inline double polygon_quadrature(const std::vector<Vec3>& vertices, double luminance,
                                 bool two_sided, const Vec3& p, const Vec3& n, int cells,
                                 const Visibility& visible = {}) {
    DVec3 normal(0.0);
    for (size_t i = 0; i < vertices.size(); ++i)
        normal += glm::cross(DVec3(vertices[i]), DVec3(vertices[(i + 1) % vertices.size()]));
    normal = glm::normalize(normal);
    const DVec3 q(p), nd(n);
    double sum = 0.0;
    for (size_t t = 1; t + 1 < vertices.size(); ++t) {
        const DVec3 v0(vertices[0]), v1(vertices[t]), v2(vertices[t + 1]);
        const double area2 = glm::length(glm::cross(v1 - v0, v2 - v0));
        for (int i = 0; i < cells; ++i) {
            const double u = (i + 0.5) / cells;
            for (int j = 0; j < cells; ++j) {
                const double v = (j + 0.5) / cells;
                const DVec3 x = v0 + u * (v1 - v0) + u * v * (v2 - v1);
                const DVec3 d = x - q;
                const double r2 = glm::dot(d, d);
                const double r = std::sqrt(r2);
                const double cos_receiver = std::max(0.0, glm::dot(nd, d) / r);
                double cos_emitter = -glm::dot(normal, d) / r;
                if (two_sided)
                    cos_emitter = std::abs(cos_emitter);
                if (cos_emitter <= 0.0 || cos_receiver <= 0.0)
                    continue;
                if (visible && !visible(p, Vec3(x)))
                    continue;
                sum += cos_receiver * cos_emitter / r2 * area2 * u;
            }
        }
    }
    return luminance * sum / (static_cast<double>(cells) * cells);
}

/// E = ∫ I_l sin α max(0, cos θ) / r² dl along a segment, midpoint rule with `steps` points.
inline double line_quadrature(const Vec3& from, const Vec3& to, double intensity_per_m,
                              const Vec3& p, const Vec3& n, int steps) {
    const DVec3 a(from), b(to), q(p), nd(n);
    const double length = glm::length(b - a);
    const DVec3 t = (b - a) / length;
    double sum = 0.0;
    for (int i = 0; i < steps; ++i) {
        const DVec3 x = a + (i + 0.5) / steps * length * t;
        const DVec3 d = x - q;
        const double r = glm::length(d);
        const double sin_alpha = glm::length(glm::cross(t, d / r));
        sum += sin_alpha * std::max(0.0, glm::dot(nd, d) / r) / (r * r);
    }
    return intensity_per_m * sum * length / steps;
}

/// E = L ∫ max(0, n·ω) dω over the cone a sphere subtends at p, midpoint rule in (cos t, φ)
/// about the axis to the centre (dω = d cos t dφ).
inline double sphere_quadrature(const Vec3& center, double radius, double luminance, const Vec3& p,
                                const Vec3& n, int cells) {
    const DVec3 axis = DVec3(center) - DVec3(p);
    const double d = glm::length(axis);
    const double cos_sigma = std::sqrt(1.0 - (radius / d) * (radius / d));
    const Frame frame(Vec3(axis / d));
    const DVec3 nl(frame.to_local(n));
    double sum = 0.0;
    for (int i = 0; i < cells; ++i) {
        const double c = cos_sigma + (i + 0.5) / cells * (1.0 - cos_sigma);
        const double s = std::sqrt(1.0 - c * c);
        for (int j = 0; j < cells; ++j) {
            const double phi = (j + 0.5) / cells * 2.0 * kPiD;
            const DVec3 w(s * std::cos(phi), s * std::sin(phi), c);
            sum += std::max(0.0, glm::dot(nl, w));
        }
    }
    return luminance * sum * (1.0 - cos_sigma) * 2.0 * kPiD / (static_cast<double>(cells) * cells);
}

/// The shadowed illuminance E = L ∫ max(0, n·ω) V dω over the cone `light` subtends at p, where
/// V is `visible` toward a target far beyond the light along ω (the occluder lies between p and
/// the light); midpoint rule in (cos t, φ) about the axis, independent of the sampler.
inline double sphere_quadrature(const SphereLight& light, const Vec3& p, const Vec3& n,
                                const Visibility& visible, int cells) {
    const DVec3 to_center = DVec3(light.center) - DVec3(p);
    const double d = glm::length(to_center);
    const double sin_sigma = light.radius / d;
    const double one_minus_cos = 1.0 - std::sqrt(1.0 - sin_sigma * sin_sigma);
    const Frame frame(Vec3(to_center / d));
    double sum = 0.0;
    for (int i = 0; i < cells; ++i) {
        const double ct = 1.0 - one_minus_cos * (i + 0.5) / cells;
        const double st = std::sqrt(1.0 - ct * ct);
        for (int j = 0; j < cells; ++j) {
            const double phi = 2.0 * kPiD * (j + 0.5) / cells;
            const Vec3 w = frame.to_world(Vec3(static_cast<float>(st * std::cos(phi)),
                                               static_cast<float>(st * std::sin(phi)),
                                               static_cast<float>(ct)));
            const double c = std::max(0.0f, glm::dot(n, w));
            if (c > 0.0 && visible(p, p + 100.0f * w))
                sum += c;
        }
    }
    return luminance(light.luminance) * sum * 2.0 * kPiD * one_minus_cos / (double(cells) * cells);
}

/// Occluder of the penumbra tests: the half-plane y = 2, x < 0 (its edge along z). A ray from p
/// (below) toward the target (above) is blocked when it crosses y = 2 at x < 0.
inline bool past_edge(const Vec3& p, const Vec3& target) {
    const float t = (2.0f - p.y) / (target.y - p.y);
    return p.x + t * (target.x - p.x) >= 0.0f;
}

/// P-value of Pearson's chi-square for observed vs expected counts; cells expecting fewer than
/// 5 are pooled into one.
inline double chi_square_p_value(const std::vector<double>& observed,
                                 const std::vector<double>& expected) {
    double statistic = 0.0, pooled_o = 0.0, pooled_e = 0.0;
    int cells = 0;
    for (size_t i = 0; i < observed.size(); ++i) {
        if (expected[i] < 5.0) {
            pooled_o += observed[i];
            pooled_e += expected[i];
            continue;
        }
        statistic += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
        ++cells;
    }
    if (pooled_e >= 5.0) {
        statistic += (pooled_o - pooled_e) * (pooled_o - pooled_e) / pooled_e;
        ++cells;
    } else if (pooled_o > pooled_e + 10.0) {
        return 0.0;  // mass where the pdf has almost none
    }
    return upper_incomplete_gamma_q(0.5 * std::max(1, cells - 1), 0.5 * statistic);
}

}  // namespace kasumi::test
