#pragma once
/// The sun: a directional light with an angular radius, a limb-darkened disc and a spectrum.
/// `illuminance_lux` is the illuminance at the top of the atmosphere on a surface facing the
/// sun; the atmosphere (sky/sky_scene.h) attenuates it on the way down.
/// Directions: +y up, azimuth clockwise from north with north = -z and east = +x.
#include "core/csv_table.h"
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
/// Nominal effective temperature of the sun, K (IAU 2015 Resolution B3): the black body of
/// `"spectrum": "blackbody"`.
inline constexpr double kSunTemperatureK = 5772.0;

/// The shape of the sun's spectrum: the measured extraterrestrial table (default), a black
/// body, or a table from the scene.
enum class SunSpectrum {
    AstmG173,   ///< ASTM G173-03 ETR, 10 nm bins (core/reference_spectra.h)
    Blackbody,  ///< Planck's law at SunDesc::blackbody_k
    Table,      ///< SunDesc::spectrum_table
};

struct SunDesc {
    double elevation_deg = 45.0;  ///< geometric elevation above the horizon
    double azimuth_deg = 180.0;   ///< clockwise from north
    double illuminance_lux = kSolarIlluminanceLux;
    double angular_radius_deg = kSunAngularRadiusDeg;
    SunSpectrum spectrum = SunSpectrum::AstmG173;
    double blackbody_k = kSunTemperatureK;  ///< for SunSpectrum::Blackbody
    WavelengthTable spectrum_table;         ///< relative irradiance, for SunSpectrum::Table
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

/// Relative spectral irradiance of the sun at lambda_nm (any unit: the scale is set by
/// illuminance_lux): the built-in ASTM table or a scene table, linear between rows (an input
/// error outside the table's range, naming the table), or Planck's law.
double sun_relative_spectrum(const SunDesc& sun, double lambda_nm);

/// Colour of the sun's spectrum in linear Rec.709 with luminance 1: the CIE 1931 integral of
/// the spectrum over 360-830 nm (where the spectrum is defined), divided by its Y. RGB mode
/// gives the sun's three channels these weights times illuminance_lux.
glm::dvec3 sun_rgb_color(const SunDesc& sun);

/// Parses a "sun" object; errors name the file and JSON path.
SunDesc parse_sun(const JsonNode& node);

}  // namespace kasumi
