#pragma once
/// Luminous intensity distributions read from IES LM-63 photometric files ("Standard File Format
/// for the Electronic Transfer of Photometric Data"), every published revision: LM-63-1986 (no
/// format line), LM-63-1991 (`IESNA91`), LM-63-1995, LM-63-2002 and LM-63-2019; photometric
/// type C; TILT=NONE, INCLUDE or a tilt file.
#include "core/math.h"

#include <string>
#include <vector>

namespace kasumi {

/// Lamp output multipliers against the luminaire's tilt (the TILT=INCLUDE block or a tilt file):
/// <lamp-to-luminaire geometry> <number of pairs> <angles> <multiplying factors>.
struct IesTilt {
    /// 0 for TILT=NONE; 1 lamp vertical (base up or down) with the luminaire aimed straight down,
    /// 2 lamp horizontal and staying horizontal as the luminaire tilts, 3 lamp horizontal and
    /// tilting with the luminaire.
    int geometry = 0;
    std::vector<float> angle_deg;   ///< increasing, in [0°, 180°]
    std::vector<float> multiplier;  ///< >= 0, one per angle
    std::string source;             ///< "INCLUDE" or the tilt file's path
};

/// A type C candela table over vertical angle γ (0° = nadir, 180° = zenith) and horizontal
/// angle C (0° along the luminaire's +x, 90° along its +y, counter-clockwise seen from above),
/// expanded from the file's symmetry to C in [0°, 360°].
struct IesProfile {
    std::string file;
    std::string format;  ///< "LM-63-1986", "LM-63-1991", "LM-63-1995", "LM-63-2002" or "LM-63-2019"
    std::vector<float> vertical_deg;    ///< increasing; starts at 0 or 90, ends at 90 or 180
    std::vector<float> horizontal_deg;  ///< increasing from 0 to 360
    /// candela[h * vertical_deg.size() + v], with the candela multiplier and ballast factors
    /// applied.
    std::vector<float> candela;
    /// Lamps × lumens per lamp as the file states them; negative for absolute photometry
    /// (LM-63-2002 writes −1), where the file states no lamp lumens.
    double file_lumens = -1.0;
    float max_candela = 0.0f;
    /// The file's tilt data; the table above does not include it (it depends on the luminaire's
    /// orientation in the scene: `ies_tilt_multiplier`).
    IesTilt tilt;
};

/// Parses LM-63 text. Input errors read "FILE:LINE: what is wrong".
IesProfile parse_ies(const std::string& text, const std::string& file);
/// Reads and parses an LM-63 file.
IesProfile read_ies(const std::string& path);

/// The tilt multiplier for a luminaire tilted by `tilt_deg` from aiming straight down (the angle
/// between its up axis and the vertical): 1 without tilt data; linear between the tabulated
/// angles, the end values beyond them. A table that stops at 90° is read at 180° − tilt above 90°
/// (the lamp axis then makes the same angle with the vertical, base up and down swapped).
float ies_tilt_multiplier(const IesProfile& profile, float tilt_deg);

/// Candela at (γ, C) in degrees, bilinear in (γ, C) between the measured angles; zero outside
/// the measured vertical range. C is taken modulo 360.
float ies_candela(const IesProfile& profile, float vertical_deg, float horizontal_deg);

/// Candela toward a unit direction in the luminaire's frame (z up, nadir −z, C = 0° along +x,
/// C = 90° along +y).
float ies_candela(const IesProfile& profile, const Vec3& direction_local);

/// Luminous flux of the interpolated distribution, lm: ∫∫ I(γ, C) sin γ dγ dC, exact for the
/// bilinear interpolant (linear in γ times sin γ integrates in closed form per cell).
double ies_flux_lm(const IesProfile& profile);

}  // namespace kasumi
