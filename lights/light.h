#pragma once
/// Lights, as a closed set of small value types. Units are photometric (see core/color.h for
/// how Rgb carries photometric quantities): directional lights by illuminance in lux on a
/// surface facing the light, point-like lights by luminous intensity in candela, line lights
/// by candela per metre, area and sphere lights by luminance in cd/m².
#include "core/color.h"
#include "core/math.h"
#include "core/rng.h"
#include "lights/goniometric_light.h"
#include "lights/incident_light.h"
#include "lights/line_light.h"
#include "lights/polygon_light.h"
#include "lights/sphere_light.h"
#include "lights/spot_light.h"

#include <string>
#include <variant>

namespace kasumi {

/// Light from infinitely far away, travelling along `direction` (unit vector).
struct DirectionalLight {
    Vec3 direction{0.0f, -1.0f, 0.0f};
    Rgb illuminance{0.0f};  ///< lux on a surface facing the light
};

/// An isotropic point source: illuminance I cos θ / r² at distance r (inverse-square law).
struct PointLight {
    Vec3 position{0.0f};
    Rgb intensity{0.0f};  ///< candela
};

/// How a light's visibility is decided.
enum class ShadowMode {
    Ray,           ///< shadow rays: one for a delta light, `samples` for an extended one
    None,          ///< the light is never blocked
    Map,           ///< depth maps rendered from the light once per render (surface/shadows/)
    ShadowVolume,  ///< Crow's shadow volumes of the meshes, point-like and directional lights
    ObjectSpace,   ///< lit and shadowed detail polygons per face (Atherton et al. 1978)
    Scanline,      ///< shadowed sub-spans of a scanline pass at the camera's pixel centres
};

/// True when a stage built before the first pixel decides the light's visibility (maps, shadow
/// volumes, detail polygons) rather than a shadow ray per shading point.
bool shadows_by_stage(ShadowMode mode);

/// Settings of a light's shadow maps (docs/lights.md, "Shadow maps").
struct ShadowMapSettings {
    int resolution = 0;       ///< texels along each side of each map; 0: 1024 (area lights 512)
    float bias = 0.0f;        ///< constant depth bias, m; 0: two texels' world size
    float slope_bias = 1.5f;  ///< texels of depth per unit tan θ of the receiver
    int pcf_radius = 1;       ///< percentage-closer filter over (2r + 1)² taps; 0: one tap
    int views = 8;            ///< area lights: maps from this many points on the light
};

struct Light {
    std::string name;
    std::variant<DirectionalLight, PointLight, SpotLight, GoniometricLight, LineLight, PolygonLight,
                 SphereLight>
        emitter;
    ShadowMode shadows = ShadowMode::Ray;
    int samples = 16;  ///< shadow samples per shading point for extended (non-delta) lights
    /// Adaptive shadows: when the first `shadow_probes` samples agree, the rest are skipped
    /// (lights/light_samples.h, ProbeRule; biased). 0: every point takes all `samples`.
    int shadow_probes = 0;
    /// Sphere lights: shadow rays toward this many points on the light's outline decide first
    /// whether a point is entirely lit or in umbra (then no samples are traced); biased, with a
    /// stated bound (lights/light_samples.h, OutlineProbes). 0: off.
    int outline_probes = 0;
    /// Sphere and polygon lights: where the closed form applies, the visible part of the light is
    /// computed exactly against the scene's spheres, boxes and quads instead of sampled
    /// (surface/sphere_light_occluders.h); elsewhere the samples (and probes) as usual.
    bool exact_penumbra = false;
    ShadowMapSettings shadow_map{};  ///< used when shadows == ShadowMode::Map
};

/// Texels along each side of the light's shadow maps: `resolution`, or its default.
int shadow_map_resolution(const Light& light);

/// True for lights that emit from one point or direction (directional, point, spot,
/// goniometric): a single shadow ray decides their visibility.
bool is_delta(const Light& light);

/// The light a delta light delivers at point p. For a point-like light closer than 1e-6 m the
/// irradiance is zero rather than unbounded. Extended lights return zero irradiance: sample them
/// with sample_incident.
IncidentLight incident_light(const Light& light, const Vec3& p);

/// One sample of the light arriving at p, u uniform in [0, 1)²: for a delta light exactly
/// incident_light (u unused); for an extended light a point on it with the normal-incidence
/// irradiance divided by the pdf, so that the mean over samples of irradiance · max(0, n·wi) ·
/// V(p, light_position) is an unbiased estimate of the shadowed illuminance E·V.
IncidentLight sample_incident(const Light& light, const Vec3& p, Vec2 u);

/// The same, drawing u from `rng` only for extended lights, so that scenes with delta lights
/// alone consume the same random numbers as before extended lights existed.
IncidentLight sample_incident(const Light& light, const Vec3& p, Pcg32& rng);

/// The weight that turns Σ_k f_k E_k cos θ_k V_k over one shading point's samples of `light`
/// into its reflected radiance, with `unshadowed_sum` = Σ_k luminance(E_k) max(0, cos θ_k) over
/// the same samples (visible or not). Delta lights: 1. Extended lights: the "analytic times
/// visible fraction" ratio estimator E(p, n) / unshadowed_sum, E the closed-form unoccluded
/// illuminance (0 when the sum is 0). It is exact where the light is entirely visible (no
/// noise outside penumbrae) or entirely hidden, and otherwise biased by O(1/N) (a ratio of
/// means; docs/lights.md) while consistent.
float shadow_sample_weight(const Light& light, const Vec3& p, const Vec3& n, float unshadowed_sum);

/// Unoccluded illuminance in lux at p on a surface with unit normal n, in closed form for every
/// light type (media and surfaces ignored).
Rgb unshadowed_irradiance(const Light& light, const Vec3& p, const Vec3& n);

/// Luminous flux in lumens for lights that have one; 0 for directional lights.
float luminous_flux_lm(const Light& light);

/// The light's type as written in scene files.
std::string light_type_name(const Light& light);

}  // namespace kasumi
