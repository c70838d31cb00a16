#include "core/exposure_meter.h"

#include <algorithm>
#include <cmath>

namespace kasumi {

double log2_average_luminance(const float* r, const float* g, const float* b, size_t pixels) {
    // Summed in double in pixel order: the same frame meters to the same bits on any machine
    // and thread count (a 4K frame has 8e6 terms; float would lose their low digits).
    double sum = 0.0;
    size_t count = 0;
    for (size_t i = 0; i < pixels; ++i) {
        const double y = 0.2126 * r[i] + 0.7152 * g[i] + 0.0722 * b[i];
        if (!std::isfinite(y))
            continue;
        sum += std::log2(kMeterDeltaCdM2 + std::max(0.0, y));
        ++count;
    }
    return count == 0 ? std::log2(kMeterDeltaCdM2) : sum / static_cast<double>(count);
}

float metered_exposure_stops(double log2_luminance) {
    const double stops = std::log2(kExposureKey) - log2_luminance;
    return static_cast<float>(std::clamp(stops, static_cast<double>(kAutoExposureMinStops),
                                         static_cast<double>(kAutoExposureMaxStops)));
}

}  // namespace kasumi
