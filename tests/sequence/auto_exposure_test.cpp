// Auto exposure's metering (core/exposure_meter.h) and smoothing (sequence/auto_exposure.h)
// against exact answers: the log average of known pixels, the clamp, and the smoothing's
// response to constant light and to a 10x step.
#include "sequence/auto_exposure.h"
#include "core/exposure_meter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace kasumi {
namespace {

TEST(ExposureMeter, LogAverageOfGreyPixelsIsTheirLuminance) {
    // Y = 100 and 1 cd/m2 on half the pixels each: log2 average = mean of log2(delta + Y).
    const std::vector<float> grey = {100.0f, 100.0f, 1.0f, 1.0f};
    const double expected =
        0.5 * (std::log2(100.0 + kMeterDeltaCdM2) + std::log2(1.0 + kMeterDeltaCdM2));
    EXPECT_NEAR(log2_average_luminance(grey.data(), grey.data(), grey.data(), 4), expected, 1e-12);
}

TEST(ExposureMeter, NonFinitePixelsAreLeftOut) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    const std::vector<float> r = {10.0f, nan, inf}, g = {10.0f, 1.0f, 1.0f},
                             b = {10.0f, 1.0f, 1.0f};
    EXPECT_DOUBLE_EQ(log2_average_luminance(r.data(), g.data(), b.data(), 3),
                     std::log2(10.0 + kMeterDeltaCdM2));
    EXPECT_DOUBLE_EQ(log2_average_luminance(r.data() + 1, g.data(), b.data(), 0),
                     std::log2(kMeterDeltaCdM2));
}

TEST(ExposureMeter, ExposureTakesTheAverageToTheKeyWithinTheRange) {
    // 0.18 * 2^-10 cd/m2 exposed by +10 stops is middle grey.
    EXPECT_NEAR(metered_exposure_stops(std::log2(0.18) - 10.0), 10.0f, 1e-5f);
    EXPECT_NEAR(metered_exposure_stops(std::log2(0.18) + 5.0), -5.0f, 1e-5f);
    EXPECT_EQ(metered_exposure_stops(100.0), kAutoExposureMinStops);
    EXPECT_EQ(metered_exposure_stops(-100.0), kAutoExposureMaxStops);
}

TEST(AutoExposureSmoothing, ConstantLightGivesItsMeteringExactly) {
    const double m = std::log2(737.3);
    for (int64_t frame : {0, 1, 5, 23, 24, 1000})
        EXPECT_EQ(smoothed_log2_luminance(frame, [&](int64_t) { return m; }), m) << frame;
}

TEST(AutoExposureSmoothing, TenfoldDarkerSettlesAtLog2TenStopsAfterTheWindow) {
    const int64_t step = 100;  // frames >= step are 10x darker
    const auto meter = [&](int64_t f) { return f < step ? std::log2(500.0) : std::log2(50.0); };
    const double before = smoothed_log2_luminance(step - 1, meter);
    const double settled = smoothed_log2_luminance(step + kAutoExposureWindowFrames - 1, meter);
    EXPECT_NEAR(metered_exposure_stops(settled) - metered_exposure_stops(before), std::log2(10.0),
                1e-5);
    // Between, it moves monotonically, a first-order response: 1 - e^-1 of the way after
    // about one time constant (the truncated window shifts it a little).
    double last = before;
    for (int64_t f = step; f < step + kAutoExposureWindowFrames; ++f) {
        const double now = smoothed_log2_luminance(f, meter);
        EXPECT_LT(now, last) << f;
        last = now;
    }
    const double after_tau = smoothed_log2_luminance(
        step + static_cast<int64_t>(kAutoExposureTimeConstantFrames) - 1, meter);
    const double fraction = (before - after_tau) / (before - settled);
    EXPECT_GT(fraction, 0.55);
    EXPECT_LT(fraction, 0.75);
}

TEST(AutoExposureSmoothing, FramesBeforeZeroAreNotAsked) {
    const double value = smoothed_log2_luminance(3, [](int64_t f) {
        EXPECT_GE(f, 0);
        return static_cast<double>(f);
    });
    EXPECT_LT(value, 3.0);
    EXPECT_GT(value, 0.0);
}

}  // namespace
}  // namespace kasumi
