// The OpenColorIO module's entry point; built only into libkasumi_ocio.so (see ocio_module.h).
#include "core/ocio_module.h"

extern "C" __attribute__((visibility("default"))) const kasumi::OcioModuleApi*
kasumi_ocio_module_api() {
    static const kasumi::OcioModuleApi api{
        kasumi::kOcioModuleAbi, &kasumi::write_preview_png, &kasumi::apply_display_view,
        &kasumi::list_displays, &kasumi::list_views,        &kasumi::default_ocio_config_path};
    return &api;
}
