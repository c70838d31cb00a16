#pragma once
/// The detail polygons of recent (light, geometry) pairs, kept for the process: the frames of a
/// sequence that keep the light and the polygons fixed skip pass 1 of the object-space method.
/// The key is the exact bits of the light's centre and of every shape's vertices (not a hash,
/// so a changed vertex can never reuse stale polygons); materials and the camera are not in it.
#include "surface/shadows/light_centre.h"
#include "surface/shadows/shadow_polygons.h"

#include <memory>

namespace kasumi {

/// Shapes' polygons for `light`: from the cache when an entry's key equals this one (then
/// *reused = true), else built and stored (the cache holds the 8 most recent entries).
/// Thread-safe.
std::shared_ptr<const ShadowPolygons> cached_shadow_polygons(const std::vector<Shape>& shapes,
                                                             const LightCentre& light,
                                                             bool* reused = nullptr);

}  // namespace kasumi
