// load_density_grid and write_fog_volume for the executable: they load the OpenVDB module on
// first use and call its copies (see vdb_module.h).
#include "volume/grid/vdb_module.h"

#include "core/module_loader.h"
#include "volume/grid/vdb_direct.h"

#include <cstdlib>
#include <cstring>

#ifndef KASUMI_VDB_MODULE_BUILD_PATH
#define KASUMI_VDB_MODULE_BUILD_PATH ""
#endif

namespace kasumi {

namespace {

const VdbModuleApi& vdb_module() {
    static const ModuleSpec spec{
        "OpenVDB module",    "to read or write .vdb files", kVdbModuleFile,
        "KASUMI_VDB_MODULE", KASUMI_VDB_MODULE_BUILD_PATH,  kVdbModuleEntry,
        kVdbModuleAbi};
    return module_api<VdbModuleApi>(spec);
}

}  // namespace

LoadedGrid load_density_grid(const std::string& path, const std::string& grid_name,
                             const std::string& context) {
    // The common layouts without OpenVDB (vdb_direct.h); everything else, and every error,
    // through it. KASUMI_VDB_DIRECT=0 always takes OpenVDB's path.
    const char* direct = std::getenv("KASUMI_VDB_DIRECT");
    if (!(direct && std::strcmp(direct, "0") == 0)) {
        if (std::optional<LoadedGrid> loaded =
                read_density_grid_direct(path, grid_name, nullptr, context))
            return std::move(*loaded);
    }
    return load_density_grid_openvdb(path, grid_name, context);
}

LoadedGrid load_density_grid_openvdb(const std::string& path, const std::string& grid_name,
                                     const std::string& context) {
    return vdb_module().load_density_grid(path, grid_name, context);
}

void write_fog_volume(const std::string& path, const std::string& grid_name,
                      const DenseVoxels& voxels, double voxel_size_m, const Vec3& world_offset,
                      bool constant_tiles) {
    vdb_module().write_fog_volume(path, grid_name, voxels, voxel_size_m, world_offset,
                                  constant_tiles);
}

}  // namespace kasumi
