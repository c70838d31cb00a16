#include "volume/grid/vdb_direct.h"

#include "core/error.h"
#include "core/zeroed_allocator.h"
#include "volume/grid/density_grid_build.h"
#include "volume/grid/vdb_codecs.h"
#include "volume/grid/vdb_mapped_file.h"
#include "volume/grid/vdb_tree.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <vector>

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "VDB files are little-endian");

namespace kasumi {

namespace {

using namespace vdb_file;

std::function<void(const std::string&, const char*)>& read_hook() {
    static std::function<void(const std::string&, const char*)> hook;
    return hook;
}

/// Math/Maps.h: the map's type name, then its doubles; the matrix maps index to world for row
/// vectors (world = index * M), stored as index_to_world[i][j] = M(i, j) like vdb_read.cpp.
glm::dmat4 read_transform(Cursor& in) {
    const std::string type = in.string();
    auto vec3 = [&in] {
        double v[3];
        std::memcpy(v, in.take(sizeof(v)), sizeof(v));
        return glm::dvec3(v[0], v[1], v[2]);
    };
    glm::dmat4 m(1.0);
    if (type == "AffineMap") {
        double a[16];  // Mat4d, row-major
        std::memcpy(a, in.take(sizeof(a)), sizeof(a));
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j)
                m[i][j] = a[4 * i + j];
    } else if (type == "ScaleMap" || type == "UniformScaleMap") {
        const glm::dvec3 s = vec3();
        in.take(4 * 3 * sizeof(double));  // voxel size, inverse scale, its square, 1 / (2 scale)
        m[0][0] = s.x;
        m[1][1] = s.y;
        m[2][2] = s.z;
    } else if (type == "ScaleTranslateMap" || type == "UniformScaleTranslateMap") {
        const glm::dvec3 t = vec3();
        const glm::dvec3 s = vec3();
        in.take(4 * 3 * sizeof(double));
        m[0][0] = s.x;
        m[1][1] = s.y;
        m[2][2] = s.z;
        m[3] = glm::dvec4(t, 1.0);
    } else if (type == "TranslationMap") {
        m[3] = glm::dvec4(vec3(), 1.0);
    } else {
        decline("map " + type);
    }
    return m;
}

struct Descriptor {
    std::string name, type;
    bool half = false, instance = false;
    uint64_t grid = 0, block = 0, end = 0;
};

/// The transform must map index space to world space and back (OpenVDB's maps are affine).
void check_transform(const glm::dmat4& m, const std::string& where) {
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            if (!std::isfinite(m[i][j]))
                throw_input_error(where + ": the transform holds a non-finite number");
    if (m[0][3] != 0.0 || m[1][3] != 0.0 || m[2][3] != 0.0 || m[3][3] != 1.0)
        throw_input_error(where + ": the transform is not affine");
    const double det = glm::determinant(glm::dmat3(m));
    const glm::dmat4 inverse = glm::inverse(m);
    bool finite = std::isfinite(det) && det != 0.0;
    for (int i = 0; i < 4 && finite; ++i)
        for (int j = 0; j < 4; ++j)
            finite = finite && std::isfinite(inverse[i][j]);
    if (!finite)
        throw_input_error(where + ": the transform is not invertible");
}

/// What a read builds, kept outside the guarded reads (SigbusGuard::run): a jump out of them
/// skips the destructors of what they created.
struct ReadState {
    std::vector<Descriptor> grids;
    Tree tree;
    std::vector<float> scratch;
    std::vector<size_t> values_at;
    std::vector<float, ZeroedAllocator<float>> values;
    std::string shifted_where;
    LoadedGrid loaded;
};

/// The file's header and descriptors, the chosen grid's topology and the positions of its
/// leaves' values; returns false when the grid is empty (nothing more to read).
bool read_layout(const MappedFile& file, const std::string& path, const std::string& wanted,
                 const std::string& context, ReadState& state) {
    Cursor in(file.data(), file.size());
    if (in.get<int64_t>() != 0x56444220)  // "VDB "
        decline("not a VDB file");
    const uint32_t version = in.get<uint32_t>();
    if (version < 222 || version > 224)  // node-mask compression .. OpenVDB 11's format
        decline("file format " + std::to_string(version));
    in.take(8);  // library major and minor version
    if (in.get<uint8_t>() == 0)
        decline("no grid offsets");
    in.take(36);  // UUID
    in.skip_metadata();
    const int32_t count = in.get<int32_t>();
    if (count < 0)
        decline("a negative grid count");
    std::vector<Descriptor>& grids = state.grids;
    grids.resize(static_cast<size_t>(std::min(count, 1 << 16)));
    if (static_cast<int32_t>(grids.size()) != count)
        decline("too many grids");
    static const std::string kHalf = "_HalfFloat", kDensity = "density";
    for (Descriptor& d : grids) {
        d.name = in.string();
        d.type = in.string();
        if (d.type.size() > kHalf.size() &&
            d.type.compare(d.type.size() - kHalf.size(), kHalf.size(), kHalf) == 0) {
            d.half = true;
            d.type.resize(d.type.size() - kHalf.size());
        }
        d.instance = !in.string().empty();
        const auto grid = in.get<int64_t>(), block = in.get<int64_t>(), end = in.get<int64_t>();
        if (grid < 0 || block < grid || end < block || static_cast<uint64_t>(end) > file.size())
            decline("grid positions outside the file");
        d.grid = static_cast<uint64_t>(grid);
        d.block = static_cast<uint64_t>(block);
        d.end = static_cast<uint64_t>(end);
        if (d.name.find('\x1e') != std::string::npos)  // a suffixed duplicate name
            decline("several grids of one name");
    }
    // The grid vdb_read.cpp picks: the one named; else "density"; else the first float grid in
    // name order (OpenVDB's File::beginName iterates a map sorted by name).
    const Descriptor* d = nullptr;
    const std::string& name = wanted.empty() ? kDensity : wanted;
    for (const Descriptor& g : grids)
        if (g.name == name)
            d = &g;
    if (!d && wanted.empty()) {
        for (const Descriptor& g : grids)
            if (g.type == "Tree_float_5_4_3" && (!d || g.name < d->name))
                d = &g;
    }
    if (!d)
        decline("no such grid");
    if (d->type != "Tree_float_5_4_3" || d->half || d->instance)
        decline("grid type " + d->type + (d->half ? " (half)" : "") +
                (d->instance ? " (an instance)" : ""));

    LoadedGrid& loaded = state.loaded;
    Tree& tree = state.tree;
    loaded.grid_name = d->name;
    in.seek(d->grid);
    tree.where = (context.empty() ? path : context + ": " + path) + " grid \"" + d->name + "\"";
    tree.compression = in.get<uint32_t>();
    if (tree.compression & ~(kCompressZip | kCompressActiveMask | kCompressBlosc))
        decline("unknown compression flags");
    in.set_where(&tree.where);
    in.skip_metadata();
    loaded.index_to_world = read_transform(in);
    check_transform(loaded.index_to_world, tree.where);
    if (in.get<int32_t>() != 1)
        decline("a buffer count other than 1");
    const float background = in.get<float>();
    if (background != 0.0f)
        decline("a non-zero background");
    const uint32_t root_tiles = in.get<uint32_t>(), root_children = in.get<uint32_t>();
    for (uint32_t i = 0; i < root_tiles; ++i) {
        in.take(3 * sizeof(int32_t) + sizeof(float));
        if (in.get<uint8_t>() != 0)  // 4096³ voxels
            throw_input_error(tree.where + ": active tiles cover more than 2^27 voxels");
    }
    if (in.pos() > d->block)
        decline("the topology starts past the grid's data");
    tree.leaves.reserve((d->block - in.pos()) /
                        sizeof(VoxelBlock::active));  // a bound: 64-byte masks
    for (uint32_t i = 0; i < root_children; ++i) {
        int32_t o[3];
        std::memcpy(o, in.take(sizeof(o)), sizeof(o));
        if ((o[0] | o[1] | o[2]) & 4095)  // RootNode keys: origins of 4096³ children
            decline("a root child off the 4096-voxel lattice");
        read_internal<5>(in, tree, IVec3(o[0], o[1], o[2]), state.scratch);
    }
    if (read_hook())
        read_hook()(path, "topology");

    // Leaf values (LeafNode::readBuffers): found in order, then decompressed in parallel. The
    // value mask stored again here is skipped, as OpenVDB does on a seekable stream. OpenVDB
    // reads them from wherever the topology ended, not from the descriptor's block position:
    // node masks that claim leaves the file does not hold (a flipped bit) shift every leaf
    // after them, and the sizes read there are garbage. A chunk past the end of the file is an
    // input error then (Cursor::chunk: OpenVDB would allocate it), the rest is declined below.
    const size_t topology_end = in.pos();
    const size_t leaves = tree.leaves.size();
    std::string& shifted = state.shifted_where;
    shifted = tree.where + ": the node masks claim " + std::to_string(leaves) +
              " leaves, whose topology ends at byte " + std::to_string(topology_end) +
              ", not where the grid's data start (byte " + std::to_string(d->block) + ")";
    if (topology_end != d->block)
        in.set_where(&shifted);
    state.values_at.resize(leaves);
    for (size_t i = 0; i < leaves; ++i) {
        in.take(sizeof(VoxelBlock::active));
        state.values_at[i] = in.pos();
        skip_values(in, tree.compression, VoxelBlock::kVoxels, tree.leaves[i].active.data());
        expand_by_leaf(tree, tree.leaves[i]);
        tree.active_voxels += count_on(tree.leaves[i].active.data(), 8);
    }
    if (topology_end != d->block)
        decline("the topology does not end where the grid's data start");
    if (in.pos() != d->end)
        decline("the leaves do not end where the grid does");
    loaded.active_voxels = tree.active_voxels;
    loaded.active_tiles = tree.active_tiles;
    return tree.active_voxels != 0;
}

/// The leaves' values, decompressed in parallel into state.values, each worker under the
/// guard; false if the file was cut meanwhile.
bool read_leaf_values(const MappedFile& file, const SigbusGuard& guard, ReadState& state) {
    const Tree& tree = state.tree;
    const size_t leaves = tree.leaves.size();
    const size_t floats = leaves * VoxelBlock::kVoxels;
    // Zeroed pages (every float is written below anyway), 2 MiB-aligned as transparent huge
    // pages from the start: with new float[] and advice on its aligned middle only, the rest
    // faulted in 4 KiB at a time (~550 faults of the 256³ render's ~1300).
    state.values.resize(floats);
    std::atomic<bool> broken{false}, cut{false};
    tbb::parallel_for(tbb::blocked_range<size_t>(0, leaves),
                      [&](const tbb::blocked_range<size_t>& r) {
                          float buffer[VoxelBlock::kVoxels];
                          const bool whole = guard.run([&] {
                              try {
                                  for (size_t i = r.begin(); i != r.end(); ++i) {
                                      Cursor c(file.data(), file.size(), state.values_at[i]);
                                      c.set_where(&tree.where);
                                      float* dest = state.values.data() + i * VoxelBlock::kVoxels;
                                      read_values(c, tree.compression, dest, VoxelBlock::kVoxels,
                                                  tree.leaves[i].active.data(), buffer);
                                  }
                              } catch (const Declined&) {
                                  broken = true;
                              }
                          });
                          if (!whole)
                              cut = true;
                      });
    if (broken && !cut)
        decline("a broken leaf");
    return !cut;
}

[[noreturn]] void file_cut(const MappedFile& file, const std::string& path,
                           const std::string& context) {
    throw_input_error((context.empty() ? path : context + ": " + path) +
                      ": the file was cut from " + std::to_string(file.size()) + " to " +
                      std::to_string(file.size_now()) +
                      " bytes while it was read (is another process writing it?)");
}

LoadedGrid read_grid(const std::string& path, const std::string& wanted,
                     const std::string& context) {
    const MappedFile file(path);
    const SigbusGuard guard(file.data(), file.size());
    ReadState state;
    bool any = false;
    if (!guard.run([&] { any = read_layout(file, path, wanted, context, state); }))
        file_cut(file, path, context);
    if (!any) {
        state.loaded.grid = std::make_shared<DensityGrid>();
        return std::move(state.loaded);
    }
    Tree& tree = state.tree;
    const glm::i64vec3 extent =
        glm::i64vec3(tree.box_max) - glm::i64vec3(tree.box_min) + glm::i64vec3(1);
    const glm::i64vec3 bricks =
        (extent + glm::i64vec3(2 + DensityGrid::kBrick - 1)) / glm::i64vec3(DensityGrid::kBrick);
    if (glm::any(glm::greaterThan(extent, glm::i64vec3(kMaxEdgeVoxels))) ||
        static_cast<uint64_t>(bricks.x * bricks.y) * static_cast<uint64_t>(bricks.z) >
            kMaxBrickSlots)
        throw_input_error(tree.where + ": the active voxels span " + std::to_string(extent.x) +
                          " x " + std::to_string(extent.y) + " x " + std::to_string(extent.z) +
                          " voxels, more than a grid may hold (2^24 per axis, 2^33 in all)");
    if (read_hook())
        read_hook()(path, "values");
    if (!read_leaf_values(file, guard, state))
        file_cut(file, path, context);
    const size_t leaves = tree.leaves.size();
    std::vector<VoxelBlock> blocks = std::move(tree.leaves);
    for (size_t i = 0; i < leaves; ++i)
        blocks[i].values = state.values.data() + i * VoxelBlock::kVoxels;
    blocks.insert(blocks.end(), tree.tiles.begin(), tree.tiles.end());
    DensityGridBuild built = DensityGridBuilder::build(tree.box_min, tree.box_max, blocks);
    if (built.has_invalid)
        decline("an invalid voxel");  // OpenVDB's path names it
    state.loaded.grid = std::move(built.grid);
    return std::move(state.loaded);
}

}  // namespace

std::optional<LoadedGrid> read_density_grid_direct(const std::string& path,
                                                   const std::string& grid_name,
                                                   std::string* why_not,
                                                   const std::string& context) {
    try {
        return read_grid(path, grid_name, context);
    } catch (const Declined& e) {
        if (why_not)
            *why_not = e.why;
        return std::nullopt;
    }
}

void set_direct_read_hook(std::function<void(const std::string& path, const char* stage)> hook) {
    read_hook() = std::move(hook);
}

}  // namespace kasumi
