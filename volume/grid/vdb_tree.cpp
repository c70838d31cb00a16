#include "volume/grid/vdb_tree.h"

#include <algorithm>
#include <cstring>

namespace kasumi::vdb_file {

/// A leaf's active-voxel box from its mask (offset = x << 6 | y << 3 | z: word x, byte y, bit z).
void expand_by_leaf(Tree& tree, const VoxelBlock& leaf) {
    int x0 = -1, x1 = -1;
    uint64_t any = 0;
    for (int x = 0; x < 8; ++x) {
        if (leaf.active[x] != 0) {
            x0 = x0 < 0 ? x : x0;
            x1 = x;
            any |= leaf.active[x];
        }
    }
    if (x0 < 0)
        return;
    int y0 = 8, y1 = -1;
    uint8_t zs = 0;
    for (int y = 0; y < 8; ++y) {
        const uint8_t byte = static_cast<uint8_t>(any >> (8 * y));
        if (byte != 0) {
            y0 = std::min(y0, y);
            y1 = y;
            zs |= byte;
        }
    }
    const int z0 = __builtin_ctz(zs), z1 = 31 - __builtin_clz(zs);
    tree.expand(leaf.origin + IVec3(x0, y0, z0), leaf.origin + IVec3(x1, y1, z1));
}

template <int Log2>
void read_internal(Cursor& in, Tree& tree, IVec3 origin, std::vector<float>& values) {
    constexpr uint32_t kCount = 1u << (3 * Log2);
    constexpr int kWords = kCount / 64;
    constexpr int kChildTotal = Log2 == 5 ? 7 : 3;  // log2 of a child's edge in voxels
    uint64_t child_mask[kWords], value_mask[kWords];
    std::memcpy(child_mask, in.take(sizeof(child_mask)), sizeof(child_mask));
    std::memcpy(value_mask, in.take(sizeof(value_mask)), sizeof(value_mask));
    // The node's values are used only for its active tiles; a node with none (every node of
    // most fog volumes) skips them (checking their sizes as OpenVDB reads them).
    bool any_tile = false;
    for (int w = 0; w < kWords; ++w)
        any_tile = any_tile || (value_mask[w] & ~child_mask[w]) != 0;
    if (!any_tile) {
        skip_values(in, tree.compression, kCount, value_mask);
    } else {
        values.resize(2 * kCount);
        read_values(in, tree.compression, values.data(), kCount, value_mask,
                    values.data() + kCount);
    }
    auto local = [](uint32_t i) {
        return IVec3(static_cast<int>(i >> (2 * Log2)),
                     static_cast<int>((i >> Log2) & ((1u << Log2) - 1)),
                     static_cast<int>(i & ((1u << Log2) - 1)));
    };
    // Active tiles: cut into 8³ blocks of one value, as vdb_read.cpp does.
    for (int w = 0; w < kWords; ++w) {
        for (uint64_t word = value_mask[w] & ~child_mask[w]; word != 0; word &= word - 1) {
            const uint32_t i = static_cast<uint32_t>(w * 64 + __builtin_ctzll(word));
            const IVec3 lo = origin + (local(i) << kChildTotal);
            const int edge = 1 << kChildTotal;
            if (tree.active_voxels + uint64_t(edge) * edge * edge > kMaxTileVoxels)
                throw_input_error(tree.where + ": active tiles cover more than 2^27 voxels");
            tree.tile_values.emplace_back(VoxelBlock::kVoxels, values[i]);
            ++tree.active_tiles;
            tree.active_voxels += uint64_t(edge) * edge * edge;
            tree.expand(lo, lo + IVec3(edge - 1));
            VoxelBlock block;
            block.values = tree.tile_values.back().data();
            block.active.fill(~uint64_t(0));
            for (int z = 0; z < edge; z += VoxelBlock::kEdge)
                for (int y = 0; y < edge; y += VoxelBlock::kEdge)
                    for (int x = 0; x < edge; x += VoxelBlock::kEdge) {
                        block.origin = lo + IVec3(x, y, z);
                        tree.tiles.push_back(block);
                    }
        }
    }
    for (int w = 0; w < kWords; ++w) {
        for (uint64_t word = child_mask[w]; word != 0; word &= word - 1) {
            const uint32_t i = static_cast<uint32_t>(w * 64 + __builtin_ctzll(word));
            const IVec3 child = origin + (local(i) << kChildTotal);
            if constexpr (Log2 == 5) {
                read_internal<4>(in, tree, child, values);
            } else {
                VoxelBlock leaf;  // LeafNode::readTopology: its value mask
                leaf.origin = child;
                std::memcpy(leaf.active.data(), in.take(sizeof(leaf.active)), sizeof(leaf.active));
                tree.leaves.push_back(leaf);
            }
        }
    }
}

template void read_internal<5>(Cursor& in, Tree& tree, IVec3 origin, std::vector<float>& values);

}  // namespace kasumi::vdb_file
