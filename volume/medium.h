#pragma once
/// Participating media as a closed set of value types (homogeneous boxes, height fog and VDB
/// density grids; the atmosphere is rendered by volume/sky_renderer). Coefficients are per metre,
/// per RGB channel.
#include "core/bounds.h"
#include "core/color.h"
#include "phase/phase_function.h"
#include "volume/blackbody.h"
#include "volume/grid/density_grid.h"
#include "volume/height_fog.h"

#include <memory>
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

/// Blackbody emission of a grid medium: temperature T(x) = scale * value(x) + offset (kelvin)
/// from its own grid; the medium emits sigma_a(x) * emission_scale * B(T(x)) per metre
/// (Kirchhoff: emission equals absorption times the black body's radiance), in cd/m² per metre.
struct VdbTemperature {
    std::shared_ptr<const DensityGrid> grid;
    Mat4 world_to_index{1.0f};
    float scale = 1.0f;   ///< kelvin per grid unit
    float offset = 0.0f;  ///< kelvin
    float emission_scale = 1.0f;
    std::shared_ptr<const BlackbodyTable> blackbody;
    std::string file;
    std::string grid_name;

    /// emission_scale * B(T) at world point p, Rec.709 cd/m².
    Rgb radiance(const Vec3& p) const {
        const float value = grid->density(Vec3(world_to_index * Vec4(p, 1.0f)));
        return emission_scale * (*blackbody)(scale * value + offset);
    }
};

/// A density grid (from an OpenVDB file) scaled into coefficients: at a world point x,
/// sigma_a(x) = density(x) * sigma_a_per_density and likewise sigma_s, where density(x) is the
/// grid's trilinear value at world_to_index(x) (already multiplied by `density_scale`).
struct VdbMedium {
    std::shared_ptr<const DensityGrid> grid;
    Mat4 world_to_index{1.0f};      ///< affine: world metres to grid index space
    Rgb sigma_a_per_density{0.0f};  ///< 1/m per unit density, density_scale folded in
    Rgb sigma_s_per_density{0.0f};  ///< 1/m per unit density, density_scale folded in
    PhaseFunction phase = Isotropic{};
    Bounds3 bounds_world;       ///< world box holding every non-zero density
    float voxel_size_m = 1.0f;  ///< shortest world length of a voxel edge
    std::string file;           ///< the grid file, for messages and the plan
    std::string grid_name;
    std::optional<VdbTemperature> temperature;  ///< blackbody emission, if any
    double load_s = 0.0;  ///< wall time to read the grid(s) and build the bricks (statistics)

    Rgb sigma_t_per_density() const { return sigma_a_per_density + sigma_s_per_density; }
};

struct Medium {
    std::string name;
    std::variant<HomogeneousMedium, VdbMedium, HeightFogMedium> model;
};

}  // namespace kasumi
