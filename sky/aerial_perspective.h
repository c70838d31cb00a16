#pragma once
/// Camera-frustum aerial-perspective table (Hillaire 2020, "A Scalable and Production Ready Sky
/// and Atmosphere Rendering Technique", Computer Graphics Forum 39(4), sec. 5.4): the light the
/// air scatters toward the camera and its transmittance, from the camera to each of 32 depth
/// slices along 32 x 32 rays through the image, built per frame from the fast sky's tables and
/// looked up trilinearly for every camera ray that reaches a surface.
///
/// Differences from Hillaire's table (what we chose):
///  - The phase functions are factored out: along a camera ray the angle to the sun is
///    constant, so each froxel holds the Rayleigh and Mie single scattering *without* phase and
///    the (isotropic) multiple scattering separately, and the lookup multiplies them by the
///    ray's own phases. The Mie forward peak around the sun is exact per pixel instead of being
///    interpolated over 2 degrees of froxel. (The Rayleigh phase, whose depolarisation may vary
///    with the wavelength, is c0_b + c2_b mu² per band: its light is kept as two sums, below.)
///  - Depth slices crowd quadratically toward the camera: slice k ends at 32 km (k / 32)², the
///    first at 31 m, the last 2 km wide; between slices the values are linear in the distance
///    (so the first slice is exact to first order in t, where L ~ t and 1 - T ~ t).
///  - The 32 x 32 rays pass through the image's corners and edges, so every camera ray
///    interpolates (no extrapolation at the border).
/// Values are stored in the working RGB (to_rgb of the bands, and the transmittance reduced as
/// SkyRenderer::transmittance_rgb does): both maps are linear, so interpolating RGB equals
/// converting the interpolated bands.
#include "core/camera.h"
#include "core/color.h"
#include "sky/sky_luts.h"
#include "sky/sky_scene.h"

#include <vector>

namespace kasumi {

/// A pinhole camera's view: its position and the image plane at unit distance along forward,
/// `corner + u du + v dv` for film coordinates (u, v) in [0, 1]² (u = x / width, v = y / height).
struct ViewFrustum {
    DVec3 origin{0.0};
    DVec3 forward{0.0, 0.0, -1.0};  ///< unit
    DVec3 corner{0.0}, du{0.0}, dv{0.0};

    /// Unit direction through film coordinates (u, v).
    DVec3 direction(double u, double v) const { return glm::normalize(corner + u * du + v * dv); }
    /// Film coordinates of unit direction d; false when d points away from the image plane.
    bool film_coordinates(const DVec3& d, double& u, double& v) const;
};

/// The frustum of `camera` for a width x height film (from its rays through three corners).
ViewFrustum make_view_frustum(const Camera& camera, int width, int height);

class AerialPerspective {
  public:
    static constexpr int kWidth = 32, kHeight = 32, kSlices = 32;
    static constexpr double kDepthM = 32000.0;  ///< far end of the last slice, metres

    /// Marches the 32 x 32 rays of `frustum` through the tables of `luts` (the transmittance and
    /// multiple-scattering tables; the sky view is not used). `white` is SkyScene::to_rgb of a
    /// flat unit spectrum (the transmittance's normaliser).
    AerialPerspective(const SkyScene& sky, const SkyLuts& luts, const ViewFrustum& frustum,
                      const Rgb& white);

    /// Distance of slice k's far end from the camera (k = 0: the camera).
    static double slice_distance(int k) {
        const double x = static_cast<double>(k) / kSlices;
        return kDepthM * x * x;
    }

    /// In-scattered radiance (working RGB, cd/m²) and transmittance of the air from the camera
    /// along unit direction d over [0, min(t, kDepthM)]. False when d lies outside the frustum
    /// (then the outputs are untouched).
    bool lookup(const DVec3& d, double t, Rgb& radiance, Rgb& transmittance) const;

    const ViewFrustum& frustum() const { return m_frustum; }

  private:
    /// Per froxel: single scattering by Rayleigh and by Mie without their phases, multiple
    /// scattering (isotropic, phase included), transmittance; RGB each. The Rayleigh phase of
    /// band b is c0_b + c2_b mu² (its depolarisation may depend on the wavelength), so its
    /// light is kept as the two sums over bands weighted by c0_b and by c2_b:
    /// radiance = rayleigh + mu² rayleigh_mu2, exact per band.
    /// Five RGB values per froxel in one padded row of 16 floats (the lookup's trilinear sum
    /// runs over the row as one vectorisable loop): Rayleigh without its phase as c0 and c2
    /// parts, Mie without its phase, multiple scattering, transmittance.
    struct Froxel {
        static constexpr int kRayleigh = 0, kRayleighMu2 = 3, kMie = 6, kMultiple = 9,
                             kTransmittance = 12, kFloats = 16;
        float v[kFloats] = {};
    };
    const Froxel& at(int slice, int y, int x) const {
        return m_froxels[(static_cast<size_t>(slice) * kHeight + y) * kWidth + x];
    }

    ViewFrustum m_frustum;
    DVec3 m_sun_direction{0.0, 1.0, 0.0};
    PhaseFunction m_mie_phase;
    std::vector<Froxel> m_froxels;  ///< [slice 0..kSlices][y][x]; slice 0: L = 0, T = 1
};

}  // namespace kasumi
