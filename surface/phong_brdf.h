#pragma once
/// The Phong BRDF of a PhongMaterial, one for every technique (direct shading, Whitted, the path
/// tracer, photon tracing and gathering, radiosity highlights): the normalised modified Phong
/// model (Lewis 1994, "Making Shaders More Physically Plausible"; Lafortune & Willems 1994)
///   f(wo, wi) = kd / π + W(θi) (n + 2) / (2π) cos^n α   per steradian,
/// α = angle(wo, mirror of wi about n), W = ks or its Fresnel curve (material.h). Its
/// directional albedo is at most max(kd + W) <= 1: the lobe's (n + 2)/(2π) cos^n α cos θ
/// integrates to at most 1 over the hemisphere (equality at normal incidence).
///
/// Conventions: n is the unit shading normal; wo points toward the viewer, wi toward the light,
/// both unit and away from the point. Horizon rule (the only one): f = 0 unless both wo and wi
/// lie strictly above the shading normal (n·wo > 0 and n·wi > 0). It makes f reciprocal,
/// f(wo, wi) = f(wi, wo), when W is constant (ks_fresnel "none"; a Fresnel W(θi) is not).
#include "core/math.h"
#include "surface/material.h"

#include <optional>

namespace kasumi {

/// f(wo, wi) per steradian, RGB; zero below the horizon of n (see above).
Rgb eval(const PhongMaterial& m, const Vec3& n, const Vec3& wo, const Vec3& wi);

/// Probability with which sample() picks the specular lobe:
/// luminance(ks) / (luminance(kd) + luminance(ks)), 0 for a black material.
float specular_lobe_probability(const PhongMaterial& m);

/// Density (per steradian, over the hemisphere of n) with which sample() draws wi: the
/// mixture (1 − p_s) cos θi / π + p_s (n + 1)/(2π) cos^n α, with p_s the specular lobe
/// probability. Zero for wi below the horizon of n or wo below it.
float pdf(const PhongMaterial& m, const Vec3& n, const Vec3& wo, const Vec3& wi);

/// One direction drawn by sample().
struct PhongSample {
    Vec3 wi{0.0f};     ///< unit, above the horizon of n
    Rgb f{0.0f};       ///< eval(m, n, wo, wi)
    float pdf = 0.0f;  ///< pdf(m, n, wo, wi), per steradian, > 0
};

/// Draws wi: u_lobe in [0, 1) picks the specular lobe with specular_lobe_probability, else
/// the cosine-weighted hemisphere; u in [0, 1)² places the direction. Empty when the material
/// reflects nothing, wo is below the horizon or wi falls below it (the path ends: absorbed).
std::optional<PhongSample> sample(const PhongMaterial& m, const Vec3& n, const Vec3& wo,
                                  float u_lobe, Vec2 u);

/// A direction about the mirror direction `mirror` (unit) with density (n + 1)/(2π) cos^n α
/// per steradian over the whole sphere, α the angle to `mirror`: cos α = u.x^(1/(n+1)),
/// azimuth 2π u.y. The specular half of sample(); it may fall below a surface's horizon.
Vec3 sample_specular_lobe(const Vec3& mirror, float exponent, Vec2 u);

}  // namespace kasumi
