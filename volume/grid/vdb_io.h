#pragma once
/// Reading and writing OpenVDB float grids. The OpenVDB headers stay inside vdb_read.cpp and
/// vdb_write.cpp; everything else sees our own DensityGrid.
#include "core/math.h"
#include "volume/grid/density_grid.h"

#include <memory>
#include <string>
#include <vector>

namespace kasumi {

struct LoadedGrid {
    std::shared_ptr<const DensityGrid> grid;
    glm::dmat4 index_to_world{1.0};  ///< the grid's own (linear) transform
    std::string grid_name;           ///< the grid actually read
    uint64_t active_voxels = 0;
    uint64_t active_tiles = 0;  ///< active tiles of OpenVDB's internal nodes among them
};

/// Reads float grid `grid_name` (empty: "density" if present, else the first float grid) from
/// `path` into a DensityGrid. Input errors (missing file or grid, not a float grid, a non-linear
/// transform, a non-zero background, NaN, infinite or negative voxels) throw kasumi::Error
/// (Input) whose message starts with `context` (e.g. "scene.json: /media/0/file").
/// Files in the common layout are read without OpenVDB (volume/grid/vdb_direct.h), the rest through
/// it ($KASUMI_VDB_DIRECT=0: always through it); the result is the same either way.
LoadedGrid load_density_grid(const std::string& path, const std::string& grid_name,
                             const std::string& context);
/// load_density_grid always through OpenVDB (the module): the reference the direct reader is
/// tested against.
LoadedGrid load_density_grid_openvdb(const std::string& path, const std::string& grid_name,
                                     const std::string& context);

/// A dense block of voxels: value of voxel origin + (x, y, z) at values[x + nx (y + ny z)].
struct DenseVoxels {
    IVec3 origin{0};
    IVec3 dims{0};
    std::vector<float> values;
    /// For tests of readers: empty, or one flag per value: store that voxel inactive, keeping
    /// its value (a fog volume's reader must read it as 0).
    std::vector<uint8_t> inactive;
    /// For tests of readers: the file's compression as OpenVDB's io::COMPRESS_* flags (1 zip,
    /// 2 active mask, 4 blosc); -1: OpenVDB's default (blosc with the active mask).
    int compression = -1;
};

/// Writes `voxels` as an OpenVDB fog volume (float grid `grid_name`, background 0, zero voxels
/// inactive unless flagged, see DenseVoxels) with a uniform voxel size in metres and index (0, 0,
/// 0) at `world_offset`. Values are written as given (tests use this to make invalid grids). With
/// `constant_tiles`, regions of one value that fill whole OpenVDB nodes are stored as active tiles
/// (tree prune; tests of the reader's tile path). Throws Error (Output) on failure.
void write_fog_volume(const std::string& path, const std::string& grid_name,
                      const DenseVoxels& voxels, double voxel_size_m, const Vec3& world_offset,
                      bool constant_tiles = false);

}  // namespace kasumi
