#pragma once
/// The interface between kasumi and its OpenColorIO module (libkasumi_ocio.so, built from
/// color_management.cpp, png_io.cpp and ocio_module.cpp). OpenColorIO and what it pulls in
/// (yaml-cpp, expat, pystring) cost ~5 ms of CPU to bind at every start, yet only the PNG
/// preview and the colour tests use it, so the executable does not link it:
/// color_management_loader.cpp loads the module (core/module_loader.h) on the first call.
#include "core/color_management.h"

namespace kasumi {

/// Bumped whenever OcioModuleApi, PreviewSettings or Image change layout.
constexpr int kOcioModuleAbi = 1;

/// The module's copies of the functions of color_management.h.
struct OcioModuleApi {
    int abi = kOcioModuleAbi;
    void (*write_preview_png)(const Image& image, const std::string& png_path,
                              const PreviewSettings& settings) = nullptr;
    void (*apply_display_view)(std::vector<float>& rgb, const PreviewSettings& settings) = nullptr;
    std::vector<std::string> (*list_displays)(const std::string& config_path) = nullptr;
    std::vector<std::string> (*list_views)(const std::string& config_path,
                                           const std::string& display) = nullptr;
    std::string (*default_ocio_config_path)() = nullptr;
};

/// File name of the module (override: $KASUMI_OCIO_MODULE) and the C symbol it exports:
/// `const OcioModuleApi* NAME()`.
constexpr const char* kOcioModuleFile = "libkasumi_ocio.so";
constexpr const char* kOcioModuleEntry = "kasumi_ocio_module_api";

}  // namespace kasumi
