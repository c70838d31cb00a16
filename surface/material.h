#pragma once
/// Surface materials: a closed set (Phong now; mirror and dielectric join with the Whitted
/// issue). Reflectances are RGB in [0, 1].
#include "core/color.h"
#include "core/json_node.h"

#include <variant>

namespace kasumi {

/// Phong material. Radiance leaving toward wo under a light of irradiance E (on a surface
/// facing it) arriving from wi at the shading normal n:
///   L = ka * L_ambient + (kd / π) E cos θ + ks (n + 2) / (2π) cos^n α  E cos θ,
/// with cos θ = dot(n, wi) and α the angle between wo and wi mirrored about n: the normalised
/// modified Phong lobe (Lafortune & Willems 1994), energy conserving for kd + ks <= 1.
struct PhongMaterial {
    Rgb ka{0.0f};
    Rgb kd{0.8f};
    Rgb ks{0.0f};
    float n = 20.0f;  ///< specular exponent, >= 0
};

using Material = std::variant<PhongMaterial>;

/// Parses {"type": "phong", "ka", "kd", "ks", "n"}; each reflectance a scalar or [r, g, b].
Material parse_material(const JsonNode& node);

/// Diffuse reflectance used for the `albedo` AOV.
Rgb albedo(const Material& m);

}  // namespace kasumi
