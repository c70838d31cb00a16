#include "core/color_management.h"
#include "core/preview_metadata.h"

#include "core/error.h"
#include "core/png_io.h"

#include <OpenColorIO/OpenColorIO.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>

namespace OCIO = OCIO_NAMESPACE;

namespace kasumi {
namespace {

/// Names under which configs carry scene-linear Rec.709 primaries with a D65 white: ours and the
/// ACES configs' alias first, then common names of other configs.
constexpr const char* kLinearRec709Names[] = {"lin_rec709", "Linear Rec.709 (sRGB)",
                                              "Utility - Linear - sRGB", "lin_srgb"};

bool file_exists(const std::string& path) {
    return std::ifstream(path).good();
}

std::string resolve_config_path(const std::string& config_path) {
    return config_path.empty() ? default_ocio_config_path() : config_path;
}

OCIO::ConstConfigRcPtr load_config(const std::string& path) {
    if (!file_exists(path))
        throw_input_error(path + ": cannot read OCIO config");
    return OCIO::Config::CreateFromFile(path.c_str());
}

std::string display_or_default(const OCIO::Config& config, const std::string& display,
                               const std::string& path) {
    if (display.empty())
        return config.getDefaultDisplay();
    for (int i = 0; i < config.getNumDisplays(); ++i) {
        if (display == config.getDisplay(i))
            return display;
    }
    throw_input_error(path + ": no display '" + display + "' in OCIO config");
}

std::string view_or_default(const OCIO::Config& config, const std::string& display,
                            const std::string& view, const std::string& path) {
    if (view.empty())
        return config.getDefaultView(display.c_str());
    for (int i = 0; i < config.getNumViews(display.c_str()); ++i) {
        if (view == config.getView(display.c_str(), i))
            return view;
    }
    throw_input_error(path + ": no view '" + view + "' for display '" + display +
                      "' in OCIO config");
}

std::string linear_rec709_space(const OCIO::Config& config, const std::string& path) {
    for (const char* name : kLinearRec709Names) {
        if (OCIO::ConstColorSpaceRcPtr space = config.getColorSpace(name))
            return space->getName();
    }
    throw_input_error(path +
                      ": OCIO config has no linear Rec.709 colour space (named or "
                      "aliased lin_rec709)");
}

OCIO::ConstCPUProcessorRcPtr display_processor(const PreviewSettings& settings,
                                               const std::string& path) {
    OCIO::ConstConfigRcPtr config = load_config(path);
    const std::string display = display_or_default(*config, settings.display, path);
    const std::string view = view_or_default(*config, display, settings.view, path);
    OCIO::DisplayViewTransformRcPtr transform = OCIO::DisplayViewTransform::Create();
    transform->setSrc(linear_rec709_space(*config, path).c_str());
    transform->setDisplay(display.c_str());
    transform->setView(view.c_str());
    return config->getProcessor(transform)->getDefaultCPUProcessor();
}

/// Runs `body`, turning OCIO's exceptions into kasumi errors that name the config.
template <typename Body>
auto with_ocio_errors(const std::string& path, Body&& body) -> decltype(body()) {
    try {
        return body();
    } catch (const OCIO::Exception& e) {
        throw_input_error(path + ": OCIO: " + e.what());
    }
}

std::string executable_dir() {
    std::string buffer(4096, '\0');
    const ssize_t n = ::readlink("/proc/self/exe", buffer.data(), buffer.size() - 1);
    if (n <= 0)
        return {};
    buffer.resize(static_cast<size_t>(n));
    const size_t slash = buffer.find_last_of('/');
    return slash == std::string::npos ? std::string() : buffer.substr(0, slash);
}

}  // namespace

void apply_display_view(std::vector<float>& rgb, const PreviewSettings& settings) {
    const std::string path = resolve_config_path(settings.config_path);
    if (rgb.empty())
        return;
    const float gain = std::exp2(settings.exposure_stops);
    if (gain != 1.0f) {
        for (float& v : rgb)
            v *= gain;
    }
    with_ocio_errors(path, [&] {
        OCIO::ConstCPUProcessorRcPtr processor = display_processor(settings, path);
        OCIO::PackedImageDesc desc(rgb.data(), static_cast<long>(rgb.size() / 3), 1, 3);
        processor->apply(desc);
    });
}

void write_preview_png(const Image& image, const std::string& png_path,
                       const PreviewSettings& settings) {
    write_png_rgb8(image.width, image.height,
                   display_rgb8(image, settings, "write_preview_png: " + png_path), png_path,
                   preview_png_text(settings));
}

std::vector<std::string> list_displays(const std::string& config_path) {
    const std::string path = resolve_config_path(config_path);
    return with_ocio_errors(path, [&] {
        OCIO::ConstConfigRcPtr config = load_config(path);
        std::vector<std::string> displays{config->getDefaultDisplay()};
        for (int i = 0; i < config->getNumDisplays(); ++i) {
            if (displays.front() != config->getDisplay(i))
                displays.emplace_back(config->getDisplay(i));
        }
        return displays;
    });
}

std::vector<std::string> list_views(const std::string& config_path, const std::string& display) {
    const std::string path = resolve_config_path(config_path);
    return with_ocio_errors(path, [&] {
        OCIO::ConstConfigRcPtr config = load_config(path);
        const std::string name = display_or_default(*config, display, path);
        std::vector<std::string> views{config->getDefaultView(name.c_str())};
        for (int i = 0; i < config->getNumViews(name.c_str()); ++i) {
            if (views.front() != config->getView(name.c_str(), i))
                views.emplace_back(config->getView(name.c_str(), i));
        }
        return views;
    });
}

std::string default_ocio_config_path() {
    if (const char* env = std::getenv("KASUMI_OCIO"); env && *env)
        return env;
    std::vector<std::string> tried;
#ifdef KASUMI_OCIO_SOURCE_CONFIG
    tried.emplace_back(KASUMI_OCIO_SOURCE_CONFIG);
#endif
    const std::string exe_dir = executable_dir();
    if (!exe_dir.empty())
        tried.push_back(exe_dir + "/../share/kasumi/ocio/config.ocio");
    for (const std::string& candidate : tried) {
        if (file_exists(candidate))
            return candidate;
    }
    std::string message = "no OCIO config found: set $KASUMI_OCIO (tried";
    for (const std::string& candidate : tried)
        message += " " + candidate;
    throw_input_error(message + ")");
}

}  // namespace kasumi
