#pragma once
/// Extinction from a meteorological visibility (Koschmieder's law), for fog given the way
/// weather reports give it.
///
/// A black object seen against the horizon sky through a horizontal, uniformly lit homogeneous
/// medium keeps the apparent contrast C(d) = -exp(-sigma_t d) at distance d (the airlight
/// fills in its darkness exactly as it replaces the sky's attenuated light). The visibility V is
/// the distance at which |C| falls to the observer's contrast threshold eps, so
/// sigma_t = -ln(eps) / V (H. Koschmieder 1924, "Theorie der horizontalen Sichtweite",
/// Beiträge zur Physik der freien Atmosphäre 12, 33-53 and 171-181). |C(d)| equals the
/// transmittance exp(-sigma_t d), so V is also the path over which the medium passes eps of a
/// beam.
#include <cmath>

namespace kasumi {

/// Koschmieder's threshold, eps = 0.02: sigma_t = 3.912 / V.
inline constexpr double kKoschmiederContrastThreshold = 0.02;

/// The WMO meteorological optical range (MOR): the path that reduces a collimated beam of a
/// 2700 K lamp to 5% of its flux, eps = 0.05: sigma_t = 2.996 / V (WMO-No. 8, Guide to
/// Instruments and Methods of Observation, Vol. I, ch. 9, "Measurement of visibility"). The
/// visibility of weather reports (SYNOP, METAR) and of WMO's definition of fog (< 1 km) is MOR.
inline constexpr double kMorContrastThreshold = 0.05;

/// Extinction coefficient sigma_t = -ln(eps) / V in 1/m for a visibility V > 0 in metres and a
/// contrast threshold eps in (0, 1) (callers check the ranges).
inline double extinction_from_visibility(double visibility_m, double contrast_threshold) {
    return -std::log(contrast_threshold) / visibility_m;
}

}  // namespace kasumi
