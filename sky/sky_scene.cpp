#include "sky/sky_scene.h"

#include "core/cie_1931.h"
#include "core/spectrum.h"
#include "sky/atmosphere_json.h"

#include <cstdio>

namespace kasumi {

Rgb SkyScene::to_rgb(const Bands& b) const {
    glm::dvec3 sum(0.0);
    for (int i = 0; i < bands(); ++i)
        sum += band_to_rgb[static_cast<size_t>(i)] * b[i];
    return Rgb(sum);
}

Bands SkyScene::sun_disc(double cos_angle) const {
    Bands out{};
    if (cos_angle < sun_cos_radius)
        return out;
    // Solid angle of the disc, 2 pi (1 - cos r), written with sin² (r/2) against cancellation.
    const double s = std::sin(0.5 * sun_radius_rad);
    const double solid_angle = 4.0 * kPiD * s * s;
    // Position on the disc as a fraction of its radius, then mu on the solar surface.
    const double angle = std::acos(std::min(1.0, cos_angle));
    const double x = std::min(1.0, angle / sun_radius_rad);
    const double mu = std::sqrt(std::max(0.0, 1.0 - x * x));
    for (int i = 0; i < bands(); ++i) {
        const double nm = atmosphere.wavelengths_nm[static_cast<size_t>(i)];
        out[i] = sun_limb_darkening(nm, mu) / (solid_angle * sun_limb_darkening_mean(nm));
    }
    return out;
}

std::vector<double> sky_wavelengths_nm(const SkySettings& settings) {
    if (settings.spectral_bands > 0)
        return spectral_wavelengths_nm(settings.spectral_bands);
    return settings.rgb_wavelengths_nm;
}

std::shared_ptr<const SkyScene> make_sky_scene(Atmosphere atmosphere, const SunDesc& sun,
                                               const SkySettings& settings) {
    auto sky = std::make_shared<SkyScene>();
    sky->atmosphere = std::move(atmosphere);
    sky->sun = sun;
    sky->settings = settings;
    sky->sun_direction = sun_direction(sun.elevation_deg, sun.azimuth_deg);
    sky->sun_radius_rad = sun.angular_radius_deg * kPiD / 180.0;
    sky->sun_cos_radius = std::cos(sky->sun_radius_rad);
    const int n = sky->atmosphere.bands;
    sky->band_to_rgb.assign(static_cast<size_t>(n), glm::dvec3(0.0));
    if (settings.spectral_bands == 0) {
        // RGB mode: the channels are the bands; a sun of E lux carries E times the Rec.709
        // colour of its spectrum at luminance 1 (lights/sun.h), so its luminance stays E.
        const glm::dvec3 color = sun_rgb_color(sun);
        for (int i = 0; i < 3; ++i)
            sky->band_to_rgb[static_cast<size_t>(i)][i] = sun.illuminance_lux * color[i];
    } else {
        // Spectral mode: E_i = k S(lambda_i) W/(m² nm) with 683 sum_i E_i ybar_i dlambda = E lux,
        // the same sum the conversion uses, so the sun above the atmosphere has exactly E lux.
        const double bin = spectral_bin_nm(n);
        double y_sum = 0.0;
        for (int i = 0; i < n; ++i) {
            const double nm = sky->atmosphere.wavelengths_nm[static_cast<size_t>(i)];
            y_sum += kLuminousEfficacy * sun_relative_spectrum(sun, nm) * cie_1931_cmf(nm).y * bin;
        }
        const double k = y_sum > 0.0 ? sun.illuminance_lux / y_sum : 0.0;
        for (int i = 0; i < n; ++i) {
            const double nm = sky->atmosphere.wavelengths_nm[static_cast<size_t>(i)];
            const double e_i = k * sun_relative_spectrum(sun, nm);
            sky->band_to_rgb[static_cast<size_t>(i)] =
                xyz_to_rec709(kLuminousEfficacy * e_i * bin * cie_1931_cmf(nm));
        }
    }
    return sky;
}

std::shared_ptr<const SkyScene> make_sky_scene(const JsonNode& atmosphere,
                                               const std::optional<JsonNode>& sun,
                                               const SkySettings& settings) {
    const std::vector<double> nm = sky_wavelengths_nm(settings);
    Atmosphere a = parse_atmosphere(atmosphere, nm, settings.rgb_wavelengths_nm);
    const SunDesc s = sun ? parse_sun(*sun) : SunDesc{};
    return make_sky_scene(std::move(a), s, settings);
}

std::string describe_sky(const SkyScene& sky) {
    char buf[320];
    std::snprintf(
        buf, sizeof buf,
        "planet %.0f km / top %.0f km, Rayleigh + Mie + ozone, sun at %.2f deg "
        "elevation, %.1f deg azimuth, %.0f lux at the top; %s; %s mode",
        sky.atmosphere.ground_radius_m * 1e-3, sky.atmosphere.top_radius_m * 1e-3,
        sky.sun.elevation_deg, sky.sun.azimuth_deg, sky.sun.illuminance_lux,
        sky.settings.spectral_bands > 0
            ? (std::to_string(sky.settings.spectral_bands) + " wavelengths 360-830 nm").c_str()
            : "RGB at 3 wavelengths",
        sky_mode_name(sky.settings.mode));
    return buf;
}

std::vector<SkyPlanStage> sky_plan_stages(const SkyScene* sky) {
    if (sky == nullptr) {
        return {{"atmosphere", false, "no \"atmosphere\": no sky, no LUTs"}};
    }
    const SkySettings& s = sky->settings;
    const bool fast = s.mode == SkyMode::Fast;
    std::vector<SkyPlanStage> out;
    out.push_back({"atmosphere", true, describe_sky(*sky)});
    out.push_back(
        {"sky-luts", fast,
         fast ? "transmittance 256x64 and multiple scattering 128x32 by 4 iterated orders "
                "(atmosphere only, built once), sky view 192x108 for this camera altitude and "
                "sun (Hillaire 2020)"
              : "render.sky.mode is \"reference\": no tables"});
    out.push_back(
        {"aerial-perspective", fast && s.aerial_table,
         !fast ? "reference mode: the air in front of surfaces is marched per pixel"
         : s.aerial_table
             ? "camera-frustum table 32x32x32 to 32 km (slices crowded toward the camera), "
               "built per frame, trilinear per camera ray (phases per pixel); beyond 32 km "
               "and for secondary rays marched per pixel from the tables"
             : "render.sky.aerial_perspective is \"march\": marched per pixel from the tables"});
    out.push_back({"sky-reference", !fast,
                   !fast ? "ray marching in double precision, " + std::to_string(s.view_steps) +
                               " view nodes, " + std::to_string(s.sun_steps) + " sun nodes, " +
                               std::to_string(s.orders) +
                               " scattering orders (orders > 1 by Monte Carlo paths)"
                         : "fast mode: the reference integrator is not used"});
    out.push_back({"sky-light", true,
                   "sun through the air as a directional light (transmittance at the origin); "
                   "sky + ground irradiance table (16x32 normals, no occlusion) on diffuse "
                   "surfaces; sky as background, aerial perspective in front of surfaces"});
    return out;
}

}  // namespace kasumi
