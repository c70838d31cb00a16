#include "core/preview_metadata.h"

#include <cstdio>

namespace kasumi {

std::string exposure_text(float stops) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", static_cast<double>(stops));
    return text;
}

std::vector<PngText> preview_png_text(const PreviewSettings& settings) {
    const auto or_default = [](const std::string& name) {
        return name.empty() ? std::string("default") : name;
    };
    return {{"Software", "kasumi"},
            {"kasumi/preview/display", or_default(settings.display)},
            {"kasumi/preview/view", or_default(settings.view)},
            {"kasumi/preview/exposure_stops", exposure_text(settings.exposure_stops)}};
}

}  // namespace kasumi
