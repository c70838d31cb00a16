#pragma once
/// The sky as secondary rays meet it (Whitted reflections and refractions, path-traced
/// bounces): the sky's radiance when a ray leaves the scene, and the air's aerial perspective
/// in front of the surface it reaches. Camera rays go through SkyRenderer::apply (and the
/// shafts of render/sky_shafts.h); secondary segments are not shadowed (no shafts).
#include "core/rng.h"
#include "render/scene_runtime.h"

namespace kasumi {

/// What a secondary ray that meets no surface receives: the sky (sun disc included when
/// `sun_disc`) when the scene has an atmosphere, else the constant background. cd/m².
Rgb escaped_radiance(const SceneRuntime& scene, const Ray& ray, bool sun_disc, Pcg32& rng);

/// L_air + T_air L_behind for a secondary segment of `ray` ending on a surface at t_end (the air
/// in between); L_behind unchanged without an atmosphere.
Rgb through_air(const SceneRuntime& scene, const Ray& ray, float t_end, const Rgb& behind,
                Pcg32& rng);

}  // namespace kasumi
