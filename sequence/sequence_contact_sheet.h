#pragma once
/// The contact sheet of a sequence: downscaled frames in a grid, one scene-linear image that
/// the preview path (OCIO view) turns into a PNG like any frame.
#include "core/image.h"

#include <vector>

namespace kasumi {

/// Thumbnail width (pixels) of a contact sheet cell; frames narrower than this keep their size.
inline constexpr int kThumbnailWidth = 160;

/// `image`'s R, G, B box-filtered down to `width` pixels across (never enlarged), the height in
/// proportion (at least 1): each thumbnail pixel is the mean of the frame pixels whose centres
/// fall inside it, so the thumbnail's mean equals the frame's for integer ratios.
Image make_thumbnail(const Image& image, int width = kThumbnailWidth);

/// The thumbnails in rows, in order, with a 2-pixel black gap; the column count makes the sheet
/// about 16:9. A null entry (a missing frame) leaves its cell black. All thumbnails take the
/// first non-null one's cell size (smaller ones sit in the top-left corner, larger are cropped).
Image make_contact_sheet(const std::vector<const Image*>& thumbnails);

}  // namespace kasumi
