#include "lights/sun.h"

#include "core/cie_1931.h"
#include "core/error.h"
#include "core/reference_spectra.h"
#include "core/spectrum.h"
#include "core/wavelength_table_json.h"
#include "lights/solar_position.h"

namespace kasumi {

DVec3 sun_direction(double elevation_deg, double azimuth_deg) {
    const double e = elevation_deg * kPiD / 180.0, a = azimuth_deg * kPiD / 180.0;
    return DVec3(std::cos(e) * std::sin(a), std::sin(e), -std::cos(e) * std::cos(a));
}

namespace {

double limb_alpha(double lambda_nm) {
    return -0.023 + 0.292 / (lambda_nm * 1e-3);
}

}  // namespace

double sun_limb_darkening(double lambda_nm, double mu) {
    return mu > 0.0 ? std::pow(mu, limb_alpha(lambda_nm)) : 0.0;
}

double sun_limb_darkening_mean(double lambda_nm) {
    return 2.0 / (2.0 + limb_alpha(lambda_nm));
}

double sun_relative_spectrum(const SunDesc& sun, double lambda_nm) {
    switch (sun.spectrum) {
        case SunSpectrum::Blackbody:
            return planck_radiance(lambda_nm, sun.blackbody_k);
        case SunSpectrum::Table:
            return sun.spectrum_table.at(lambda_nm);
        case SunSpectrum::AstmG173:
            break;
    }
    return solar_irradiance_astm_g173().at(lambda_nm);
}

glm::dvec3 sun_rgb_color(const SunDesc& sun) {
    double lo = kCieFirstNm, hi = kCieFirstNm + kCieStepNm * (kCieSamples - 1);
    if (sun.spectrum == SunSpectrum::Table) {
        lo = std::max(lo, sun.spectrum_table.min_nm());
        hi = std::min(hi, sun.spectrum_table.max_nm());
    }
    // Trapezoid rule on a 1 nm grid (the tables are linear between 5 and 10 nm rows).
    const int n = std::max(1, static_cast<int>(std::ceil(hi - lo)));
    const double step = (hi - lo) / n;
    glm::dvec3 xyz(0.0);
    for (int i = 0; i <= n; ++i) {
        const double nm = lo + step * i;
        const double w = (i == 0 || i == n) ? 0.5 : 1.0;
        xyz += w * sun_relative_spectrum(sun, nm) * cie_1931_cmf(nm);
    }
    if (!(hi > lo) || !(xyz.y > 0.0))
        throw_input_error("the sun's spectrum has no luminance between 360 and 830 nm");
    return xyz_to_rec709(xyz / xyz.y);
}

SunDesc parse_sun(const JsonNode& node) {
    JsonObjectReader reader(node);
    SunDesc sun;
    const auto elevation = reader.optional("elevation_deg");
    const auto azimuth = reader.optional("azimuth_deg");
    const auto latitude = reader.optional("latitude_deg");
    const auto longitude = reader.optional("longitude_deg");
    const auto datetime = reader.optional("datetime");
    if (latitude || longitude || datetime) {
        if (elevation || azimuth)
            node.fail(
                "give elevation_deg/azimuth_deg or latitude_deg/longitude_deg/datetime, not both");
        if (!latitude || !longitude || !datetime)
            node.fail("latitude_deg, longitude_deg and datetime go together");
        const double lat = latitude->as_double();
        if (!(lat >= -90.0 && lat <= 90.0))
            latitude->fail("must be in [-90, 90] degrees");
        const double lon = longitude->as_double();
        if (!(lon >= -180.0 && lon <= 360.0))
            longitude->fail("must be in [-180, 360] degrees (east positive)");
        sun.datetime = datetime->as_string();
        const auto jd = parse_iso8601(sun.datetime);
        if (!jd)
            datetime->fail("expected ISO 8601 with a zone, e.g. \"2026-06-21T18:30:00+02:00\"");
        const SolarPosition pos = solar_position(lat, lon, *jd);
        sun.elevation_deg = pos.elevation_deg;
        sun.azimuth_deg = pos.azimuth_deg;
    } else {
        if (elevation) {
            sun.elevation_deg = elevation->as_double();
            if (!(sun.elevation_deg >= -90.0 && sun.elevation_deg <= 90.0))
                elevation->fail("must be in [-90, 90] degrees");
        }
        if (azimuth)
            sun.azimuth_deg = azimuth->as_double();
    }
    const auto lux = reader.optional("illuminance_lux");
    if (lux)
        sun.illuminance_lux = lux->non_negative();
    if (const auto spectrum = reader.optional("spectrum")) {
        if (spectrum->is_string() && spectrum->as_string() == "astm_g173") {
            sun.spectrum = SunSpectrum::AstmG173;
        } else if (spectrum->is_string() && spectrum->as_string() == "blackbody") {
            sun.spectrum = SunSpectrum::Blackbody;
        } else if (spectrum->is_object()) {
            JsonObjectReader r(*spectrum);
            const JsonNode t = r.required("blackbody_K");
            r.finish();
            sun.blackbody_k = t.as_double();
            if (!(sun.blackbody_k >= 1000.0 && sun.blackbody_k <= 100000.0))
                t.fail("must be in [1000, 100000] K");
            sun.spectrum = SunSpectrum::Blackbody;
        } else if (is_wavelength_table(*spectrum)) {
            sun.spectrum_table = read_wavelength_table(*spectrum);
            sun.spectrum = SunSpectrum::Table;
        } else {
            spectrum->fail(
                "expected \"astm_g173\", \"blackbody\", {\"blackbody_K\": T}, a CSV file path "
                "or [[wavelength_nm, value], ...]");
        }
    }
    if (const auto r = reader.optional("angular_radius_deg"))
        sun.angular_radius_deg = r->in_open(0.0f, 10.0f);
    reader.optional("comment");
    reader.finish();
    return sun;
}

}  // namespace kasumi
