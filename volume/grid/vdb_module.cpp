// The OpenVDB module's entry point; built only into libkasumi_vdb.so (see vdb_module.h).
#include "volume/grid/vdb_module.h"

extern "C" __attribute__((visibility("default"))) const kasumi::VdbModuleApi*
kasumi_vdb_module_api() {
    static const kasumi::VdbModuleApi api{kasumi::kVdbModuleAbi, &kasumi::load_density_grid,
                                          &kasumi::write_fog_volume};
    return &api;
}
