#pragma once
/// The sky at render time: the background of rays that leave the scene, aerial perspective in
/// front of surfaces, the sky's irradiance on surfaces, and the transmittance of the air, in
/// `reference` mode (sky/sky_reference.h) or `fast` mode (sky/sky_luts.h). RGB outputs
/// are in the working space with luminance in cd/m² (radiance) or lux (irradiance).
#include "core/film.h"
#include "core/rng.h"
#include "lights/light.h"
#include "sky/aerial_perspective.h"
#include "sky/sky_luts.h"
#include "sky/sky_scene.h"

#include <memory>
#include <optional>

namespace kasumi {

class SkyRenderer {
  public:
    /// Builds what the mode needs for a camera at `camera_world`: in fast mode the tables
    /// (transmittance and multiple scattering once; the sky view for this camera and sun);
    /// in both modes the table of sky irradiance on surfaces near the origin.
    /// `tables` (fast mode, may be null: build them): the sun-independent tables built earlier
    /// for the same atmosphere, wavelengths and sun angular radius (see shared_tables()); the
    /// render is then bit-identical to one that builds them.
    /// `frustum` (fast mode, may be absent): the camera's view, for which the aerial-perspective
    /// table (sky/aerial_perspective.h) is built unless render.sky.aerial_perspective is
    /// "march"; without it every segment is marched per pixel.
    SkyRenderer(std::shared_ptr<const SkyScene> sky, const Vec3& camera_world,
                std::shared_ptr<const SkyLuts> tables = nullptr,
                const std::optional<ViewFrustum>& frustum = std::nullopt);

    const SkyScene& sky() const { return *m_sky; }
    const SkyLuts* luts() const { return m_luts.get(); }
    /// Fast mode: the sun-independent tables (transmittance, multiple scattering) without a sky
    /// view, to hand to the next frame's SkyRenderer; null in reference mode.
    std::shared_ptr<const SkyLuts> shared_tables() const { return m_tables; }
    /// Whether the constructor took the tables instead of building them.
    bool tables_reused() const { return m_tables_reused; }
    /// The camera-frustum aerial-perspective table; null when not built (reference mode, no
    /// frustum given, or render.sky.aerial_perspective "march").
    const AerialPerspective* aerial_table() const { return m_aerial.get(); }

    /// Radiance of a ray that meets no surface: sky, ground of the planet and the sun's disc.
    Rgb background(const Ray& ray, Pcg32& rng) const;
    /// Radiance of the sky arriving along a secondary ray that leaves the scene (Whitted
    /// reflections and refractions, path-traced bounces): as background(), but seen from the
    /// camera when ray.origin lies within kEnvironmentNearM of it (fast mode: the sky-view
    /// table, so a mirror shows exactly the sky the camera sees; the air changes over
    /// kilometres). The sun's disc only when `sun_disc` (the path tracer leaves it out after
    /// diffuse bounces: it samples the sun as a directional light).
    Rgb environment(const Ray& ray, bool sun_disc, Pcg32& rng) const;
    static constexpr double kEnvironmentNearM = 100.0;
    /// In-scattered radiance and transmittance of the air over [0, t] of `ray`. Camera rays
    /// (from the camera, inside the frustum) read the aerial-perspective table up to its
    /// 32 km and march the rest from its far end; other rays are marched per pixel.
    void aerial_perspective(const Ray& ray, float t, Pcg32& rng, Rgb& radiance,
                            Rgb& transmittance) const;
    /// Composes the sky into a camera sample: the background where the ray met nothing, and
    /// L = L_air + T_air * L in front of a surface at `t_hit`.
    void apply(const Ray& ray, float t_hit, Pcg32& rng, PixelSample& sample) const;
    /// Illuminance (lux) from the sky and the lit ground on a surface near the origin with
    /// unit normal n, nothing occluding (interpolated from a table of 16 x 32 normals).
    Rgb irradiance(const Vec3& n) const;
    /// Transmittance of the air between two points (RGB: the bands themselves in RGB mode, the
    /// sun-spectrum-weighted mean per channel in spectral mode).
    Rgb transmittance(const Vec3& from, const Vec3& to) const;
    /// Reduces per-band transmittance to RGB (see transmittance()).
    Rgb transmittance_rgb(const Bands& t) const;

  private:
    Bands radiance_bands(const DVec3& p, const DVec3& d, double t_max, bool sun_disc, Pcg32& rng,
                         Bands* transmittance) const;
    void build_irradiance();

    std::shared_ptr<const SkyScene> m_sky;
    std::shared_ptr<const SkyLuts> m_tables;  ///< sun independent, no sky view
    std::unique_ptr<SkyLuts> m_luts;          ///< shares m_tables' tables, plus the sky view
    std::unique_ptr<AerialPerspective> m_aerial;
    bool m_tables_reused = false;
    DVec3 m_camera{0.0};
    Rgb m_white{1.0f};  ///< to_rgb of a flat unit spectrum (transmittance normaliser)
    static constexpr int kIrrH = 16, kIrrW = 32;
    std::vector<Rgb> m_irradiance;  ///< [elevation][azimuth] of the normal
};

/// The sun as a directional light for surfaces and media: its illuminance at the top of the
/// atmosphere attenuated by the air from the origin toward it (evaluated once: scenes are
/// small against the 8 km scale height), or unattenuated without an atmosphere.
Light make_sun_light(const SkyScene& sky, bool through_atmosphere);

/// Reads the scene's "atmosphere" and "sun" keys (either may be absent): a sun adds its
/// directional light to `lights`; an atmosphere sets `sky`.
void parse_sky_keys(JsonObjectReader& scene, const SkySettings& settings,
                    std::shared_ptr<const SkyScene>& sky, std::vector<Light>& lights);

}  // namespace kasumi
