#pragma once
/// Building a DensityGrid from blocks of 8³ voxels (OpenVDB's leaf nodes, or its active tiles cut
/// into such blocks) in parallel, without a per-voxel `DensityGrid::set`: one pass finds the
/// bricks each block touches (and any invalid voxel), the bricks are allocated once, and a
/// second pass copies every block's voxels into its bricks and their aprons. Blocks never share
/// a voxel, so the copies write disjoint floats and need no locking.
///
/// Kept free of OpenVDB types: volume/grid/vdb_read.cpp (the only reader of OpenVDB files) fills
/// the blocks from the tree it read.
#include "volume/grid/density_grid.h"

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace kasumi {

/// One 8³ block of voxels in OpenVDB's leaf layout (`openvdb::tree::LeafNode<float, 3>`).
struct VoxelBlock {
    static constexpr int kEdge = 8;
    static constexpr int kVoxels = kEdge * kEdge * kEdge;
    /// Offset of voxel (x, y, z) in `values` and bit of `active`: z fastest, as in OpenVDB.
    static constexpr int offset(int x, int y, int z) { return (x << 6) | (y << 3) | z; }

    IVec3 origin{0};                              ///< index of the block's voxel (0, 0, 0)
    const float* values = nullptr;                ///< kVoxels values, at `offset(x, y, z)`
    std::array<uint64_t, kVoxels / 64> active{};  ///< bit n % 64 of word n / 64: voxel n is on
};

/// A voxel whose density is NaN, infinite or negative.
struct InvalidVoxel {
    IVec3 index{0};
    float value = 0.0f;
};

struct DensityGridBuild {
    std::shared_ptr<DensityGrid> grid;  ///< null when `invalid` is set
    bool has_invalid = false;
    InvalidVoxel invalid;  ///< the first invalid active voxel in block order, then offset order
};

class DensityGridBuilder {
  public:
    /// The grid of the active voxels of `blocks` (inactive voxels read as 0, as do active zeros),
    /// whose active voxels all lie in [index_min, index_max] (inclusive). Blocks must not
    /// overlap. Equal, voxel for voxel and bound for bound, to `DensityGrid::set` of every
    /// active voxel followed by `finalize`; the bricks are stored in slot order. Runs on TBB's
    /// worker threads. If an active voxel is invalid, nothing is allocated and the first one is
    /// returned instead.
    static DensityGridBuild build(IVec3 index_min, IVec3 index_max,
                                  const std::vector<VoxelBlock>& blocks);
};

}  // namespace kasumi
