#pragma once
/// Blackbody emission of hot media (fire, explosions) in the working space. Units: kelvin in,
/// scene-linear Rec.709 whose luminance Y is in cd/m² out.
///
/// Planck's law B(lambda, T) (W/(m² sr nm), core/spectrum.h) integrated against the CIE 1931 2°
/// colour-matching functions, times 683 lm/W, gives XYZ with Y in cd/m²; then the Rec.709 matrix
/// (D65 white). A real black body is very bright (6e5 cd/m² at 2041 K, the platinum point that
/// defined the candela until 1979), so scenes scale it with `emission_scale`. Components the
/// Rec.709 gamut cannot hold (negative blue below about 1900 K) are clamped to 0; luminance is kept
/// as computed.
#include "core/color.h"

#include <vector>

namespace kasumi {

/// Photometric radiance of a black body at temperature_k (<= 0: black), Rec.709, cd/m².
/// Exact to the 1 nm quadrature of 360-830 nm.
Rgb blackbody_rec709(double temperature_k);

/// blackbody_rec709 tabulated every kStepK kelvin up to kMaxK (the hot-loop form). Between
/// entries the luminance is interpolated in log (log Y is nearly linear in T over a step: Wien's
/// exp(-c2 / lambda T)) and the colour Rec.709 / Y linearly; relative error below 1e-3 from
/// 500 K up. Above kMaxK a second table, uniform in kMaxK / T down to T -> infinity, holds
/// Y / T and the colour (the visible radiance of a very hot body grows like T, Rayleigh-Jeans,
/// not like Stefan-Boltzmann's T⁴ of the total); relative error below 1e-4.
class BlackbodyTable {
  public:
    static constexpr double kStepK = 10.0;
    static constexpr double kMaxK = 40000.0;
    static constexpr int kHotNodes = 257;  ///< nodes of u = kMaxK / T in [0, 1]

    BlackbodyTable();
    Rgb operator()(float temperature_k) const;

  private:
    std::vector<float> m_log_y;         ///< log of the luminance, cd/m² (very negative when 0)
    std::vector<Rgb> m_colour;          ///< Rec.709 / Y
    std::vector<float> m_hot_y_over_t;  ///< above kMaxK: luminance / T, cd/(m² K), by u
    std::vector<Rgb> m_hot_colour;      ///< above kMaxK: Rec.709 / Y, by u
};

}  // namespace kasumi
