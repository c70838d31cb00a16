#pragma once
/// Display previews through OpenColorIO (OCIO headers stay in color_management.cpp).
///
/// The renderer's pixels are scene-linear Rec.709 (core/color.h). The preview takes the R, G, B
/// channels from the config's linear Rec.709 colour space (named or aliased `lin_rec709`, as in
/// data/ocio/config.ocio and the ACES CG/studio configs) through a display/view transform.
#include "core/image.h"

#include <cstdint>
#include <string>
#include <vector>

namespace kasumi {

/// How to turn scene-linear pixels into a display-referred 8-bit preview.
struct PreviewSettings {
    std::string config_path;       ///< OCIO config file; empty: default_ocio_config_path()
    std::string display = "sRGB";  ///< OCIO display; empty: the config's default display
    std::string view;              ///< OCIO view; empty: the display's default view
    float exposure_stops = 0;      ///< scene-linear gain 2^stops applied before the view
};

/// Writes an 8-bit RGB PNG of `image`'s R, G, B channels through the OCIO display/view transform
/// of `settings`: display values are clipped to [0, 1] and rounded to the nearest of 0..255.
/// Alpha is ignored. Throws ErrorKind::Input naming the config for an unreadable config or an
/// unknown display/view, ErrorKind::Runtime if R, G or B is missing, ErrorKind::Output naming
/// `png_path` if it cannot be written (atomically, as write_png_rgb8).
void write_preview_png(const Image& image, const std::string& png_path,
                       const PreviewSettings& settings);

/// The 8-bit display RGB (packed, row-major) of `image`'s R, G, B channels through the view of
/// `settings`, clipped and rounded as write_preview_png writes them (a movie frame). Throws
/// ErrorKind::Runtime naming `what` if R, G or B is missing, and the OCIO errors of
/// write_preview_png.
std::vector<uint8_t> display_rgb8(const Image& image, const PreviewSettings& settings,
                                  const std::string& what);

/// Applies the display/view transform of `settings` to scene-linear Rec.709 pixels in place
/// (`rgb` is packed RGB floats), including the exposure; no clipping. What write_preview_png
/// quantises; tests and probes use it directly.
void apply_display_view(std::vector<float>& rgb, const PreviewSettings& settings);

/// The active displays of a config, default first. Throws ErrorKind::Input naming the config.
std::vector<std::string> list_displays(const std::string& config_path);

/// The active views of `display` (empty: the default display) in a config, default first.
/// Throws ErrorKind::Input naming the config if it cannot be read or lacks the display.
std::vector<std::string> list_views(const std::string& config_path, const std::string& display);

/// The OCIO config used when none is given, first found of:
///   1. $KASUMI_OCIO if set and non-empty (returned even if missing: the user asked for it);
///   2. <source dir>/data/ocio/config.ocio, baked in at compile time (KASUMI_OCIO_SOURCE_CONFIG);
///   3. <directory of the running executable>/../share/kasumi/ocio/config.ocio (installed).
/// $OCIO is deliberately not consulted, so a studio-wide config never changes previews unasked.
/// Throws ErrorKind::Input listing the paths tried if none exists.
std::string default_ocio_config_path();

}  // namespace kasumi
