#pragma once
/// Fast sky: precomputed tables after Hillaire 2020 ("A Scalable and Production Ready Sky and
/// Atmosphere Rendering Technique", Computer Graphics Forum 39(4)):
///  - transmittance to the top of the atmosphere T(r, mu), 256 x 64, Bruneton's 2017
///    parametrisation (exact at the texel centres, bilinear between);
///  - multiple scattering Psi_ms(r, mu_s), 128 x 16: the light scattered into orders 2 and up
///    with an isotropic phase (Hillaire eqs. 5-10), its orders iterated through the table (as
///    in Bruneton & Neyret 2008) instead of Hillaire's local geometric series, which fails in
///    twilight; with it, the sky's irradiance on the ground per sun cosine;
///  - sky view for one camera altitude and sun, 96 x 108 in (azimuth from the sun over [0, pi]:
///    the sky is symmetric about the sun's vertical plane; elevation with sqrt crowding at the
///    horizon), marched with the two tables above. Along a view ray the angle to the sun is
///    constant, so the phases factor out of its integral: each texel holds Rayleigh and Mie
///    single scattering without their phases and the rest (multiple scattering, the ground),
///    and the lookup applies the direction's own phases (as sky/aerial_perspective.h does):
///    the Mie forward peak is exact per pixel instead of interpolated between texels.
/// Transmittance and multiple scattering depend on the atmosphere (at the render's wavelengths)
/// and the sun's angular radius only, not on the sun's direction: they are built once and shared
/// by copies of a SkyLuts (sequence/sequence_cache.h keeps them across the frames of a sequence);
/// the sky view depends on the sun and the camera altitude and belongs to each copy. Values per
/// band, per unit TOA solar irradiance (radiance 1/sr).
#include "sky/sky_scene.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

namespace kasumi {

class SkyLuts {
  public:
    /// Builds the transmittance and multiple-scattering tables (sun independent). A copy shares
    /// them (they are immutable) and has its own sky view.
    explicit SkyLuts(const SkyScene& sky);

    /// Builds the sky-view table for a camera at `camera` (world metres) and the scene's sun.
    void build_sky_view(const SkyScene& sky, const DVec3& camera);

    /// Transmittance from a point at radius r toward cosine mu (mu above the horizon), bilinear.
    void transmittance(double r, double mu, Bands& out) const;
    /// The parts of transmittance() that depend on the radius alone (its table row among
    /// them), for many cosines at one radius: transmittance(row, mu) equals
    /// transmittance(r, mu) bit for bit.
    struct TransmittanceRow {
        double r = 0.0, d_min = 0.0, d_max = 0.0;
        int y0 = 0, y1 = 0;
        double fy = 0.0;
    };
    TransmittanceRow transmittance_row(double r) const;
    void transmittance(const TransmittanceRow& row, double mu, double* out) const;
    /// Sun transmittance at world point p including the disc fraction above the horizon.
    void sun_transmittance(const SkyScene& sky, const DVec3& p, Bands& out) const;
    /// Multiple-scattering radiance per unit sigma_s at radius r, sun zenith cosine mu_s.
    void multiple_scattering(double r, double mu_s, Bands& out) const;
    /// Irradiance of the sky (all orders; no direct sun) on the ground where the sun's zenith
    /// cosine is mu_s, per unit TOA solar irradiance.
    void ground_sky_irradiance(double mu_s, Bands& out) const;
    /// Sky (and ground) radiance seen from the sky-view camera along d, without the sun disc.
    void sky_view(const SkyScene& sky, const DVec3& d, Bands& out) const;

    /// The light scattered toward p along d, split by the phase that multiplies it (per band,
    /// per unit TOA solar irradiance): Rayleigh and Mie single scattering without their phases,
    /// and the rest (multiple scattering with its isotropic phase, the ground); radiance =
    /// p_R(mu) rayleigh + p_M(mu) mie + rest with mu the cosine between d and the sun.
    struct ScatteringTerms {
        Bands rayleigh{}, mie{}, rest{}, transmittance{};
    };
    /// The terms along p + t d over [0, t_max] by `steps` nodes (the long-segment part of
    /// march()); adds the ground if the segment reaches it.
    void march_terms(const SkyScene& sky, const DVec3& p, const DVec3& d, double t_max, int steps,
                     ScatteringTerms& out) const;

    /// In-scattering and transmittance along p + t d over [0, t_max] by `steps` nodes with the
    /// tables for the light (aerial perspective; also fills the sky-view table). Adds the
    /// ground if the segment reaches it.
    void march(const SkyScene& sky, const DVec3& p, const DVec3& d, double t_max, int steps,
               Bands& radiance, Bands& transmittance) const;

    /// The multiple-scattering table's texture coordinate of a sun cosine (texel centres on
    /// mu_s = -1 and 1).
    static double multiple_u(double mu_s) {
        // unit_to_texel (sky_luts.cpp) of the cosine's unit coordinate, inline for the table build.
        return 0.5 / kMultipleW +
               std::clamp(0.5 * (mu_s + 1.0), 0.0, 1.0) * (1.0 - 1.0 / kMultipleW);
    }

    /// Drops the multiple-scattering table (single scattering only), for measurements; call
    /// before build_sky_view.
    void disable_multiple_scattering() {
        m_multiple = std::make_shared<const std::vector<float>>(m_multiple->size(), 0.0f);
        m_ground_irradiance =
            std::make_shared<const std::vector<float>>(m_ground_irradiance->size(), 0.0f);
    }

    /// Segments shorter than this (metres) are integrated in closed form from one node.
    static constexpr double kShortSegmentM = 1000.0;
    static constexpr int kTransmittanceW = 256, kTransmittanceH = 64;
    static constexpr int kMultipleW = 128, kMultipleH = 16;
    /// Orders of the multiple-scattering table computed by iteration (2 to kMultipleOrders + 1
    /// scattering events), then a geometric tail.
    static constexpr int kMultipleOrders = 4;
    /// Sky view: azimuths over [0, pi], elevations, nodes per marched texel.
    static constexpr int kSkyViewW = 96, kSkyViewH = 108, kSkyViewSteps = 40;

    /// The sun's angular radius (radians) with its cosine and sine, evaluated once per table
    /// instead of per node.
    struct SunDisc {
        double radius = 0.0, cos_radius = 1.0, sin_radius = 0.0;
        SunDisc() = default;
        explicit SunDisc(double radius_rad)
            : radius(radius_rad),
              cos_radius(std::cos(radius_rad)),
              sin_radius(std::sin(radius_rad)) {}
    };

  private:
    void build_multiple_scattering(const SkyScene& sky);
    /// The multiple-scattering table's texture coordinate of a radius (texel centres on the
    /// ground and the top; altitude by its square root).
    double multiple_v(double r) const;
    void lookup(const std::vector<float>& table, int w, int h, double u, double v,
                Bands& out) const;
    int m_bands = 3;
    double m_rg = 0.0, m_rt = 0.0;
    SunDisc m_sun;
    DVec3 m_camera{0.0};
    double m_camera_r = 0.0;
    DVec3 m_up{0.0, 1.0, 0.0}, m_forward{1.0, 0.0, 0.0}, m_side{0.0, 0.0, 1.0};  ///< sky-view frame
    double m_horizon = 0.0;  ///< elevation of the planet's horizon from the camera, radians
    std::shared_ptr<const std::vector<float>> m_transmittance;      ///< [y][x][band]
    std::shared_ptr<const std::vector<float>> m_multiple;           ///< [r][mu_s][band]
    std::shared_ptr<const std::vector<float>> m_ground_irradiance;  ///< [mu_s][band]
    std::vector<float> m_sky_view;  ///< [y][x][rayleigh bands, mie bands, rest bands]
};

}  // namespace kasumi
