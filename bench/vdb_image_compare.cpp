// Error of an image against a reference, for the peer benchmark (bench/vdb_render_bench.py):
//
//   vdb_image_compare REF_A.exr REF_B.exr IMAGE.exr [IMAGE_SCALE]
//
// The reference is the mean of two independent renders A and B (different seeds). Over the R, G,
// B channels of every pixel it prints one JSON object:
//   rmse            sqrt(mean((s·I - (A + B)/2)²)), s = IMAGE_SCALE (default 1)
//   ref_noise_rmse  sqrt(mean((A - B)²) / 4): the reference's own noise, since
//                   Var((A + B)/2) = Var(A)/2 and E[(A - B)²] = 2 Var(A) for independent A, B
//   rmse_corrected  sqrt(max(rmse² - ref_noise_rmse², 0)): the image's error against the
//                   converged answer (the reference noise is independent of the image's error)
//   ref_mean        mean of the reference (for relative figures)
#include "core/error.h"
#include "core/exr_io.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

const std::vector<float>& channel(const kasumi::Image& image, const char* name,
                                  const std::string& path) {
    for (const kasumi::ImageChannel& c : image.channels) {
        if (c.name == name)
            return c.data;
    }
    throw kasumi::Error(kasumi::ErrorKind::Input, path + ": no channel " + name);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 4 && argc != 5) {
        std::fprintf(stderr, "usage: %s REF_A.exr REF_B.exr IMAGE.exr [IMAGE_SCALE]\n", argv[0]);
        return 2;
    }
    try {
        const kasumi::Image a = kasumi::read_exr(argv[1]);
        const kasumi::Image b = kasumi::read_exr(argv[2]);
        const kasumi::Image img = kasumi::read_exr(argv[3]);
        const double scale = argc == 5 ? std::atof(argv[4]) : 1.0;
        if (a.width != b.width || a.height != b.height || a.width != img.width ||
            a.height != img.height) {
            std::fprintf(stderr, "images differ in size\n");
            return 3;
        }
        double se = 0.0, noise = 0.0, sum = 0.0;
        size_t n = 0;
        for (const char* name : {"R", "G", "B"}) {
            const auto& ca = channel(a, name, argv[1]);
            const auto& cb = channel(b, name, argv[2]);
            const auto& ci = channel(img, name, argv[3]);
            for (size_t i = 0; i < ca.size(); ++i) {
                const double ref = 0.5 * (static_cast<double>(ca[i]) + cb[i]);
                const double d = scale * ci[i] - ref;
                se += d * d;
                const double e = static_cast<double>(ca[i]) - cb[i];
                noise += e * e;
                sum += ref;
                ++n;
            }
        }
        const double mse = se / n, noise_mse = noise / n / 4.0;
        std::printf(
            "{\"rmse\": %.9g, \"ref_noise_rmse\": %.9g, \"rmse_corrected\": %.9g, "
            "\"ref_mean\": %.9g}\n",
            std::sqrt(mse), std::sqrt(noise_mse), std::sqrt(std::max(mse - noise_mse, 0.0)),
            sum / n);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 3;
    }
    return 0;
}
