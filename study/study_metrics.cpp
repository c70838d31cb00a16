#include "study/study_metrics.h"

#include "core/error.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace kasumi {

namespace {

void require_same_size(const RgbPlane& a, const RgbPlane& b) {
    if (a.width != b.width || a.height != b.height || a.pixels.size() != b.pixels.size()) {
        throw_input_error("images differ in size: " + std::to_string(a.width) + "x" +
                          std::to_string(a.height) + " against " + std::to_string(b.width) + "x" +
                          std::to_string(b.height));
    }
}

double channel(const Rgb& c, int i) {
    return i == 0 ? c.r : i == 1 ? c.g : c.b;
}

/// An ImageError holding the scales set by a reference of mean luminance y_mean: eps, which
/// regularises the relative MSE, and the luminance floor of the max relative error.
ImageError scaled_by(double y_mean, const ErrorSettings& settings) {
    ImageError e;
    e.eps = std::pow(settings.eps_fraction * y_mean, 2.0);
    e.luminance_floor = settings.floor_fraction * y_mean;
    return e;
}

/// The eps the relative MSE divides by: a black reference has no scale, so an absolute eps
/// keeps rel_mse finite.
double relative_eps(const ImageError& e) {
    return e.eps > 0.0 ? e.eps : 1e-12;
}

/// Sets rmse and rel_mse from sums of squared and relative squared errors over the three
/// channels of `pixels` pixels.
void set_means(ImageError& e, double squared, double relative, size_t pixels) {
    const double n = 3.0 * static_cast<double>(std::max<size_t>(pixels, 1));
    e.rmse = std::sqrt(squared / n);
    e.rel_mse = relative / n;
}

}  // namespace

RgbPlane rgb_plane(const Image& image, const std::string& what) {
    const ImageChannel* r = image.find("R");
    const ImageChannel* g = image.find("G");
    const ImageChannel* b = image.find("B");
    if (r == nullptr || g == nullptr || b == nullptr)
        throw_input_error(what + ": no R, G, B channels");
    RgbPlane plane{image.width, image.height, {}};
    plane.pixels.resize(static_cast<size_t>(image.width) * image.height);
    for (size_t i = 0; i < plane.pixels.size(); ++i)
        plane.pixels[i] = Rgb(r->data[i], g->data[i], b->data[i]);
    return plane;
}

double mean_luminance(const RgbPlane& image) {
    double sum = 0.0;
    for (const Rgb& c : image.pixels)
        sum += luminance(c);
    return image.pixels.empty() ? 0.0 : sum / static_cast<double>(image.pixels.size());
}

RgbPlane average(const RgbPlane& a, const RgbPlane& b) {
    require_same_size(a, b);
    RgbPlane out{a.width, a.height, std::vector<Rgb>(a.pixels.size())};
    for (size_t i = 0; i < a.pixels.size(); ++i)
        out.pixels[i] = (a.pixels[i] + b.pixels[i]) * 0.5f;
    return out;
}

ImageError image_error(const RgbPlane& test, const RgbPlane& reference,
                       const ErrorSettings& settings) {
    require_same_size(test, reference);
    const double y_mean = mean_luminance(reference);
    ImageError e = scaled_by(y_mean, settings);
    const double eps = relative_eps(e);
    double squared = 0.0, relative = 0.0;
    for (size_t i = 0; i < test.pixels.size(); ++i) {
        const Rgb& a = test.pixels[i];
        const Rgb& b = reference.pixels[i];
        for (int c = 0; c < 3; ++c) {
            const double d = channel(a, c) - channel(b, c);
            squared += d * d;
            relative += d * d / (channel(b, c) * channel(b, c) + eps);
        }
        const double y_ref = luminance(b);
        if (y_ref > e.luminance_floor && y_ref > 0.0) {
            ++e.pixels_above_floor;
            e.max_rel_luminance =
                std::max(e.max_rel_luminance, std::abs(double(luminance(a)) - y_ref) / y_ref);
        }
    }
    set_means(e, squared, relative, test.pixels.size());
    e.mean_luminance_error = y_mean > 0.0 ? (mean_luminance(test) - y_mean) / y_mean : 0.0;
    return e;
}

ImageError reference_standard_error(const RgbPlane& a, const RgbPlane& b,
                                    const ErrorSettings& settings) {
    require_same_size(a, b);
    const RgbPlane mean = average(a, b);
    ImageError e = scaled_by(mean_luminance(mean), settings);
    const double eps = relative_eps(e);
    double variance = 0.0, relative = 0.0;
    for (size_t i = 0; i < a.pixels.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            const double d = channel(a.pixels[i], c) - channel(b.pixels[i], c);
            const double m = channel(mean.pixels[i], c);
            variance += d * d / 4.0;
            relative += d * d / 4.0 / (m * m + eps);
        }
    }
    set_means(e, variance, relative, a.pixels.size());
    return e;
}

std::vector<size_t> pareto_front(const std::vector<double>& time,
                                 const std::vector<double>& error) {
    KASUMI_CHECK(time.size() == error.size());
    std::vector<size_t> order(time.size());
    std::iota(order.begin(), order.end(), size_t{0});
    // By time, then error, then index: a sweep keeps each point whose error is below every
    // faster (or equally fast, listed earlier) point's.
    std::stable_sort(order.begin(), order.end(), [&](size_t i, size_t j) {
        return time[i] != time[j] ? time[i] < time[j] : error[i] < error[j];
    });
    std::vector<size_t> front;
    double best = INFINITY;
    for (size_t i : order) {
        if (error[i] < best) {
            front.push_back(i);
            best = error[i];
        }
    }
    return front;
}

}  // namespace kasumi
