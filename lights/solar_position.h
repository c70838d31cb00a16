#pragma once
/// The sun's position in the sky from latitude, longitude and a UTC instant, by the NOAA solar
/// calculator algorithm (NOAA Global Monitoring Laboratory, "Solar Calculation Details" and its
/// spreadsheet NOAA_Solar_Calculations_day.xls), itself the low-accuracy method of J. Meeus,
/// "Astronomical Algorithms" (2nd ed., 1998), chapters 25 and 28. Stated accuracy: about 1
/// minute of time and 0.01° for years 1800-2100 at latitudes within ±72°.
#include <optional>
#include <string>

namespace kasumi {

/// A UTC instant as a Julian Day (days since noon UTC, 1 January 4713 BC, proleptic Julian).
struct JulianDay {
    double day = 0.0;
};

/// Julian Day of a Gregorian calendar date and UTC time (Meeus eq. 7.1).
JulianDay julian_day(int year, int month, int day, double hours_utc);

/// Parses an ISO 8601 date-time with an explicit zone: "2026-06-21T12:00:00Z",
/// "2026-06-21T14:30+02:00" (seconds optional, fractions allowed). Empty on malformed text.
std::optional<JulianDay> parse_iso8601(const std::string& text);

struct SolarPosition {
    double declination_deg = 0.0;         ///< apparent declination of the sun
    double equation_of_time_min = 0.0;    ///< apparent minus mean solar time, minutes
    double hour_angle_deg = 0.0;          ///< 0 at local solar noon, positive afternoon
    double elevation_deg = 0.0;           ///< geometric (no refraction), above the horizon
    double azimuth_deg = 0.0;             ///< clockwise from north: 90 east, 180 south
    double refraction_deg = 0.0;          ///< NOAA's approximate atmospheric refraction
    double apparent_elevation_deg = 0.0;  ///< elevation_deg + refraction_deg
};

/// Sun position seen from latitude_deg (north positive) and longitude_deg (east positive) at
/// the UTC instant `when`.
SolarPosition solar_position(double latitude_deg, double longitude_deg, JulianDay when);

}  // namespace kasumi
