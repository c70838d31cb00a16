#pragma once
// The white furnace shared by the tests of the multiple-scattering integrators: media of albedo
// 1 inside a uniform environment of radiance 1 return L = 1 exactly in expectation, whatever the
// path lengths (energy conservation).
#include "vdb_test_grids.h"
#include "volume/volume_path.h"

#include <string>

namespace kasumi::test {

/// Paths that leave the media see a uniform background (no surfaces).
class UniformBackground final : public PathEnvironment {
  public:
    explicit UniformBackground(Rgb radiance) : m_radiance(radiance) {}
    float surface_distance(const Ray&) const override { return kInfinity; }
    Rgb radiance(const Ray&, Pcg32&) const override { return m_radiance; }

  private:
    Rgb m_radiance;
};

/// Two albedo-1 media, each with a camera ray starting inside it: a 16³ VDB box (voxels 0.25 m,
/// density 3, HG g = 0.6; written to the temporary grid `grid_name`) and a homogeneous box of
/// sigma_s = 4 /m on [-1, 1]³ (isotropic).
struct WhiteFurnace {
    explicit WhiteFurnace(const std::string& grid_name)
        : grid({vdb_medium(write_box(grid_name, 16, 1.0f, 0.25),
                           {{"density_scale", 3.0},
                            {"albedo", 1.0},
                            {"phase", {{"model", "hg"}, {"g", 0.6}}}})}) {}

    const MediumSet grid;
    const MediumSet fog{{Medium{"fog", HomogeneousMedium{Bounds3{Vec3(-1.0f), Vec3(1.0f)},
                                                         Rgb(0.0f), Rgb(4.0f), Isotropic{}}}}};
    const Ray inside_grid{Vec3(2.0f, 1.9f, 2.1f), glm::normalize(Vec3(1, 0.3f, -0.2f)), 0.0f,
                          kInfinity};
    const Ray inside_fog{Vec3(0.1f, 0.2f, 0.0f), glm::normalize(Vec3(-1, 0.5f, 0.2f)), 0.0f,
                         kInfinity};

    /// L = L_volume + T * L_background (green channel) of one sample along `ray`.
    static double radiance(const MediumSet& media, const VolumeSettings& settings, const Ray& ray,
                           Pcg32& rng) {
        const UniformBackground background(Rgb(1.0f));
        VolumeCounters counters;
        const VolumeResult v =
            integrate_media(media, {}, nullptr, &background, ray, settings, true, rng, counters);
        return v.radiance.g + v.transmittance.g;
    }
};

}  // namespace kasumi::test
