#include "volume/grid/vdb_io.h"

#include "core/atomic_file.h"
#include "core/error.h"

#include <openvdb/openvdb.h>

#include <mutex>

namespace kasumi {

void write_fog_volume(const std::string& path, const std::string& grid_name,
                      const DenseVoxels& voxels, double voxel_size_m, const Vec3& world_offset,
                      bool constant_tiles) {
    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
    KASUMI_CHECK(voxels.values.size() ==
                 static_cast<size_t>(voxels.dims.x) * voxels.dims.y * voxels.dims.z);
    KASUMI_CHECK(voxels.inactive.empty() || voxels.inactive.size() == voxels.values.size());
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setName(grid_name);
    grid->setGridClass(openvdb::GRID_FOG_VOLUME);
    auto transform = openvdb::math::Transform::createLinearTransform(voxel_size_m);
    transform->postTranslate(openvdb::Vec3d(world_offset.x, world_offset.y, world_offset.z));
    grid->setTransform(transform);
    auto accessor = grid->getAccessor();
    size_t i = 0;
    for (int z = 0; z < voxels.dims.z; ++z)
        for (int y = 0; y < voxels.dims.y; ++y)
            for (int x = 0; x < voxels.dims.x; ++x, ++i) {
                const float v = voxels.values[i];
                const openvdb::Coord c(voxels.origin.x + x, voxels.origin.y + y,
                                       voxels.origin.z + z);
                if (!voxels.inactive.empty() && voxels.inactive[i])
                    accessor.setValueOff(c, v);
                else if (v != 0.0f)
                    accessor.setValue(c, v);
            }
    if (constant_tiles)
        grid->tree().prune();  // tolerance 0: only nodes of one value and one active state
    AtomicFile out(path);
    try {
        openvdb::io::File file(out.temp_path());
        if (voxels.compression >= 0)
            file.setCompression(static_cast<uint32_t>(voxels.compression));
        file.write({grid});
        file.close();
    } catch (const openvdb::Exception& e) {
        throw_output_error("cannot write " + path + ": " + e.what());
    }
    out.commit();
}

}  // namespace kasumi
