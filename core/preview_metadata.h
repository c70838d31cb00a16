#pragma once
/// What a preview records about how it was made: the same keys in the EXR's kasumi/preview/*
/// attributes (render/frame_output.cpp) and the preview PNG's tEXt chunks, so a PNG found alone
/// still says which view and exposure turned the scene's luminance into its pixels.
#include "core/color_management.h"
#include "core/png_io.h"

#include <string>
#include <vector>

namespace kasumi {

/// `stops` as the kasumi/preview/exposure_stops metadata holds it (%.9g: the float exactly).
std::string exposure_text(float stops);

/// The PNG's tEXt chunks: Software, kasumi/preview/display, kasumi/preview/view (empty names
/// stand for the config's defaults and are written as "default") and
/// kasumi/preview/exposure_stops.
std::vector<PngText> preview_png_text(const PreviewSettings& settings);

}  // namespace kasumi
