#pragma once
/// What both EXR writers share (core/exr_io.cpp writes ZIP through OpenEXR's core library, the
/// OpenEXR module core/exr_imf.cpp the other compressions through Imf): the float to half
/// conversion and the string attributes of the header. Compiled into kasumi_core and the module.
#include "core/exr_io.h"

#include <half.h>

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace kasumi {

/// Rounds `n` floats to half (Imath: to nearest, ties to even), saturating |v| > 65504 to
/// +-65504 (Imath would give infinity from 65520 on) and counting the non-zero values flushed
/// to zero (see ExrPixelType) in `report`. Finite values only (checked first).
void convert_to_half(const float* from, size_t n, Imath::half* to, ExrWriteReport& report);

/// The string attributes of the header of `image`: its metadata as "kasumi/<key>" and, when any
/// channel is HALF, what `half` says of them ("kasumi/half/saturated", "kasumi/half/max_abs":
/// in the file itself, a reader sees whether values were saturated, and from what).
std::vector<std::pair<std::string, std::string>> exr_string_attributes(const Image& image,
                                                                       bool any_half,
                                                                       const ExrWriteReport& half);

}  // namespace kasumi
