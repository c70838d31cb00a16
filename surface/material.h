#pragma once
/// Surface materials: a closed set of small value types (Phong; the Whitted materials mirror
/// and dielectric). Reflectances are RGB in [0, 1].
#include "core/color.h"
#include "core/json_node.h"

#include <variant>

namespace kasumi {

/// How the Phong specular reflectance W depends on the angle of incidence θi (Phong 1975 allows
/// any W(θi); the classic choice is a Fresnel curve). ks is W at normal incidence in every mode.
enum class SpecularFresnel {
    None,     ///< W = ks, constant
    Schlick,  ///< W = ks + (1 - ks)(1 - cos θi)^5 (Schlick 1994)
    Exact,    ///< W = F(cos θi, η) exact unpolarised Fresnel per channel, η from F(1, η) = ks
};

/// Phong material. Radiance leaving toward wo under a light of irradiance E (on a surface
/// facing it) arriving from wi at the shading normal n:
///   L = ka * L_ambient + (kd / π) E cos θ + W(θ) (n + 2) / (2π) cos^n α  E cos θ,
/// with cos θ = dot(n, wi), α the angle between wo and wi mirrored about n, and W = ks unless
/// `ks_fresnel` says otherwise: the normalised modified Phong lobe (Lafortune & Willems 1994),
/// energy conserving for kd + W <= 1 (a Fresnel W reaches 1 at grazing incidence).
struct PhongMaterial {
    Rgb ka{0.0f};
    Rgb kd{0.8f};
    Rgb ks{0.0f};
    float n = 20.0f;  ///< specular exponent, >= 0
    SpecularFresnel ks_fresnel = SpecularFresnel::None;
    Rgb emission{0.0f};  ///< cd/m², Lambertian, from the front side (emitted_radiance)
};

/// A perfect mirror: reflects kr of the radiance arriving from the mirror direction.
struct MirrorMaterial {
    Rgb kr{1.0f};        ///< reflectance in [0, 1]
    Rgb emission{0.0f};  ///< cd/m², Lambertian, from the front side (emitted_radiance)
};

/// A smooth dielectric interface (glass, water): exact Fresnel reflection, refraction with the
/// rest (1 - F, times `tint` on every crossing), total internal reflection. The outside is the
/// side the shape's normal points to.
struct DielectricMaterial {
    float ior = 1.5f;    ///< index of refraction relative to the outside medium, > 0
    Rgb tint{1.0f};      ///< transmittance factor per refraction, in [0, 1]
    Rgb emission{0.0f};  ///< cd/m², Lambertian, from the front side (emitted_radiance)
};

using Material = std::variant<PhongMaterial, MirrorMaterial, DielectricMaterial>;

/// Parses {"type": "phong", "ka", "kd", "ks", "n", "ks_fresnel"}, {"type": "mirror", "kr"} or
/// {"type": "dielectric", "ior", "tint"}; reflectances are a scalar or [r, g, b] in [0, 1].
/// Every type also takes "emission_cd_m2": a scalar L (white, luminance L) or [r, g, b] (scene-
/// linear RGB radiance whose luminance is in cd/m²), >= 0, default 0: a Lambertian emitter.
/// Bad values throw an input error naming the file and JSON path (never clamped).
Material parse_material(const JsonNode& node);

/// The material's emitted radiance (cd/m², RGB), the same in every direction of its front side.
Rgb emission(const Material& m);

/// Diffuse reflectance for the `albedo` AOV: Phong kd, mirror kr, dielectric tint.
Rgb albedo(const Material& m);

/// True for materials that reflect or refract only in discrete directions (mirror, dielectric):
/// lights reach them only through the Whitted recursion, never by direct shading.
bool is_specular(const Material& m);

/// The Phong specular reflectance W(θi) per channel; cos_theta_i = dot(n, wi) in [0, 1].
Rgb specular_reflectance(const PhongMaterial& m, float cos_theta_i);

}  // namespace kasumi
