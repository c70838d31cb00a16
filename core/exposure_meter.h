#pragma once
/// Exposure metering of a scene-linear frame on its log-average luminance (Reinhard, Stark,
/// Shirley & Ferwerda 2002, "Photographic tone reproduction for digital images", eq. 1 and 2):
/// the exposure maps the log-average luminance to the key, middle grey 0.18, before the
/// display view (core/color_management.h). Luminance Y is Rec.709's, in cd/m2 (core/color.h).
#include <cstddef>

namespace kasumi {

/// Middle grey: the scene-linear value the metered luminance is exposed to.
inline constexpr double kExposureKey = 0.18;
/// The delta of Reinhard's eq. 1, in cd/m2: keeps log(Y) finite on black pixels and bounds
/// what darkness can ask of the exposure (about starlight on snow, far below twilight).
inline constexpr double kMeterDeltaCdM2 = 1e-4;
/// The range metered exposures are clamped to, in stops: -24 exposes 0.18 * 2^24 ~ 3e6 cd/m2
/// (beyond the sun-lit sky, ~1e4), +12 the delta itself (0.18 * 2^-12 ~ 4.4e-5 cd/m2).
inline constexpr float kAutoExposureMinStops = -24.0f;
inline constexpr float kAutoExposureMaxStops = 12.0f;

/// log2 of the log-average luminance, log2(exp(mean(ln(delta + Y)))) with Y = max(0, Rec.709
/// luminance of r, g, b) in cd/m2, over the `pixels` pixels whose Y is finite (non-finite
/// ones are left out); a frame without a finite pixel meters as black: log2(delta).
double log2_average_luminance(const float* r, const float* g, const float* b, size_t pixels);

/// The exposure in stops that takes a frame of log2 luminance `log2_luminance` to the key:
/// log2(key) - log2_luminance, clamped to [kAutoExposureMinStops, kAutoExposureMaxStops].
float metered_exposure_stops(double log2_luminance);

}  // namespace kasumi
