// load_density_grid and write_fog_volume for the executable: they load the OpenVDB module on
// first use and call its copies (see vdb_module.h).
#include "volume/vdb_module.h"

#include "core/module_loader.h"

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
    return vdb_module().load_density_grid(path, grid_name, context);
}

void write_fog_volume(const std::string& path, const std::string& grid_name,
                      const DenseVoxels& voxels, double voxel_size_m, const Vec3& world_offset,
                      bool constant_tiles) {
    vdb_module().write_fog_volume(path, grid_name, voxels, voxel_size_m, world_offset,
                                  constant_tiles);
}

}  // namespace kasumi
