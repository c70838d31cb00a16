#include "lights/sun.h"

#include "core/spectrum.h"
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
    const auto& t = sun.spectrum;
    if (t.empty())
        return planck_radiance(lambda_nm, kSunTemperatureK);
    if (lambda_nm <= t.front().first)
        return t.front().second;
    if (lambda_nm >= t.back().first)
        return t.back().second;
    size_t i = 1;
    while (t[i].first < lambda_nm)
        ++i;
    const double f = (lambda_nm - t[i - 1].first) / (t[i].first - t[i - 1].first);
    return t[i - 1].second + f * (t[i].second - t[i - 1].second);
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
        double last = 0.0;
        for (const JsonNode& row : spectrum->elements()) {
            if (!row.is_array() || row.size() != 2)
                row.fail("expected [wavelength_nm, value]");
            const double nm = row.child(size_t{0}).as_double();
            const double v = row.child(size_t{1}).as_double();
            if (!(nm > last))
                row.fail("wavelengths must increase");
            if (!(v >= 0.0))
                row.fail("value must be >= 0");
            sun.spectrum.emplace_back(nm, v);
            last = nm;
        }
        if (sun.spectrum.size() < 2)
            spectrum->fail("needs at least two rows");
    }
    if (const auto r = reader.optional("angular_radius_deg"))
        sun.angular_radius_deg = r->in_open(0.0f, 10.0f);
    reader.optional("comment");
    reader.finish();
    return sun;
}

}  // namespace kasumi
