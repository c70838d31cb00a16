#pragma once
/// Shadow photons (Jensen & Christensen, "Efficiently Rendering Shadows using the Photon Map",
/// Compugraphics 1995; Jensen, "Global Illumination using Photon Maps", EGWR 1996, §3): the
/// shadow pass (PhotonPass::Shadow) follows each photon's straight line from a light through the
/// scene and stores a direct-illumination photon where it first meets a surface and shadow
/// photons wherever it meets surfaces behind that. At a shading point the nearest of them decide,
/// per light, whether a shadow ray is needed:
///   - only direct photons of that light: lit, no shadow ray;
///   - only shadow photons of that light: shadowed, no shadow ray;
///   - both, or too few of that light's photons: unknown, shadow rays as usual.
#include "gi/photon/photon_estimate.h"
#include "gi/photon/photon_map.h"
#include "render/integrator.h"

namespace kasumi {

/// Fraction of the search radius a photon may lie off the shading point's tangent plane and
/// still count: photons on nearby surfaces that are not the shading point's (the far side of a
/// corner, a block standing on the floor) are left out.
inline constexpr float kShadowDiscThickness = 0.25f;

/// Photons of one light that must be among the k nearest for a decision: ⌈k/4⌉.
inline int shadow_min_photons(int k) {
    return (k + 3) / 4;
}

/// Per-light visibility at x from the shadow map: the k nearest photons within max_radius that
/// arrived on the side n faces (dot(n, wi) > 0, n the geometric normal turned to the viewer) and
/// lie within kShadowDiscThickness × (the farthest one's distance) of the tangent plane, counted
/// per light; `known[l]` (l < lights) is Lit when all of light l's counted photons are direct
/// and there are at least shadow_min_photons(k), Shadowed when all are shadow photons, else
/// Unknown. A wrong Lit or Shadowed can only happen within the nearest counted photon's distance
/// of the light's shadow boundary (on a plane: the segment from x to that photon crosses it),
/// so shadows narrower than the photon spacing can be missed.
void classify_shadow_photons(const PhotonMap& shadow_map, const Vec3& x, const Vec3& n, int k,
                             float max_radius, size_t lights, PhotonQueryScratch& scratch,
                             KnownVisibility* known);

}  // namespace kasumi
