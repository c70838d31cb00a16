#pragma once
/// The tree of a float grid as the direct .vdb reader (vdb_direct.h) reads its topology: OpenVDB's
/// 5-4-3 internal nodes with their active tiles, and the leaves' masks (their values are read
/// afterwards). Internal to volume/grid.
#include "volume/grid/density_grid_build.h"
#include "volume/grid/vdb_codecs.h"

#include <deque>
#include <limits>
#include <string>
#include <vector>

namespace kasumi::vdb_file {

// What a grid may cover. Both readers store every active voxel of a tile and a brick index over
// the active box, so a few bytes of a hostile file (one mask bit is a tile of 128³ voxels, two
// leaves far apart span 2^32 voxels per axis) would ask either for terabytes: such grids are
// input errors here rather than a decline (OpenVDB's path would allocate until it fails).
constexpr uint64_t kMaxTileVoxels = uint64_t(1) << 27;  // 512³ voxels of tiles: 0.8 GB of bricks
constexpr int64_t kMaxEdgeVoxels = int64_t(1) << 24;    // per axis of the active box
constexpr uint64_t kMaxBrickSlots = uint64_t(1) << 24;  // bricks of 8³ cells in the box: 0.2 GB

/// The topology of one grid as read: leaves (values later), active tiles cut into blocks, the
/// active box and counts.
struct Tree {
    std::string where;  ///< "context: path grid "name"", for input errors
    uint32_t compression = 0;
    std::vector<VoxelBlock> leaves;  ///< in file order (their values are read later)
    std::vector<VoxelBlock> tiles;   ///< active tiles cut into 8³ blocks of one value
    std::deque<std::vector<float>> tile_values;
    uint64_t active_voxels = 0;
    uint64_t active_tiles = 0;
    IVec3 box_min{std::numeric_limits<int>::max()};
    IVec3 box_max{std::numeric_limits<int>::min()};

    void expand(IVec3 lo, IVec3 hi) {
        box_min = glm::min(box_min, lo);
        box_max = glm::max(box_max, hi);
    }
};

/// A leaf's active-voxel box from its mask (offset = x << 6 | y << 3 | z: word x, byte y, bit z).
void expand_by_leaf(Tree& tree, const VoxelBlock& leaf);

/// InternalNode<ChildT, Log2>::readTopology (file format >= 222) for the root's children
/// (Log2 = 5), their children read recursively: active tiles into tree.tiles, leaves (their
/// value masks) into tree.leaves. `values`: scratch. Throws an input error past
/// kMaxTileVoxels of tiles; declines what it cannot read.
template <int Log2>
void read_internal(Cursor& in, Tree& tree, IVec3 origin, std::vector<float>& values);

}  // namespace kasumi::vdb_file
