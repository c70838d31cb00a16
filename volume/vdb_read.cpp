#include "volume/vdb_io.h"

#include "core/error.h"
#include "volume/density_grid_build.h"
#include "volume/vdb_header.h"

#include <openvdb/openvdb.h>

#include <cmath>
#include <deque>
#include <filesystem>
#include <mutex>

namespace kasumi {

namespace {

void initialize_openvdb() {
    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
}

std::string coord_text(const openvdb::Coord& c) {
    return "(" + std::to_string(c.x()) + ", " + std::to_string(c.y()) + ", " +
           std::to_string(c.z()) + ")";
}

openvdb::FloatGrid::Ptr read_float_grid(const std::string& path, const std::string& wanted,
                                        const std::string& context) {
    openvdb::io::File file(path);
    try {
        file.open(false);
    } catch (const openvdb::Exception& e) {
        throw_input_error(context + ": cannot read OpenVDB file " + path + ": " + e.what());
    }
    openvdb::GridBase::Ptr base;
    std::string first_float;
    for (auto it = file.beginName(); it != file.endName(); ++it) {
        const openvdb::GridBase::Ptr meta = file.readGridMetadata(it.gridName());
        if (first_float.empty() && meta->isType<openvdb::FloatGrid>())
            first_float = it.gridName();
    }
    std::string name = wanted;
    if (name.empty())
        name = file.hasGrid("density") ? "density" : first_float;
    if (name.empty() || !file.hasGrid(name)) {
        std::string names;
        for (auto it = file.beginName(); it != file.endName(); ++it)
            names += (names.empty() ? "" : ", ") + it.gridName();
        throw_input_error(context + ": " + path + " has no " +
                          (name.empty() ? "float grid" : "grid \"" + name + "\"") +
                          " (grids: " + (names.empty() ? "none" : names) + ")");
    }
    base = file.readGrid(name);
    file.close();
    auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(base);
    if (!grid)
        throw_input_error(context + ": " + path + ": grid \"" + name + "\" is not a float grid");
    return grid;
}

}  // namespace

LoadedGrid load_density_grid(const std::string& path, const std::string& grid_name,
                             const std::string& context) {
    if (!std::filesystem::is_regular_file(path))
        throw_input_error(context + ": no such file: " + path);
    check_vdb_header(path, context);  // OpenVDB trusts the header's lengths and counts
    initialize_openvdb();
    openvdb::FloatGrid::Ptr grid;
    try {
        grid = read_float_grid(path, grid_name, context);
    } catch (const openvdb::Exception& e) {
        throw_input_error(context + ": " + path + ": " + e.what());
    }
    const std::string where = context + ": " + path + " grid \"" + grid->getName() + "\"";
    if (!grid->transform().isLinear())
        throw_input_error(where + ": only linear (affine) transforms are supported");
    if (grid->background() != 0.0f)
        throw_input_error(where + ": background is " + std::to_string(grid->background()) +
                          ", must be 0 (a fog volume)");

    LoadedGrid loaded;
    loaded.grid_name = grid->getName();
    const openvdb::Mat4d m = grid->transform().baseMap()->getAffineMap()->getMat4();
    // OpenVDB maps row vectors (world = index * M); glm maps column vectors, so g[i][j] = M(i, j).
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            loaded.index_to_world[i][j] = m(i, j);

    loaded.active_voxels = grid->activeVoxelCount();
    if (loaded.active_voxels == 0) {
        loaded.grid = std::make_shared<DensityGrid>();
        return loaded;
    }
    const openvdb::CoordBBox box = grid->evalActiveVoxelBoundingBox();

    // Every active voxel lies in a leaf (8³ voxels) or an active tile of an internal node (a
    // box of 128³ or 4096³ voxels, aligned to 8); tiles are cut into 8³ blocks of one value.
    const openvdb::FloatTree& tree = grid->tree();
    std::vector<VoxelBlock> blocks;
    blocks.reserve(tree.leafCount());
    for (auto leaf = tree.cbeginLeaf(); leaf; ++leaf) {
        VoxelBlock block;
        block.origin = IVec3(leaf->origin().x(), leaf->origin().y(), leaf->origin().z());
        block.values = leaf->buffer().data();
        for (size_t w = 0; w < block.active.size(); ++w)
            block.active[w] =
                leaf->getValueMask().getWord<uint64_t>(static_cast<openvdb::Index>(w));
        blocks.push_back(block);
    }
    std::deque<std::vector<float>> tile_values;  // one block of each tile's value
    auto tile = tree.cbeginValueOn();
    tile.setMaxDepth(openvdb::FloatTree::ValueOnCIter::LEAF_DEPTH - 1);  // tiles only
    for (; tile; ++tile) {
        const openvdb::CoordBBox b = tile.getBoundingBox();
        tile_values.emplace_back(VoxelBlock::kVoxels, *tile);
        ++loaded.active_tiles;
        VoxelBlock block;
        block.values = tile_values.back().data();
        block.active.fill(~uint64_t(0));
        for (int z = b.min().z(); z <= b.max().z(); z += VoxelBlock::kEdge)
            for (int y = b.min().y(); y <= b.max().y(); y += VoxelBlock::kEdge)
                for (int x = b.min().x(); x <= b.max().x(); x += VoxelBlock::kEdge) {
                    block.origin = IVec3(x, y, z);
                    blocks.push_back(block);
                }
    }
    // Inactive voxels read as the background, 0; inactive values stored in leaves are ignored.
    DensityGridBuild built =
        DensityGridBuilder::build(IVec3(box.min().x(), box.min().y(), box.min().z()),
                                  IVec3(box.max().x(), box.max().y(), box.max().z()), blocks);
    if (built.has_invalid) {
        const IVec3 c = built.invalid.index;
        throw_input_error(where + ": voxel " + coord_text(openvdb::Coord(c.x, c.y, c.z)) + " = " +
                          std::to_string(built.invalid.value) +
                          ": densities must be finite and >= 0");
    }
    loaded.grid = std::move(built.grid);
    return loaded;
}

}  // namespace kasumi
