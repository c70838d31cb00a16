// color_management.h for the executable: each function loads the OpenColorIO module on first
// use and calls its copy (see ocio_module.h).
#include "core/module_loader.h"
#include "core/ocio_module.h"

#ifndef KASUMI_OCIO_MODULE_BUILD_PATH
#define KASUMI_OCIO_MODULE_BUILD_PATH ""
#endif

namespace kasumi {

namespace {

const OcioModuleApi& ocio_module() {
    static const ModuleSpec spec{"OpenColorIO module",
                                 "for PNG previews and display transforms",
                                 kOcioModuleFile,
                                 "KASUMI_OCIO_MODULE",
                                 KASUMI_OCIO_MODULE_BUILD_PATH,
                                 kOcioModuleEntry,
                                 kOcioModuleAbi};
    return module_api<OcioModuleApi>(spec);
}

}  // namespace

void write_preview_png(const Image& image, const std::string& png_path,
                       const PreviewSettings& settings) {
    ocio_module().write_preview_png(image, png_path, settings);
}

void apply_display_view(std::vector<float>& rgb, const PreviewSettings& settings) {
    ocio_module().apply_display_view(rgb, settings);
}

std::vector<std::string> list_displays(const std::string& config_path) {
    return ocio_module().list_displays(config_path);
}

std::vector<std::string> list_views(const std::string& config_path, const std::string& display) {
    return ocio_module().list_views(config_path, display);
}

std::string default_ocio_config_path() {
    return ocio_module().default_ocio_config_path();
}

}  // namespace kasumi
