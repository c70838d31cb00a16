// load_density_grid and write_fog_volume for the executable: they load the OpenVDB module on
// first use and call its copies (see vdb_module.h).
#include "volume/vdb_module.h"

#include "core/error.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>

#ifndef KASUMI_VDB_MODULE_BUILD_PATH
#define KASUMI_VDB_MODULE_BUILD_PATH ""
#endif

namespace kasumi {

namespace {

std::string executable_dir() {
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    return ec ? std::string() : exe.parent_path().string();
}

const VdbModuleApi& vdb_module() {
    static const VdbModuleApi* api = nullptr;
    static std::string failure;
    static std::once_flag once;
    std::call_once(once, [] {
        std::string tried;
        for (const std::string& path : vdb_module_search_paths()) {
            if (!std::filesystem::exists(path)) {
                tried += (tried.empty() ? " " : "; ") + path + " (no such file)";
                continue;
            }
            void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
            if (handle == nullptr) {
                const char* why = dlerror();
                tried += (tried.empty() ? " " : "; ") + path + " (" +
                         (why != nullptr ? why : "cannot load") + ")";
                continue;
            }
            // Never closed: grids it built live until the process ends.
            using Entry = const VdbModuleApi* (*)();
            const auto entry = reinterpret_cast<Entry>(dlsym(handle, kVdbModuleEntry));
            const VdbModuleApi* found = entry != nullptr ? entry() : nullptr;
            if (found == nullptr || found->abi != kVdbModuleAbi) {
                tried += (tried.empty() ? " " : "; ") + path +
                         " (not a kasumi OpenVDB module of this build)";
                continue;
            }
            api = found;
            return;
        }
        failure = std::string("cannot load the OpenVDB module ") + kVdbModuleFile +
                  " (needed to read or write .vdb files); tried" + tried +
                  "; set KASUMI_VDB_MODULE to its path";
    });
    if (api == nullptr)
        throw Error(ErrorKind::Runtime, failure);
    return *api;
}

}  // namespace

std::vector<std::string> vdb_module_search_paths() {
    if (const char* env = std::getenv("KASUMI_VDB_MODULE"); env != nullptr && *env != '\0')
        return {env};
    std::vector<std::string> paths;
    const std::string dir = executable_dir();
    if (!dir.empty()) {
        paths.push_back(dir + "/" + kVdbModuleFile);
        paths.push_back(dir + "/../lib/kasumi/" + kVdbModuleFile);
    }
    const std::string built = KASUMI_VDB_MODULE_BUILD_PATH;
    if (!built.empty() && (paths.empty() || built != paths.front()))
        paths.push_back(built);
    return paths;
}

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
