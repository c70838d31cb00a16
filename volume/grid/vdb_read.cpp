#include "volume/grid/vdb_io.h"

#include "core/error.h"
#include "volume/grid/density_grid_build.h"
#include "volume/grid/vdb_header.h"

#include <openvdb/openvdb.h>

#include <cmath>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <iostream>
#include <mutex>

#include <sys/mman.h>
#include <unistd.h>

namespace kasumi {

namespace {

void initialize_openvdb() {
    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
}

/// OpenVDB logs through log4cplus to stdout (a WARN line, colour codes and all, for a file
/// format newer than the library), and stdout carries `probe`'s and `plan --json`'s JSON.
/// While one is alive, file descriptor 1 points at an anonymous memory file (or, failing that,
/// at stderr); finish() points it back and returns what was written meanwhile, one message a
/// line without the colour codes. One at a time in the process (a mutex).
class StdoutCapture {
  public:
    StdoutCapture() : m_lock(mutex()) {
        flush();
        m_saved = ::dup(STDOUT_FILENO);
        if (m_saved < 0)
            return;  // no stdout to protect
        m_file = ::memfd_create("kasumi-openvdb-log", MFD_CLOEXEC);
        const int target = m_file >= 0 ? m_file : STDERR_FILENO;
        if (::dup2(target, STDOUT_FILENO) < 0) {
            ::close(m_saved);
            m_saved = -1;
        }
    }
    ~StdoutCapture() { finish(); }
    StdoutCapture(const StdoutCapture&) = delete;
    StdoutCapture& operator=(const StdoutCapture&) = delete;

    std::string finish() {
        std::string text;
        if (m_saved >= 0) {
            flush();
            ::dup2(m_saved, STDOUT_FILENO);
            ::close(m_saved);
            m_saved = -1;
        }
        if (m_file >= 0) {
            char buffer[4096];
            ssize_t n = 0;
            ::lseek(m_file, 0, SEEK_SET);
            while ((n = ::read(m_file, buffer, sizeof(buffer))) > 0 && text.size() < 65536)
                text.append(buffer, static_cast<size_t>(n));
            ::close(m_file);
            m_file = -1;
        }
        return plain(text);
    }

  private:
    static std::mutex& mutex() {
        static std::mutex m;
        return m;
    }
    static void flush() {
        std::cout.flush();
        std::fflush(stdout);
    }
    /// Without ANSI escape sequences, lines joined by "; ", blanks trimmed.
    static std::string plain(const std::string& text) {
        std::string out, line;
        auto end_line = [&] {
            const size_t a = line.find_first_not_of(" \t\r");
            if (a != std::string::npos) {
                const size_t b = line.find_last_not_of(" \t\r");
                out += (out.empty() ? "" : "; ") + line.substr(a, b - a + 1);
            }
            line.clear();
        };
        for (size_t i = 0; i < text.size(); ++i) {
            if (text[i] == '\x1b' && i + 1 < text.size() && text[i + 1] == '[') {
                i += 2;
                while (i < text.size() && !(text[i] >= '@' && text[i] <= '~'))
                    ++i;
            } else if (text[i] == '\n') {
                end_line();
            } else {
                line += text[i];
            }
        }
        end_line();
        return out;
    }

    std::unique_lock<std::mutex> m_lock;
    int m_saved = -1;
    int m_file = -1;
};

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
    openvdb::FloatGrid::Ptr grid;
    std::string log;
    {
        // OpenVDB's log lines go to stderr: as a warning when it reads the file, inside the
        // one-line error when it does not.
        StdoutCapture capture;
        try {
            initialize_openvdb();
            grid = read_float_grid(path, grid_name, context);
        } catch (const openvdb::Exception& e) {
            log = capture.finish();
            throw_input_error(context + ": " + path + ": " + e.what() +
                              (log.empty() ? "" : " (OpenVDB: " + log + ")"));
        } catch (const Error& e) {
            log = capture.finish();
            if (log.empty())
                throw;
            throw Error(e.kind(), std::string(e.what()) + " (OpenVDB: " + log + ")");
        }
        log = capture.finish();
    }
    if (!log.empty())
        std::fprintf(stderr, "kasumi: warning: %s: %s: OpenVDB: %s\n", context.c_str(),
                     path.c_str(), log.c_str());
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
