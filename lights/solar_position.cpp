#include "lights/solar_position.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace kasumi {

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

double wrap360(double a) {
    a = std::fmod(a, 360.0);
    return a < 0.0 ? a + 360.0 : a;
}

}  // namespace

JulianDay julian_day(int year, int month, int day, double hours_utc) {
    // Meeus eq. 7.1 with the Gregorian correction B.
    if (month <= 2) {
        year -= 1;
        month += 12;
    }
    const int a = year / 100;
    const int b = 2 - a + a / 4;
    const double jd = std::floor(365.25 * (year + 4716)) + std::floor(30.6001 * (month + 1)) + day +
                      b - 1524.5 + hours_utc / 24.0;
    return JulianDay{jd};
}

std::optional<JulianDay> parse_iso8601(const std::string& text) {
    int year = 0, month = 0, day = 0, hour = 0, minute = 0, consumed = 0;
    if (std::sscanf(text.c_str(), "%4d-%2d-%2dT%2d:%2d%n", &year, &month, &day, &hour, &minute,
                    &consumed) != 5)
        return std::nullopt;
    size_t pos = static_cast<size_t>(consumed);
    double seconds = 0.0;
    if (pos < text.size() && text[pos] == ':') {
        int n = 0;
        if (std::sscanf(text.c_str() + pos + 1, "%lf%n", &seconds, &n) != 1 || seconds < 0.0 ||
            seconds >= 61.0)
            return std::nullopt;
        pos += 1 + static_cast<size_t>(n);
    }
    double offset_h = 0.0;
    if (pos < text.size() && text[pos] == 'Z' && pos + 1 == text.size()) {
        offset_h = 0.0;
    } else if (pos < text.size() && (text[pos] == '+' || text[pos] == '-')) {
        int oh = 0, om = 0, n = 0;
        if (std::sscanf(text.c_str() + pos + 1, "%2d:%2d%n", &oh, &om, &n) != 2 ||
            pos + 1 + static_cast<size_t>(n) != text.size() || oh > 14 || om > 59)
            return std::nullopt;
        offset_h = (text[pos] == '-' ? -1.0 : 1.0) * (oh + om / 60.0);
    } else {
        return std::nullopt;
    }
    if (month < 1 || month > 12 || day < 1 || day > 31 || hour > 24 || minute > 59)
        return std::nullopt;
    const double hours_utc = hour + minute / 60.0 + seconds / 3600.0 - offset_h;
    return julian_day(year, month, day, hours_utc);
}

SolarPosition solar_position(double latitude_deg, double longitude_deg, JulianDay when) {
    // Column names of the NOAA spreadsheet in comments; angles in degrees.
    const double jc = (when.day - 2451545.0) / 36525.0;                          // Julian century
    const double l0 = wrap360(280.46646 + jc * (36000.76983 + jc * 0.0003032));  // geom mean long
    const double m = 357.52911 + jc * (35999.05029 - 0.0001537 * jc);       // geom mean anomaly
    const double e = 0.016708634 - jc * (0.000042037 + 0.0000001267 * jc);  // eccentricity
    const double c = std::sin(m * kDeg) * (1.914602 - jc * (0.004817 + 0.000014 * jc)) +
                     std::sin(2.0 * m * kDeg) * (0.019993 - 0.000101 * jc) +
                     std::sin(3.0 * m * kDeg) * 0.000289;  // equation of centre
    const double true_long = l0 + c;
    const double omega = 125.04 - 1934.136 * jc;
    const double app_long = true_long - 0.00569 - 0.00478 * std::sin(omega * kDeg);
    const double obliq_mean =
        23.0 + (26.0 + (21.448 - jc * (46.815 + jc * (0.00059 - jc * 0.001813))) / 60.0) / 60.0;
    const double obliq = obliq_mean + 0.00256 * std::cos(omega * kDeg);
    SolarPosition out;
    out.declination_deg = std::asin(std::sin(obliq * kDeg) * std::sin(app_long * kDeg)) / kDeg;
    // Equation of time (Smart 1956; Meeus eq. 28.3), minutes.
    const double y = std::pow(std::tan(obliq * kDeg / 2.0), 2);
    const double eot_rad = y * std::sin(2.0 * l0 * kDeg) - 2.0 * e * std::sin(m * kDeg) +
                           4.0 * e * y * std::sin(m * kDeg) * std::cos(2.0 * l0 * kDeg) -
                           0.5 * y * y * std::sin(4.0 * l0 * kDeg) -
                           1.25 * e * e * std::sin(2.0 * m * kDeg);
    out.equation_of_time_min = 4.0 * eot_rad / kDeg;
    // True solar time from the UTC time of day (the spreadsheet's time zone term cancels).
    const double day_fraction = std::fmod(when.day + 0.5, 1.0);
    const double tst = std::fmod(
        day_fraction * 1440.0 + out.equation_of_time_min + 4.0 * longitude_deg + 1440.0 * 2.0,
        1440.0);
    out.hour_angle_deg = tst / 4.0 < 0.0 ? tst / 4.0 + 180.0 : tst / 4.0 - 180.0;
    const double lat = latitude_deg * kDeg, dec = out.declination_deg * kDeg;
    const double cos_zenith =
        std::clamp(std::sin(lat) * std::sin(dec) +
                       std::cos(lat) * std::cos(dec) * std::cos(out.hour_angle_deg * kDeg),
                   -1.0, 1.0);
    const double zenith = std::acos(cos_zenith);
    out.elevation_deg = 90.0 - zenith / kDeg;
    const double denom = std::cos(lat) * std::sin(zenith);
    double az_core = 0.0;
    if (std::abs(denom) > 1e-12) {
        az_core =
            std::acos(std::clamp((std::sin(lat) * cos_zenith - std::sin(dec)) / denom, -1.0, 1.0)) /
            kDeg;
    }
    out.azimuth_deg =
        out.hour_angle_deg > 0.0 ? wrap360(az_core + 180.0) : wrap360(540.0 - az_core);
    // NOAA's refraction approximation (Saemundsson-like piecewise fit), degrees.
    const double h = out.elevation_deg;
    double refraction_arcsec = 0.0;
    if (h > 85.0) {
        refraction_arcsec = 0.0;
    } else if (h > 5.0) {
        const double t = std::tan(h * kDeg);
        refraction_arcsec = 58.1 / t - 0.07 / (t * t * t) + 0.000086 / std::pow(t, 5);
    } else if (h > -0.575) {
        refraction_arcsec = 1735.0 + h * (-518.2 + h * (103.4 + h * (-12.79 + h * 0.711)));
    } else {
        refraction_arcsec = -20.772 / std::tan(h * kDeg);
    }
    out.refraction_deg = refraction_arcsec / 3600.0;
    out.apparent_elevation_deg = out.elevation_deg + out.refraction_deg;
    return out;
}

}  // namespace kasumi
