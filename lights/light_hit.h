#pragma once
/// A light as a ray sees it: where a ray meets the emitting surface of an area light, and the
/// solid-angle density with which sample_incident picks a direction toward it (the light's half
/// of multiple importance sampling). Delta lights (directional, point, spot, goniometric) have
/// no surface: a ray never meets them and their density is a Dirac delta, reported as 0. A line
/// light is infinitely thin: rays miss it, and its samples are spread per metre over a set of
/// zero solid angle, so its solid-angle density is reported as 0 too (no MIS with it).
#include "core/color.h"
#include "core/math.h"
#include "lights/light.h"

#include <optional>

namespace kasumi {

/// A ray meeting a light.
struct LightHit {
    float t = 0.0f;      ///< metres along the ray (in units of the ray's direction)
    Rgb radiance{0.0f};  ///< cd/m² seen along the ray: the luminance, 0 behind a one-sided polygon
};

/// The polygon's plane point with t in (ray.t_min, ray.t_max) inside its edges, from either side
/// (the back of a one-sided light blocks the ray and shows radiance 0).
std::optional<LightHit> intersect(const PolygonLight& light, const Ray& ray);

/// The sphere's nearest point with t in (ray.t_min, ray.t_max] for a ray starting outside it
/// (spheres emit outward only: from inside, nothing), in double precision by the stable form of
/// intersect_sphere (lights/ray_sphere.h).
std::optional<LightHit> intersect(const SphereLight& light, const Ray& ray);

/// The light's hit for polygon and sphere lights; empty for every other type.
std::optional<LightHit> intersect(const Light& light, const Ray& ray);

/// Density per steradian with which sample_incident(light, p, u) picks unit direction wi:
/// uniform in area on the polygon, r² / (A |cos θ_light|) where the ray (p, wi) meets it (both
/// sides: the irradiance, not the density, is 0 from behind a one-sided light), 0 where it
/// misses.
float sample_pdf(const PolygonLight& light, const Vec3& p, const Vec3& wi);

/// sample_pdf for any light: polygon and sphere (lights/sphere_light.h) as stated there; 0 for
/// delta and line lights (see above).
float sample_pdf(const Light& light, const Vec3& p, const Vec3& wi);

}  // namespace kasumi
