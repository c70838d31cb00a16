// Compares two renders of one scene (e.g. shadow maps against ray-traced shadows) by the
// luminance of their beauty pixels (R, G, B): prints one JSON object with the fraction of
// pixels that differ by more than `--threshold` (relative to the larger of the two, default
// 0.01) and the RMSE (cd/m²) and relative RMSE (RMSE / mean luminance of the reference).
// Usage: shadow_compare reference.exr test.exr [threshold]
#include "core/color.h"
#include "core/error.h"
#include "core/exr_io.h"

#include <cmath>
#include <cstdio>
#include <string>

namespace {

std::vector<float> luminance_of(const kasumi::Image& image) {
    const auto* r = image.find("R");
    const auto* g = image.find("G");
    const auto* b = image.find("B");
    if (r == nullptr || g == nullptr || b == nullptr)
        throw std::runtime_error("no R, G, B channels");
    std::vector<float> y(r->data.size());
    for (size_t i = 0; i < y.size(); ++i)
        y[i] = kasumi::luminance(kasumi::Rgb(r->data[i], g->data[i], b->data[i]));
    return y;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: shadow_compare reference.exr test.exr [threshold]\n");
        return 2;
    }
    try {
        const double threshold = argc > 3 ? std::stod(argv[3]) : 0.01;
        const kasumi::Image a = kasumi::read_exr(argv[1]);
        const kasumi::Image b = kasumi::read_exr(argv[2]);
        if (a.width != b.width || a.height != b.height)
            throw std::runtime_error("the images differ in size");
        const std::vector<float> ya = luminance_of(a), yb = luminance_of(b);
        double sum2 = 0.0, mean = 0.0;
        size_t differ = 0;
        for (size_t i = 0; i < ya.size(); ++i) {
            const double d = static_cast<double>(yb[i]) - ya[i];
            sum2 += d * d;
            mean += ya[i];
            if (std::abs(d) > threshold * std::max(std::abs(ya[i]), std::abs(yb[i])))
                ++differ;
        }
        const double n = static_cast<double>(ya.size());
        const double rmse = std::sqrt(sum2 / n);
        std::printf(
            "{\"pixels\": %zu, \"differ_fraction\": %.6g, \"rmse\": %.6g, \"relative_rmse\": "
            "%.6g}\n",
            ya.size(), differ / n, rmse, mean > 0.0 ? rmse / (mean / n) : 0.0);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "shadow_compare: %s\n", e.what());
        return 1;
    }
    return 0;
}
