#pragma once
// Grids for the VDB tests, written with OpenVDB (through write_fog_volume) into a temporary
// directory and read back through the scene loader's parse_medium, as a scene would.
#include "core/json_node.h"
#include "volume/grid/vdb_io.h"
#include "volume/medium_json.h"

#include <unistd.h>

#include <filesystem>
#include <string>

namespace kasumi::test {

/// One directory per process: ctest runs each test case as its own process, in parallel, and
/// a file rewritten by one while another has it mapped kills the reader with SIGBUS. The
/// directory is removed when the process exits.
inline std::string temp_grid_path(const std::string& name) {
    struct ProcessDir {
        std::filesystem::path path = std::filesystem::temp_directory_path() /
                                     ("kasumi_vdb_tests_" + std::to_string(::getpid()));
        ProcessDir() { std::filesystem::create_directories(path); }
        ~ProcessDir() {
            std::error_code ignored;
            std::filesystem::remove_all(path, ignored);
        }
    };
    static const ProcessDir dir;
    return (dir.path / (name + ".vdb")).string();
}

/// A cube of n³ voxels of `density` (index 0..n-1), voxel size `voxel_m`, index 0 at `offset`,
/// in a float grid named `grid`.
/// With trilinear interpolation the density ramps to 0 over one voxel outside, so a ray
/// crossing two opposite faces (away from edges) sees optical depth sigma_t * n * voxel_m: the
/// ramps integrate like a sharp box from index -0.5 to n - 0.5.
inline std::string write_box(const std::string& name, int n, float density, double voxel_m,
                             Vec3 offset = Vec3(0.0f), const std::string& grid = "density") {
    DenseVoxels v;
    v.dims = IVec3(n);
    v.values.assign(static_cast<size_t>(n) * n * n, density);
    const std::string path = temp_grid_path(name);
    write_fog_volume(path, grid, v, voxel_m, offset);
    return path;
}

/// A `vdb` medium from JSON (keys as in a scene); `file` is filled in.
inline Medium vdb_medium(const std::string& path, Json keys) {
    keys["type"] = "vdb";
    keys["file"] = path;
    static Json doc;  // JsonNode does not own its document
    doc = keys;
    return parse_medium(JsonNode(doc, "test.json", "/media/0"), 0);
}

}  // namespace kasumi::test
