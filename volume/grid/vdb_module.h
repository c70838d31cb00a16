#pragma once
/// The interface between kasumi and its OpenVDB module (libkasumi_vdb.so, built from
/// vdb_read.cpp, vdb_write.cpp and vdb_module.cpp). OpenVDB and the libraries it pulls in
/// (Boost iostreams, log4cplus, Blosc, ...) export ~64k symbols whose binding costs more CPU than
/// the rest of a small render, so the executable does not link them: volume/grid/vdb_io.cpp loads
/// the module with dlopen the first time a grid is read or written (see vdb_io.h).
#include "volume/grid/vdb_io.h"

namespace kasumi {

/// Bumped whenever VdbModuleApi, LoadedGrid, DenseVoxels or DensityGrid change layout: a module
/// from another build is refused instead of misread.
constexpr int kVdbModuleAbi = 2;

/// The module's entry points (its own copies of load_density_grid and write_fog_volume).
struct VdbModuleApi {
    int abi = kVdbModuleAbi;
    LoadedGrid (*load_density_grid)(const std::string& path, const std::string& grid_name,
                                    const std::string& context) = nullptr;
    void (*write_fog_volume)(const std::string& path, const std::string& grid_name,
                             const DenseVoxels& voxels, double voxel_size_m,
                             const Vec3& world_offset, bool constant_tiles) = nullptr;
};

/// File name of the module, and the C symbol it exports: `const VdbModuleApi* NAME()`. Found
/// and loaded by core/module_loader.h (override: $KASUMI_VDB_MODULE).
constexpr const char* kVdbModuleFile = "libkasumi_vdb.so";
constexpr const char* kVdbModuleEntry = "kasumi_vdb_module_api";

}  // namespace kasumi
