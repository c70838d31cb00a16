#pragma once
/// The interface between kasumi and its OpenVDB module (libkasumi_vdb.so, built from
/// vdb_read.cpp, vdb_write.cpp and vdb_module.cpp). OpenVDB and the libraries it pulls in
/// (Boost iostreams, log4cplus, Blosc, ...) export ~64k symbols whose binding costs more CPU than
/// the rest of a small render, so the executable does not link them: volume/vdb_io.cpp loads
/// the module with dlopen the first time a grid is read or written (see vdb_io.h).
#include "volume/vdb_io.h"

namespace kasumi {

/// Bumped whenever VdbModuleApi, LoadedGrid, DenseVoxels or DensityGrid change layout: a module
/// from another build is refused instead of misread.
constexpr int kVdbModuleAbi = 1;

/// The module's entry points (its own copies of load_density_grid and write_fog_volume).
struct VdbModuleApi {
    int abi = kVdbModuleAbi;
    LoadedGrid (*load_density_grid)(const std::string& path, const std::string& grid_name,
                                    const std::string& context) = nullptr;
    void (*write_fog_volume)(const std::string& path, const std::string& grid_name,
                             const DenseVoxels& voxels, double voxel_size_m,
                             const Vec3& world_offset, bool constant_tiles) = nullptr;
};

/// File name of the module, and the C symbol it exports: `const VdbModuleApi* NAME()`.
constexpr const char* kVdbModuleFile = "libkasumi_vdb.so";
constexpr const char* kVdbModuleEntry = "kasumi_vdb_module_api";

/// Where the module is looked for, in order: $KASUMI_VDB_MODULE if set (then only there); the
/// executable's directory; <executable's directory>/../lib/kasumi (installed); the build tree
/// it was built in (so tests and benchmarks find it without installing).
std::vector<std::string> vdb_module_search_paths();

}  // namespace kasumi
