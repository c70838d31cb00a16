#pragma once
/// A procedural cumulus: a seeded cluster of spheres with a flat base, eroded by fractal value
/// noise (fBm), as densities in [0, 1] on a res³ grid. Deterministic for a given (res, seed).
#include "volume/grid/vdb_io.h"

#include <cstdint>

namespace kasumi {

struct CloudParams {
    int res = 256;      ///< voxels per edge (>= 8)
    uint64_t seed = 7;  ///< arranges the puffs and the noise
    int octaves = 5;    ///< fBm octaves; the finest is 2^(octaves-1) times the base frequency
};

/// Densities of the cloud: voxel (x, y, z) samples the unit cube at ((x, y, z) + 0.5) / res,
/// y up. Values are exactly 0 outside the cloud (a sparse VDB stays sparse).
DenseVoxels make_cumulus(const CloudParams& params);

}  // namespace kasumi
