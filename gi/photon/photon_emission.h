#pragma once
/// Photon emission (Jensen 2001, §5.1): photons leave every light with directions (and points,
/// for extended lights) drawn in proportion to the emitted intensity, so all photons of one
/// light carry the same flux and the photons of a pass sum exactly to the lights' flux.
#include "core/color.h"
#include "core/rng.h"
#include "lights/light.h"

#include <memory>
#include <vector>

namespace kasumi {

/// The sphere around the scene that directional lights cover: their photons start on a disc of
/// this radius facing the light, just outside the sphere.
struct BoundingSphere {
    Vec3 center{0.0f};
    float radius = 0.0f;  ///< m; 0: directional lights emit nothing
};

/// A photon as it leaves its source.
struct EmittedPhoton {
    Ray ray;              ///< origin on the source, unit direction of travel
    Rgb power{0.0f};      ///< flux, photometrically scaled RGB (lm)
    uint32_t source = 0;  ///< index of the source (lights first, in the scene's order)
};

/// A surface that emits uniform Lambertian radiance from its front: a triangle whose front is
/// the side its vertices wind counter-clockwise toward, or a sphere emitting outward.
struct EmissiveTriangle {
    Vec3 v0{0.0f}, v1{0.0f}, v2{0.0f};
    Rgb radiance{0.0f};  ///< cd/m²
};
struct EmissiveSphere {
    Vec3 center{0.0f};
    float radius = 1.0f;
    Rgb radiance{0.0f};  ///< cd/m²
};

/// RGB flux of a light (luminance in lm): 4π I (point), the spot's cone integral, the IES
/// table's integral, π² I_l L (line), π L A per side (polygon), 4π² R² L (sphere), and for a
/// directional light E π R² through the bounding sphere's disc.
Rgb light_flux(const Light& light, const BoundingSphere& scene);
/// π L A (one-sided Lambertian emitters).
Rgb emissive_flux(const EmissiveTriangle& t);
Rgb emissive_flux(const EmissiveSphere& s);

/// Draws a photon leaving `light` with direction (and point) density proportional to what the
/// light emits, carrying `power`. Point: uniform sphere. Spot: cos θ ∝ the falloff s(cos θ).
/// Goniometric: a cell of the IES table in proportion to its exact (bilinear) flux, then
/// uniform solid angle in the cell accepted with I / I_max,cell (exact rejection). Line: a
/// point uniform in length, angle α to the line with density ∝ sin²α. Polygon, sphere and
/// emissive surfaces: a point uniform in area, a cosine-weighted direction. Directional: a point
/// uniform on the disc.
class PhotonSource;

/// All sources of a scene with the photons of a pass allotted to them: source s gets N_s photons
/// of N in proportion to its flux's luminance (largest remainders; at least one for every
/// source that emits when N allows), each carrying Φ_s / N_s. Photon i belongs to the source
/// whose range holds i, so a pass is deterministic for any thread count.
class PhotonEmitter {
  public:
    PhotonEmitter(const std::vector<Light>& lights, const BoundingSphere& scene,
                  const std::vector<EmissiveTriangle>& triangles = {},
                  const std::vector<EmissiveSphere>& spheres = {});
    ~PhotonEmitter();
    PhotonEmitter(PhotonEmitter&&) noexcept;

    /// Sets the pass size N and allots it.
    void allot(uint64_t count);
    uint64_t count() const { return m_count; }
    /// Photons allotted to source s (lights first, then triangles, then spheres).
    uint64_t source_count(size_t s) const;
    size_t sources() const;
    /// Sum over sources of their flux (what the photons of a pass sum to).
    Rgb total_flux() const;

    /// Photon `index` < count() of the pass; `rng` drives its sampling.
    EmittedPhoton emit(uint64_t index, Pcg32& rng) const;

  private:
    std::vector<std::unique_ptr<PhotonSource>> m_sources;
    std::vector<uint64_t> m_first;  ///< first photon index of each source, plus the end
    uint64_t m_count = 0;
};

}  // namespace kasumi
