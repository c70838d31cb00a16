#include "surface/shadows/shadow_map.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace kasumi {

namespace {

/// A spot light's cone up to this half-angle fits one perspective map; wider cones (whose
/// single map would spread texels thinly toward its edges) take a cube.
constexpr float kMaxSpotMapHalfAngleDeg = 60.0f;

/// The six 90° faces around `center`: face k looks along ±axis (k = 2·axis + (negative)).
std::vector<DepthView> cube_faces(const Vec3& center, int resolution) {
    std::vector<DepthView> faces;
    for (int k = 0; k < 6; ++k) {
        const int axis = k / 2;
        const float sign = (k % 2) ? -1.0f : 1.0f;
        DepthView v;
        v.origin = center;
        v.forward = Vec3(0.0f);
        v.forward[axis] = sign;
        const int a = (axis + 1) % 3, b = (axis + 2) % 3;
        v.right = Vec3(0.0f);
        v.right[a] = 1.0f;
        v.up = Vec3(0.0f);
        v.up[b] = 1.0f;
        v.half_extent = Vec2(1.0f);
        v.clamp_edges = true;
        v.resolution = resolution;
        faces.push_back(std::move(v));
    }
    return faces;
}

int cube_face(const Vec3& d) {
    const Vec3 a = glm::abs(d);
    const int axis = (a.x >= a.y && a.x >= a.z) ? 0 : (a.y >= a.z ? 1 : 2);
    return 2 * axis + (d[axis] < 0.0f ? 1 : 0);
}

/// Orthographic view along `direction` framing every corner of `bounds`, with its near plane
/// just before the nearest corner.
DepthView fitted_orthographic(const Vec3& direction, const Bounds3& bounds, int resolution) {
    const Frame frame(direction);
    DepthView v;
    v.orthographic = true;
    v.forward = direction;
    v.right = frame.tangent;
    v.up = frame.bitangent;
    Vec3 lo(kInfinity), hi(-kInfinity);
    for (int c = 0; c < 8; ++c) {
        const Vec3 corner((c & 1) ? bounds.max.x : bounds.min.x,
                          (c & 2) ? bounds.max.y : bounds.min.y,
                          (c & 4) ? bounds.max.z : bounds.min.z);
        const Vec3 local = frame.to_local(corner);
        lo = glm::min(lo, local);
        hi = glm::max(hi, local);
    }
    // Pad by a part in 1e4 (and 1 mm) so points on the bounds fall inside the first and last
    // texels, and the near plane lies strictly before every surface.
    const Vec3 pad = 1e-4f * (hi - lo) + Vec3(1e-3f);
    lo -= pad;
    hi += pad;
    const Vec3 center_local = 0.5f * (lo + hi);
    v.origin = frame.to_world(Vec3(center_local.x, center_local.y, lo.z));
    v.half_extent = 0.5f * Vec2(hi.x - lo.x, hi.y - lo.y);
    v.resolution = resolution;
    return v;
}

std::string format_number(float x) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", static_cast<double>(x));
    return text;
}

float radical_inverse_base2(uint32_t bits) {
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    return static_cast<float>(bits) * 0x1p-32f;
}

}  // namespace

void render_depth(DepthView& view, const SurfaceScene& scene) {
    const int n = view.resolution;
    view.depth.assign(static_cast<size_t>(n) * n, kInfinity);
    tbb::parallel_for(tbb::blocked_range<int>(0, n), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y < rows.end(); ++y) {
            const float t = ((static_cast<float>(y) + 0.5f) / n * 2.0f - 1.0f) * view.half_extent.y;
            for (int x = 0; x < n; ++x) {
                const float s =
                    ((static_cast<float>(x) + 0.5f) / n * 2.0f - 1.0f) * view.half_extent.x;
                Ray ray;
                if (view.orthographic) {
                    ray.origin = view.origin + s * view.right + t * view.up;
                    ray.direction = view.forward;
                } else {
                    ray.origin = view.origin;
                    ray.direction = glm::normalize(view.forward + s * view.right + t * view.up);
                }
                if (const auto hit = scene.intersect(ray))
                    view.depth[static_cast<size_t>(y) * n + x] = hit->t;
            }
        }
    });
}

ViewProjection project(const DepthView& view, const Vec3& p) {
    ViewProjection out;
    const Vec3 d = p - view.origin;
    const Vec3 local(glm::dot(d, view.right), glm::dot(d, view.up), glm::dot(d, view.forward));
    const float n = static_cast<float>(view.resolution);
    Vec2 image;  // in [-1, 1] across the view
    if (view.orthographic) {
        image = Vec2(local.x, local.y) / view.half_extent;
        out.depth = local.z;
        out.texel_size = 2.0f * std::max(view.half_extent.x, view.half_extent.y) / n;
        out.inside = true;
    } else {
        if (!(local.z > 0.0f))
            return out;
        image = Vec2(local.x, local.y) / (local.z * view.half_extent);
        out.depth = glm::length(d);
        // A texel subtends 2 tan(half) / n of the image plane at unit distance along forward;
        // across its ray at radial distance r it is that times r (up to the obliquity of
        // off-axis texels, ≤ √3 on a cube face).
        out.texel_size = 2.0f * std::max(view.half_extent.x, view.half_extent.y) / n * local.z;
        out.inside = true;
    }
    out.texel = (image + 1.0f) * 0.5f * n - 0.5f;
    return out;
}

float shadow_bias(const ShadowMapSettings& settings, float texel_size, float tan_theta) {
    return settings.bias + texel_size * (0.5f + settings.slope_bias * std::min(tan_theta, 8.0f) *
                                                    static_cast<float>(1 + settings.pcf_radius));
}

float filtered_visibility(const DepthView& view, const ShadowMapSettings& settings, const Vec3& p,
                          const Vec3& n, const Vec3& to_light) {
    const ViewProjection proj = project(view, p);
    if (!proj.inside)
        return 1.0f;
    const float cos_theta = std::clamp(std::abs(glm::dot(n, to_light)), 1e-6f, 1.0f);
    const float tan_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta)) / cos_theta;
    const float compare = proj.depth - shadow_bias(settings, proj.texel_size, tan_theta);
    const int res = view.resolution;
    const int cx = static_cast<int>(std::floor(proj.texel.x + 0.5f));
    const int cy = static_cast<int>(std::floor(proj.texel.y + 0.5f));
    const int r = settings.pcf_radius;
    int lit = 0, taps = 0;
    for (int dy = -r; dy <= r; ++dy) {
        for (int dx = -r; dx <= r; ++dx) {
            int x = cx + dx, y = cy + dy;
            ++taps;
            if (x < 0 || y < 0 || x >= res || y >= res) {
                if (!view.clamp_edges) {
                    ++lit;
                    continue;
                }
                x = std::clamp(x, 0, res - 1);
                y = std::clamp(y, 0, res - 1);
            }
            if (compare <= view.depth[static_cast<size_t>(y) * res + x])
                ++lit;
        }
    }
    return static_cast<float>(lit) / static_cast<float>(taps);
}

std::vector<Vec3> shadow_map_centers(const Light& light, int count) {
    std::vector<Vec3> centers;
    if (const auto* polygon = std::get_if<PolygonLight>(&light.emitter)) {
        // Any receiver in front works: the polygon's sampler is uniform in area whatever p is.
        const Vec3 p = polygon->vertices[0] + polygon->normal;
        for (int k = 0; k < count; ++k) {
            const Vec2 u((static_cast<float>(k) + 0.5f) / count,
                         radical_inverse_base2(static_cast<uint32_t>(k)));
            centers.push_back(sample_incident(*polygon, p, u).light_position);
        }
    } else if (const auto* sphere = std::get_if<SphereLight>(&light.emitter)) {
        // Fibonacci lattice: z uniform in (−1, 1), longitude stepped by the golden angle.
        const float golden = kPi * (3.0f - std::sqrt(5.0f));
        for (int k = 0; k < count; ++k) {
            const float z = 1.0f - (2.0f * static_cast<float>(k) + 1.0f) / count;
            const float rho = safe_sqrt(1.0f - z * z);
            const float phi = golden * static_cast<float>(k);
            centers.push_back(sphere->center +
                              sphere->radius * Vec3(rho * std::cos(phi), rho * std::sin(phi), z));
        }
    } else if (const auto* line = std::get_if<LineLight>(&light.emitter)) {
        for (int k = 0; k < count; ++k) {
            const float s = (static_cast<float>(k) + 0.5f) / count;
            centers.push_back(line->from + s * (line->to - line->from));
        }
    }
    return centers;
}

LightShadowMaps::LightShadowMaps(const Light& light, const SurfaceScene& scene)
    : m_settings(light.shadow_map) {
    const int resolution = shadow_map_resolution(light);
    if (const auto* directional = std::get_if<DirectionalLight>(&light.emitter)) {
        ShadowProjector p;
        p.directional = true;
        p.views.push_back(fitted_orthographic(directional->direction, scene.bounds(), resolution));
        m_projectors.push_back(std::move(p));
    } else if (const auto* spot = std::get_if<SpotLight>(&light.emitter);
               spot != nullptr && spot->cos_cone >= std::cos(radians(kMaxSpotMapHalfAngleDeg))) {
        ShadowProjector p;
        p.center = spot->position;
        DepthView v;
        const Frame frame(spot->direction);
        v.origin = spot->position;
        v.forward = spot->direction;
        v.right = frame.tangent;
        v.up = frame.bitangent;
        const float tan_cone = safe_sqrt(1.0f - spot->cos_cone * spot->cos_cone) / spot->cos_cone;
        v.half_extent = Vec2(tan_cone);
        v.resolution = resolution;
        p.views.push_back(std::move(v));
        m_projectors.push_back(std::move(p));
    } else if (is_delta(light)) {
        // Point, wide spot and goniometric lights: one cube around the light's position (the
        // incident light at any point names it).
        ShadowProjector p;
        p.center = incident_light(light, Vec3(0.0f)).light_position;
        p.views = cube_faces(p.center, resolution);
        m_projectors.push_back(std::move(p));
    } else {
        for (const Vec3& center : shadow_map_centers(light, light.shadow_map.views)) {
            ShadowProjector p;
            p.center = center;
            p.views = cube_faces(center, resolution);
            m_projectors.push_back(std::move(p));
        }
    }
    for (ShadowProjector& p : m_projectors)
        for (DepthView& v : p.views)
            render_depth(v, scene);
}

float LightShadowMaps::visibility(const Vec3& p, const Vec3& n, const Vec3& light_point) const {
    const ShadowProjector* projector = &m_projectors.front();
    if (m_projectors.size() > 1) {
        float best = kInfinity;
        for (const ShadowProjector& candidate : m_projectors) {
            const Vec3 d = candidate.center - light_point;
            const float d2 = glm::dot(d, d);
            if (d2 < best) {
                best = d2;
                projector = &candidate;
            }
        }
    }
    if (projector->directional) {
        const DepthView& view = projector->views.front();
        return filtered_visibility(view, m_settings, p, n, -view.forward);
    }
    const Vec3 d = p - projector->center;
    const float distance = glm::length(d);
    if (!(distance > 0.0f))
        return 1.0f;
    const DepthView& view =
        projector->views.size() == 6 ? projector->views[cube_face(d)] : projector->views.front();
    return filtered_visibility(view, m_settings, p, n, -d / distance);
}

size_t LightShadowMaps::texels() const {
    size_t total = 0;
    for (const ShadowProjector& p : m_projectors)
        for (const DepthView& v : p.views)
            total += v.depth.size();
    return total;
}

std::string describe_shadow_maps(const Light& light) {
    const std::string res = std::to_string(shadow_map_resolution(light));
    const ShadowMapSettings& m = light.shadow_map;
    std::string layout;
    if (std::holds_alternative<DirectionalLight>(light.emitter)) {
        layout = "orthographic " + res + "² fitted to the scene bounds";
    } else if (const auto* spot = std::get_if<SpotLight>(&light.emitter);
               spot != nullptr && spot->cos_cone >= std::cos(radians(kMaxSpotMapHalfAngleDeg))) {
        layout = "perspective " + res + "² over the cone";
    } else if (is_delta(light)) {
        layout = "cube 6 × " + res + "²";
    } else {
        layout = std::to_string(m.views) + " cubes 6 × " + res +
                 "² from points on the light, each sample tested in the nearest";
    }
    const int taps = 2 * m.pcf_radius + 1;
    return layout + ", PCF " + std::to_string(taps) + "×" + std::to_string(taps) + ", slope_bias " +
           format_number(m.slope_bias) + " texels" +
           (m.bias > 0.0f ? ", bias " + format_number(m.bias) + " m" : "");
}

ShadowMapSet::ShadowMapSet(const std::vector<Light>& lights, const SurfaceScene& scene) {
    for (const Light& light : lights) {
        m_maps.push_back(light.shadows == ShadowMode::Map
                             ? std::make_unique<LightShadowMaps>(light, scene)
                             : nullptr);
    }
}

bool ShadowMapSet::empty() const {
    return std::none_of(m_maps.begin(), m_maps.end(), [](const auto& m) { return m != nullptr; });
}

}  // namespace kasumi
