#pragma once
/// Participating media as a closed set of value types (homogeneous now; height fog, VDB grids
/// and the atmosphere join later). Coefficients are per metre, per RGB channel.
#include "core/bounds.h"
#include "core/color.h"
#include "phase/phase_function.h"

#include <optional>
#include <string>
#include <variant>

namespace kasumi {

/// Constant absorption and scattering inside an axis-aligned box, or everywhere when `bounds`
/// is empty.
struct HomogeneousMedium {
    std::optional<Bounds3> bounds;
    Rgb sigma_a{0.0f};  ///< absorption coefficient, 1/m
    Rgb sigma_s{0.0f};  ///< scattering coefficient, 1/m
    PhaseFunction phase = Isotropic{};

    Rgb sigma_t() const { return sigma_a + sigma_s; }
};

struct Medium {
    std::string name;
    std::variant<HomogeneousMedium> model;
};

/// Single-scattering albedo sigma_s / sigma_t per channel (0 where sigma_t = 0).
inline Rgb single_scattering_albedo(const HomogeneousMedium& m) {
    const Rgb t = m.sigma_t();
    return Rgb(t.r > 0 ? m.sigma_s.r / t.r : 0.0f, t.g > 0 ? m.sigma_s.g / t.g : 0.0f,
               t.b > 0 ? m.sigma_s.b / t.b : 0.0f);
}

}  // namespace kasumi
