#pragma once
// A heterogeneous grid for the estimator tests (unbiased march, decomposition tracking): smooth
// enough that a 1/64-voxel march is exact far below their noise, with bricks that are neither
// constant nor empty and one constant brick-aligned block (a minorant equal to the majorant).
#include "volume/grid/density_grid.h"
#include "volume/medium.h"
#include "volume/medium_set.h"

#include <algorithm>
#include <cmath>
#include <memory>

namespace kasumi::test {

/// A grid medium over `grid` with extinction sigma_t per unit density (albedo 0.8), its box the
/// index-space box `bounds` (index space is world space here).
inline MediumSet grid_media(std::shared_ptr<DensityGrid> grid, float sigma_t, Bounds3 bounds) {
    VdbMedium v;
    v.grid = std::move(grid);
    v.sigma_a_per_density = Rgb(0.2f * sigma_t);
    v.sigma_s_per_density = Rgb(0.8f * sigma_t);
    v.bounds_world = bounds;
    return MediumSet({Medium{"grid", v}});
}

/// A smooth cloud of 40³ voxels: a ball of radius 16 whose density falls from 2 at the centre
/// to 0 at its rim, modulated by a few sines (so bricks are neither constant nor empty), with
/// one constant brick-aligned block of density 1.5 in a corner.
inline std::shared_ptr<DensityGrid> smooth_cloud() {
    auto grid = std::make_shared<DensityGrid>(IVec3(0), IVec3(39));
    for (int z = 0; z < 40; ++z)
        for (int y = 0; y < 40; ++y)
            for (int x = 0; x < 40; ++x) {
                const Vec3 p(x, y, z);
                const float r = glm::length(p - Vec3(20.0f)) / 16.0f;
                float d = std::max(0.0f, 2.0f * (1.0f - r)) *
                          (1.0f + 0.4f * std::sin(0.7f * x) * std::cos(0.5f * y + 0.3f * z));
                if (x <= 8 && y <= 8 && z <= 8)
                    d = 1.5f;
                grid->set(IVec3(x, y, z), d);
            }
    grid->finalize();
    return grid;
}

/// A grid of 25³ voxels all of density 1 (index 0..24). Its bricks start at index -1 (the zero
/// apron below voxel 0 is in the first ones, whose minorant is 0).
inline std::shared_ptr<DensityGrid> constant_grid() {
    auto grid = std::make_shared<DensityGrid>(IVec3(0), IVec3(24));
    for (int z = 0; z <= 24; ++z)
        for (int y = 0; y <= 24; ++y)
            for (int x = 0; x <= 24; ++x)
                grid->set(IVec3(x, y, z), 1.0f);
    grid->finalize();
    return grid;
}

/// A box inside constant_grid() where every brick has its minorant equal to its majorant (the
/// bricks [7, 15] and [15, 23] on each axis), 15 voxels across.
inline const Bounds3 kConstantBox{Vec3(7.0f), Vec3(22.0f)};

}  // namespace kasumi::test
