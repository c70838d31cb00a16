#pragma once
/// The energy-conserving Phong BRDF of the GI methods as a sampleable distribution: the
/// normalised modified Phong model (Lafortune & Willems 1994)
///   f(wo, wi) = kd / π + W(θi) (n + 2) / (2π) cos^n α,   α = angle(wo, reflect(wi, n)),
/// whose directional albedo is at most kd + W <= 1 (the lobe (n + 2)/(2π) cos^n α cos θ
/// integrates to at most 1 over the hemisphere). Directions point away from the surface.
#include "core/math.h"
#include "surface/material.h"

#include <optional>

namespace kasumi {

/// BRDF value (per steradian), zero when wo or wi is below the shading normal n.
Rgb phong_eval(const PhongMaterial& m, const Vec3& n, const Vec3& wo, const Vec3& wi);

/// Probability of picking the specular lobe: luminance(ks) / (luminance(kd) + luminance(ks)).
float phong_specular_probability(const PhongMaterial& m);

/// Density (per steradian) with which phong_sample draws wi: a mixture of the cosine density
/// cos θ / π and the lobe density (n + 1)/(2π) cos^n α around the mirror direction.
float phong_pdf(const PhongMaterial& m, const Vec3& n, const Vec3& wo, const Vec3& wi);

struct PhongSample {
    Vec3 wi{0.0f};
    Rgb f{0.0f};       ///< phong_eval(wo, wi)
    float pdf = 0.0f;  ///< phong_pdf(wo, wi), per steradian
};

/// Draws wi by lobe (u_lobe picks diffuse or specular, u the direction); empty when the material
/// reflects nothing or the direction falls below the surface (the path ends: absorbed).
std::optional<PhongSample> phong_sample(const PhongMaterial& m, const Vec3& n, const Vec3& wo,
                                        float u_lobe, Vec2 u);

}  // namespace kasumi
