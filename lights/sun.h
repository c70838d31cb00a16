#pragma once
/// The sun: a directional light with an angular radius, a limb-darkened disc and a spectrum.
/// `illuminance_lux` is the illuminance at the top of the atmosphere on a surface facing the
/// sun; the atmosphere (volume/sky_scene.h) attenuates it on the way down.
/// Directions: +y up, azimuth clockwise from north with north = -z and east = +x.
#include "core/json_node.h"
#include "core/math.h"

#include <utility>
#include <vector>

namespace kasumi {

/// Solar illuminance constant commonly quoted for the top of the atmosphere, lux (128 klx;
/// Darula, Kittler & Gueymard 2005, Solar Energy 79, 559, revise it to 133.8 klx).
inline constexpr double kSolarIlluminanceLux = 128000.0;
/// Mean angular radius of the solar disc seen from Earth, degrees (959.63 arcsec at 1 au).
inline constexpr double kSunAngularRadiusDeg = 0.26656;
/// Nominal effective temperature of the sun, K (IAU 2015 Resolution B3): the default shape of
/// the spectrum in spectral mode.
inline constexpr double kSunTemperatureK = 5772.0;

struct SunDesc {
    double elevation_deg = 45.0;  ///< geometric elevation above the horizon
    double azimuth_deg = 180.0;   ///< clockwise from north
    double illuminance_lux = kSolarIlluminanceLux;
    double angular_radius_deg = kSunAngularRadiusDeg;
    /// Relative spectral irradiance (nm, any unit) for spectral mode; empty: black body.
    std::vector<std::pair<double, double>> spectrum;
    std::string datetime;  ///< when the position came from latitude/longitude/datetime
};

/// Unit vector toward the sun.
DVec3 sun_direction(double elevation_deg, double azimuth_deg);

/// Limb darkening I(mu) / I(disc centre) at cosine mu of the angle between the line of sight
/// and the solar surface normal: mu^alpha with alpha = -0.023 + 0.292 / lambda_um (Hestroffer &
/// Magnan 1998, A&A 333, 338, their eq. 8 fitted to Neckel & Labs 1994 between 0.3 and 1.1 µm).
double sun_limb_darkening(double lambda_nm, double mu);

/// Mean of sun_limb_darkening over the disc (by area): 2 / (2 + alpha).
double sun_limb_darkening_mean(double lambda_nm);

/// Relative spectral irradiance of the sun at lambda_nm: the table if given (linear, clamped),
/// else Planck's law at kSunTemperatureK.
double sun_relative_spectrum(const SunDesc& sun, double lambda_nm);

/// Parses a "sun" object; errors name the file and JSON path.
SunDesc parse_sun(const JsonNode& node);

}  // namespace kasumi
