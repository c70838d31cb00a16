// The NOAA solar position algorithm against Meeus's worked examples, and the sun's disc.
#include "lights/solar_position.h"
#include "lights/sun.h"

#include <gtest/gtest.h>

#include <cmath>

namespace kasumi {
namespace {

TEST(SolarPosition, JulianDayOfMeeusExample7a) {
    // Meeus, Astronomical Algorithms (2nd ed.), Example 7.a: 1957 October 4.81 = JD 2436116.31.
    EXPECT_NEAR(julian_day(1957, 10, 4, 0.81 * 24.0).day, 2436116.31, 1e-6);
    // Example 7.b: 333 January 27.5 is Julian-calendar; the J2000 epoch is exact instead.
    EXPECT_NEAR(julian_day(2000, 1, 1, 12.0).day, 2451545.0, 1e-9);
}

TEST(SolarPosition, DeclinationAndEquationOfTimeOfMeeusExamples) {
    // Meeus Example 25.a (1992 October 13.0 TD, low-accuracy method, as NOAA's): apparent
    // declination -7°47'06" = -7.78507°. Example 28.b (Smart's formula, as NOAA's): equation of
    // time +13m42.7s = 13.712 min. (TD - UT ~ 1 min in 1992 moves neither by the tolerance.)
    const SolarPosition s = solar_position(0.0, 0.0, julian_day(1992, 10, 13, 0.0));
    EXPECT_NEAR(s.declination_deg, -7.78507, 3e-4);
    EXPECT_NEAR(s.equation_of_time_min, 13.712, 0.01);
}

TEST(SolarPosition, NrelSpaReferenceExample) {
    // Reda & Andreas, "Solar Position Algorithm for Solar Radiation Applications" (NREL/TP-560-
    // 34302, 2004/2008), the example of its Table A5.1/A5.2 and of spa_tester.c: 2003 October 17,
    // 12:30:30 local time at UTC-7, latitude 39.742476°, longitude -105.1786°, 1830.14 m, 820 mbar,
    // 11 °C. Published: JD 2452930.312847, declination -9.31434° (geocentric), observer hour angle
    // 11.105902°, topocentric zenith angle 50.111622° (refracted) and azimuth 194.340241°.
    // NOAA's low-accuracy method is good to ~0.01° (1800-2100); its refraction is for sea level
    // (0.0193° here, SPA's 0.0163° at 820 mbar) and it has no parallax (0.0019°): both move the
    // zenith by less than the 0.01° allowed. A swapped azimuth branch, a sign error in the hour
    // angle or a wrong time zone moves these by degrees.
    const auto when = parse_iso8601("2003-10-17T12:30:30-07:00");
    ASSERT_TRUE(when.has_value());
    EXPECT_NEAR(when->day, 2452930.312847, 1e-6);
    const SolarPosition s = solar_position(39.742476, -105.1786, *when);
    EXPECT_NEAR(s.declination_deg, -9.31434, 0.005);
    EXPECT_NEAR(s.hour_angle_deg, 11.105902, 0.01);
    EXPECT_NEAR(90.0 - s.apparent_elevation_deg, 50.111622, 0.01);
    EXPECT_NEAR(s.azimuth_deg, 194.340241, 0.01);
}

TEST(SolarPosition, SolarNoonElevationAndAzimuth) {
    // At true solar noon (UTC 12:00 - 4 min/deg east longitude - equation of time) the sun
    // stands on the meridian: hour angle 0, elevation 90 - |lat - dec|, azimuth 180 north of the
    // sun's declination and 0 south of it.
    for (const double lat : {52.0, -33.9}) {
        const double lon = 13.4;
        const JulianDay day = julian_day(2026, 6, 21, 12.0);
        const SolarPosition approx = solar_position(lat, lon, day);
        const double noon_h = (720.0 - 4.0 * lon - approx.equation_of_time_min) / 60.0;
        const SolarPosition s = solar_position(lat, lon, julian_day(2026, 6, 21, noon_h));
        EXPECT_NEAR(s.hour_angle_deg, 0.0, 0.01);
        EXPECT_NEAR(s.elevation_deg, 90.0 - std::abs(lat - s.declination_deg), 0.01);
        EXPECT_NEAR(std::remainder(s.azimuth_deg - (lat > s.declination_deg ? 180.0 : 0.0), 360.0),
                    0.0, 0.5);
        EXPECT_NEAR(s.declination_deg, 23.44, 0.01);  // June solstice
    }
}

TEST(SolarPosition, MorningSunRisesInTheEastAfternoonSetsInTheWest) {
    const SolarPosition morning = solar_position(48.0, 2.35, julian_day(2026, 3, 20, 7.0));
    const SolarPosition evening = solar_position(48.0, 2.35, julian_day(2026, 3, 20, 17.0));
    EXPECT_GT(morning.azimuth_deg, 60.0);
    EXPECT_LT(morning.azimuth_deg, 120.0);
    EXPECT_GT(evening.azimuth_deg, 240.0);
    EXPECT_LT(evening.azimuth_deg, 300.0);
    EXPECT_LT(morning.hour_angle_deg, 0.0);
    EXPECT_GT(evening.hour_angle_deg, 0.0);
}

TEST(SolarPosition, Iso8601WithZones) {
    const auto a = parse_iso8601("2026-06-21T14:30:00+02:00");
    const auto b = parse_iso8601("2026-06-21T12:30Z");
    ASSERT_TRUE(a && b);
    EXPECT_NEAR(a->day, b->day, 1e-9);
    EXPECT_FALSE(parse_iso8601("2026-06-21T12:30:00"));  // no zone: ambiguous
    EXPECT_FALSE(parse_iso8601("2026-13-01T00:00Z"));
    EXPECT_FALSE(parse_iso8601("noon"));
}

TEST(Sun, DirectionConvention) {
    const DVec3 east = sun_direction(0.0, 90.0);
    EXPECT_NEAR(east.x, 1.0, 1e-12);
    const DVec3 north = sun_direction(0.0, 0.0);
    EXPECT_NEAR(north.z, -1.0, 1e-12);
    EXPECT_NEAR(sun_direction(90.0, 33.0).y, 1.0, 1e-12);
}

TEST(Sun, LimbDarkeningMeanIsTheDiscAverage) {
    // 2 / (2 + alpha) against the area average of mu^alpha over the disc by quadrature.
    for (const double nm : {400.0, 550.0, 800.0}) {
        const int n = 20000;
        double sum = 0.0;
        for (int k = 0; k < n; ++k) {
            const double r = (k + 0.5) / n;
            sum += sun_limb_darkening(nm, std::sqrt(1.0 - r * r)) * 2.0 * r / n;
        }
        EXPECT_NEAR(sum, sun_limb_darkening_mean(nm), 1e-4) << nm;
        // The limb is darker in the blue (Neckel & Labs): ~0.3 at 400 nm at mu = 0.1.
        EXPECT_LT(sun_limb_darkening(nm, 0.1), 0.5);
    }
    EXPECT_LT(sun_limb_darkening(400.0, 0.3), sun_limb_darkening(800.0, 0.3));
}

}  // namespace
}  // namespace kasumi
