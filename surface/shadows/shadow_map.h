#pragma once
/// Shadow maps (Williams 1978, "Casting curved shadows on curved surfaces"): a first pass
/// renders the depth of the scene as seen from the light; at shading time a point is lit when
/// it is no farther from the light than the depth stored where it projects, less a bias.
/// Depth is rendered by casting one Embree ray through each texel centre (no rasteriser), so a
/// texel holds the exact depth along its centre ray. Percentage-closer filtering (Reeves,
/// Salesin & Cook 1987) averages the comparisons of (2r + 1)² texels. Area lights use several
/// maps from points on the light (as Heckbert & Herf 1997 average hard shadows from light
/// samples): each sampled point on the light is tested in the map of the nearest such point.
/// Built once per render; read-only and thread-safe afterwards.
#include "core/math.h"
#include "lights/light.h"
#include "surface/surface_scene.h"

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace kasumi {

/// One depth image seen from a light. Perspective views store the distance from `origin` along
/// each texel's centre ray (radial depth, m); orthographic views the distance along `forward`
/// from the plane through `origin`. kInfinity where the texel's ray hits nothing.
struct DepthView {
    bool orthographic = false;
    Vec3 origin{0.0f};
    Vec3 right{1.0f, 0.0f, 0.0f};
    Vec3 up{0.0f, 1.0f, 0.0f};
    Vec3 forward{0.0f, 0.0f, 1.0f};  ///< right, up, forward: unit and mutually orthogonal
    /// Half the image's extent: metres (orthographic) or the tangent of the half field of view
    /// (perspective), along right (x) and up (y).
    Vec2 half_extent{1.0f};
    bool clamp_edges = false;  ///< filter taps beyond the edge read the edge (cube faces)
    int resolution = 0;
    std::vector<float> depth;  ///< resolution² texels, row y = 0 at -up
};

/// Fills view.depth by casting a ray through each texel centre of an already-framed view.
/// Parallel over rows.
void render_depth(DepthView& view, const SurfaceScene& scene);

/// Where p falls in a view: continuous texel coordinates (texel centres at integers), the
/// depth of p in the view's measure, and the world size of one texel at p (m).
struct ViewProjection {
    Vec2 texel{0.0f};
    float depth = 0.0f;
    float texel_size = 0.0f;
    bool inside = false;  ///< in front of a perspective view's eye
};
ViewProjection project(const DepthView& view, const Vec3& p);

/// Bias, filter and resolution of a map lookup (lights/light.h ShadowMapSettings).
/// The comparison subtracts from p's depth
///   bias + texel_size(p) · (0.5 + slope_bias · min(tan θ, 8) · (1 + pcf_radius))
/// (θ between the receiver's normal and the direction to the light): half a texel for the
/// depth the centre ray sees on a curved receiver, and the depth change across the filter
/// footprint on a receiver tilted by θ (slope-scaled bias; tan θ is capped where cos θ makes
/// the light negligible anyway).
float shadow_bias(const ShadowMapSettings& settings, float texel_size, float tan_theta);

/// The fraction of the PCF taps around p that see p lit (1 outside a non-clamped view).
/// n: the receiver's unit geometric normal; to_light: unit direction from p to the light.
float filtered_visibility(const DepthView& view, const ShadowMapSettings& settings, const Vec3& p,
                          const Vec3& n, const Vec3& to_light);

/// A centre of projection and the maps rendered from it: one orthographic view (directional
/// light), one perspective view (spot light with a cone up to 60°) or six cube faces.
struct ShadowProjector {
    Vec3 center{0.0f};
    bool directional = false;
    std::vector<DepthView> views;  ///< 1, or 6 cube faces (+x, −x, +y, −y, +z, −z)
};

/// Every map of one light.
class LightShadowMaps {
  public:
    /// Renders the maps of `light` (whose shadows are ShadowMode::Map) against `scene`.
    LightShadowMaps(const Light& light, const SurfaceScene& scene);

    /// Visibility in [0, 1] of the light point `light_point` (the light's position, or a
    /// sampled point on an extended light; ignored for directional lights) from the surface
    /// point p of unit geometric normal n, read from the maps of the nearest projector.
    float visibility(const Vec3& p, const Vec3& n, const Vec3& light_point) const;

    const std::vector<ShadowProjector>& projectors() const { return m_projectors; }
    size_t texels() const;

  private:
    ShadowMapSettings m_settings;
    std::vector<ShadowProjector> m_projectors;
};

/// The points on an extended light the maps are rendered from: `count` points spread over the
/// light (polygon: Hammersley points mapped uniformly in area; sphere: a Fibonacci lattice on
/// its surface; line: the midpoints of `count` equal pieces). Empty for delta lights.
std::vector<Vec3> shadow_map_centers(const Light& light, int count);

/// How the maps of `light` are laid out, for the plan: projection, resolution, views, filter.
std::string describe_shadow_maps(const Light& light);

/// Maps for every light of the scene with map shadows (others: null); built once per render.
class ShadowMapSet {
  public:
    ShadowMapSet(const std::vector<Light>& lights, const SurfaceScene& scene);
    /// The maps of light `index`, or null when it does not use map shadows.
    const LightShadowMaps* maps(size_t index) const { return m_maps[index].get(); }
    bool empty() const;

  private:
    std::vector<std::unique_ptr<LightShadowMaps>> m_maps;
};

}  // namespace kasumi
