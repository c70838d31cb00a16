#pragma once
/// An atmosphere lit by the sun, at the wavelengths the render transports, with the linear map
/// from per-wavelength radiance to the working RGB. Radiance inside the sky code is "per unit
/// solar irradiance at the top of the atmosphere" (1/sr) per band; to_rgb() scales it by the
/// sun's spectral irradiance and converts it to Rec.709 whose luminance is in cd/m².
#include "core/color.h"
#include "core/json_node.h"
#include "lights/sun.h"
#include "sky/atmosphere.h"
#include "sky/sky_settings.h"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace kasumi {

struct SkyScene {
    Atmosphere atmosphere;
    SunDesc sun;
    SkySettings settings;
    DVec3 sun_direction{0.0, 1.0, 0.0};  ///< unit, toward the sun
    double sun_radius_rad = 0.0;
    double sun_cos_radius = 1.0;
    /// radiance_rgb = sum_i band_to_rgb[i] * radiance_i (radiance_i per unit TOA irradiance).
    std::vector<glm::dvec3> band_to_rgb;

    int bands() const { return atmosphere.bands; }
    Rgb to_rgb(const Bands& per_unit_irradiance) const;
    /// Radiance of the sun's disc per unit irradiance at angular distance `cos_angle` from its
    /// centre (limb-darkened, normalised so the disc integrates to 1); zero outside.
    Bands sun_disc(double cos_angle) const;
};

/// Builds the sky from the scene's "atmosphere" and optional "sun" objects.
std::shared_ptr<const SkyScene> make_sky_scene(const JsonNode& atmosphere,
                                               const std::optional<JsonNode>& sun,
                                               const SkySettings& settings);

/// The same from values (tests, tools).
std::shared_ptr<const SkyScene> make_sky_scene(Atmosphere atmosphere, const SunDesc& sun,
                                               const SkySettings& settings);

/// The wavelengths the settings call for: the RGB triple, or N spectral bins.
std::vector<double> sky_wavelengths_nm(const SkySettings& settings);

/// One line for the plan: the atmosphere, the sun and how the sky is computed.
std::string describe_sky(const SkyScene& sky);

struct SkyPlanStage {
    std::string name;
    bool enabled = false;
    std::string reason;
};

/// The plan's sky stages (atmosphere, tables, sky light), each with why it runs or not;
/// `sky` null: no atmosphere.
std::vector<SkyPlanStage> sky_plan_stages(const SkyScene* sky);

}  // namespace kasumi
