#pragma once
/// Colour conventions. The working space is scene-linear Rec.709 (sRGB primaries, D65 white).
/// Radiometric quantities carried as Rgb are *photometrically scaled*: their Rec.709 luminance
/// Y = 0.2126 R + 0.7152 G + 0.0722 B is the photometric quantity (cd/m² for radiance, lux for
/// irradiance, cd for intensity). A white light of E lux therefore carries Rgb(E, E, E).
#include "core/math.h"

namespace kasumi {

using Rgb = glm::vec3;

/// Rec.709 / sRGB luminance weights (ITU-R BT.709-6, Table 3 item 3.2).
inline constexpr float kLumaR = 0.2126f;
inline constexpr float kLumaG = 0.7152f;
inline constexpr float kLumaB = 0.0722f;

inline float luminance(const Rgb& c) {
    return kLumaR * c.r + kLumaG * c.g + kLumaB * c.b;
}

inline bool is_black(const Rgb& c) {
    return c.r == 0.0f && c.g == 0.0f && c.b == 0.0f;
}

inline float max_component(const Rgb& c) {
    return std::max(c.r, std::max(c.g, c.b));
}

/// Exp of each channel: Beer-Lambert transmittance from an optical depth per channel.
inline Rgb exp_neg(const Rgb& tau) {
    return Rgb(std::exp(-tau.r), std::exp(-tau.g), std::exp(-tau.b));
}

/// Rec.709 primaries and D65 white point as CIE xy chromaticities (for EXR metadata).
struct Chromaticities {
    float red_x = 0.64f, red_y = 0.33f;
    float green_x = 0.30f, green_y = 0.60f;
    float blue_x = 0.15f, blue_y = 0.06f;
    float white_x = 0.3127f, white_y = 0.3290f;
};

}  // namespace kasumi
