#pragma once
/// Error of a rendered image against a reference, and the Pareto front of (time, error) points:
/// the measurements behind `kasumi study` (docs/study.md).
#include "core/color.h"
#include "core/image.h"

#include <cstddef>
#include <string>
#include <vector>

namespace kasumi {

/// The beauty (R, G, B) of an image, row-major, top row first; cd/m² (luminance).
struct RgbPlane {
    int width = 0;
    int height = 0;
    std::vector<Rgb> pixels;
};

/// The R, G, B channels of `image`; throws ErrorKind::Input naming `what` if one is missing.
RgbPlane rgb_plane(const Image& image, const std::string& what);

/// Constants of the metrics, relative to the reference's mean luminance Ybar so that the
/// metrics do not depend on the scene's photometric scale (a cloud at 1e4 cd/m² and a street
/// at night at 1 cd/m² are judged alike).
struct ErrorSettings {
    /// Relative MSE: eps = (eps_fraction * Ybar)^2 in the denominator (a - b)^2 / (b^2 + eps);
    /// keeps black reference pixels from dominating.
    double eps_fraction = 1e-2;
    /// Max relative luminance error: only pixels with reference luminance above
    /// floor_fraction * Ybar count.
    double floor_fraction = 0.1;
};

struct ImageError {
    double rmse = 0.0;  ///< sqrt of the mean over pixels and channels of (a - b)^2, cd/m²
    /// Mean over pixels and channels of (a - b)^2 / (b^2 + eps), eps as in ErrorSettings.
    double rel_mse = 0.0;
    /// max |Y(a) - Y(b)| / Y(b) over pixels with Y(b) > floor (Y: Rec.709 luminance).
    double max_rel_luminance = 0.0;
    /// (Ybar(a) - Ybar(b)) / Ybar(b): relative error of the mean luminance (bias shows here,
    /// noise averages out).
    double mean_luminance_error = 0.0;
    double eps = 0.0;               ///< the eps used, (cd/m²)^2
    double luminance_floor = 0.0;   ///< the floor used, cd/m²
    size_t pixels_above_floor = 0;  ///< pixels that entered max_rel_luminance
};

/// Error of `test` against `reference` (same size, else ErrorKind::Input).
ImageError image_error(const RgbPlane& test, const RgbPlane& reference,
                       const ErrorSettings& settings = {});

/// Mean Rec.709 luminance of an image, cd/m².
double mean_luminance(const RgbPlane& image);

/// Per-pixel mean of two images of the same size.
RgbPlane average(const RgbPlane& a, const RgbPlane& b);

/// How far a reference made as the mean of two independent half-sample renders `a` and `b`
/// is from its own expectation. For independent estimates with equal variance s^2 each,
/// E[(a - b)^2] = 2 s^2 and the mean (a + b) / 2 has variance s^2 / 2 = E[(a - b)^2] / 4, so
/// (a - b)^2 / 4 estimates the squared standard error of every pixel and channel. The fields
/// are those figures entered into the metrics of ImageError (rmse: the RMS standard error,
/// rel_mse: the relative variance); max_rel_luminance is not estimated (0).
ImageError reference_standard_error(const RgbPlane& a, const RgbPlane& b,
                                    const ErrorSettings& settings = {});

/// Indices of the points on the Pareto front of (time, error), both to be minimised: no other
/// point is at most as slow and at most as wrong while better in one of them. Sorted by
/// increasing time (hence decreasing error). Points with equal time and error keep the first.
std::vector<size_t> pareto_front(const std::vector<double>& time, const std::vector<double>& error);

}  // namespace kasumi
