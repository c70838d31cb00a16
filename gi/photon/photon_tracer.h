#pragma once
/// The first pass of photon mapping (Jensen 2001, ch. 5): photons leave the lights and are
/// traced through the surfaces (Phong with Russian roulette, mirrors, dielectrics with exact
/// Fresnel) and the media (free-flight sampling, phase sampling), and stored in three maps.
#include "gi/photon/photon_emission.h"
#include "gi/photon/photon_map.h"
#include "render/scene_runtime.h"
#include "scene/photon_settings.h"

#include <cstdint>
#include <vector>

namespace kasumi {

/// Which map a pass fills. Every pass traces whole paths; each stores only its own photons.
enum class PhotonPass {
    Global,   ///< every hit on a Phong surface (direct ones included)
    Caustic,  ///< Phong hits whose path from the light was one or more mirror/dielectric
              ///< events and nothing else (L S+ D); paths end at their first other event
    Volume,   ///< real scattering events in media after at least one event (the first
              ///< scattering of light straight from a light is rendered by shadow rays)
    Shadow,   ///< the straight line of each photon from a light through every surface, media
              ///< ignored (Jensen & Christensen 1995): a direct-illumination photon at the first
              ///< Phong hit, shadow photons at the Phong hits behind it; no power, the light's
              ///< index in Photon::light. Pass the lights alone to the emitter.
};

/// The three maps and how they were made.
struct PhotonMaps {
    PhotonMap global, caustic, volume;
    PhotonMap shadow;  ///< direct and shadow photons (gi/photon/photon_shadow.h)
    uint64_t global_emitted = 0, caustic_emitted = 0, volume_emitted = 0, shadow_emitted = 0;
    double trace_seconds = 0.0;  ///< wall time of the passes
    double build_seconds = 0.0;  ///< wall time of balancing the kd-trees
};

/// The sphere around the surfaces and bounded media (directional lights cover its disc).
BoundingSphere scene_bounding_sphere(const SceneRuntime& scene);

/// The emissive surfaces of the scene as triangles and spheres (materials with emission).
void collect_emissive_surfaces(const SceneRuntime& scene, std::vector<EmissiveTriangle>& triangles,
                               std::vector<EmissiveSphere>& spheres);

/// Traces the `count` photons of one pass (photon i drawn from its own PCG32 stream keyed by
/// seed, pass and i: the result does not depend on `threads`) and returns the stored photons in
/// photon order. `max_bounces` caps surface and volume events per path; Russian roulette ends
/// most paths earlier. Never throws.
std::vector<Photon> trace_photons(const SceneRuntime& scene, const PhotonEmitter& emitter,
                                  PhotonPass pass, int max_bounces, uint64_t seed, int threads);

/// All passes with the counts of `settings` (the shadow pass from the lights alone), and the
/// kd-trees.
PhotonMaps build_photon_maps(const SceneRuntime& scene, const PhotonSettings& settings,
                             uint64_t seed, int threads);

}  // namespace kasumi
