#include "core/exr_half.h"

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include <algorithm>
#include <cstdio>

namespace kasumi {

namespace {

/// Rounds `n` floats to half (Imath: to nearest, ties to even), saturating |v| > 65504 to
/// +-65504 (Imath would give infinity from 65520 on) and counting the non-zero values flushed
/// to zero (see ExrPixelType). Finite values only (checked first).
void convert_to_half_scalar(const float* from, size_t n, Imath::half* to, ExrWriteReport& report) {
    for (size_t i = 0; i < n; ++i) {
        const float v = std::clamp(from[i], -kHalfMax, kHalfMax);
        to[i] = Imath::half(v);
        if (v != 0.0f && (to[i].bits() & 0x7fffu) == 0)  // +-0 from a non-zero value
            ++report.half_flushed_to_zero;
    }
}

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define KASUMI_EXR_F16C 1
static_assert(sizeof(Imath::half) == 2, "the F16C path stores 16-bit halves");
/// The same 8 values at a time with the F16C instruction VCVTPS2PH in round-to-nearest-even
/// mode: IEEE 754 binary32 -> binary16 rounding, which is what Imath's software conversion
/// computes (and what Imath itself uses when built for F16C), so the same bits; ~10x fewer
/// instructions (the conversion was 8% of a 640x480 render's). Clamping first keeps the
/// saturation rule; a lane can only flush to zero when 0 < |v| < 2^-24, checked per block.
__attribute__((target("avx,f16c"))) void convert_to_half_f16c(const float* from, size_t n,
                                                              Imath::half* to,
                                                              ExrWriteReport& report) {
    const __m256 high = _mm256_set1_ps(kHalfMax), low = _mm256_set1_ps(-kHalfMax);
    const __m256 sign = _mm256_set1_ps(-0.0f), tiny = _mm256_set1_ps(0x1p-24f);
    const __m256 zero = _mm256_setzero_ps();
    size_t i = 0;
    for (; i + 8 <= n; i += 8) {
        const __m256 v = _mm256_min_ps(_mm256_max_ps(_mm256_loadu_ps(from + i), low), high);
        const __m128i h = _mm256_cvtps_ph(v, _MM_FROUND_TO_NEAREST_INT);
        _mm_storeu_si128(reinterpret_cast<__m128i*>(to + i), h);
        const __m256 magnitude = _mm256_andnot_ps(sign, v);
        const int small = _mm256_movemask_ps(_mm256_and_ps(
            _mm256_cmp_ps(magnitude, tiny, _CMP_LT_OQ), _mm256_cmp_ps(v, zero, _CMP_NEQ_OQ)));
        if (small != 0) {
            for (int k = 0; k < 8; ++k)
                if (((small >> k) & 1) != 0 && (to[i + k].bits() & 0x7fffu) == 0)
                    ++report.half_flushed_to_zero;
        }
    }
    convert_to_half_scalar(from + i, n - i, to + i, report);
}
#endif

}  // namespace

void convert_to_half(const float* from, size_t n, Imath::half* to, ExrWriteReport& report) {
#if defined(KASUMI_EXR_F16C)
    static const bool f16c = __builtin_cpu_supports("avx") && __builtin_cpu_supports("f16c");
    if (f16c) {
        convert_to_half_f16c(from, n, to, report);
        return;
    }
#endif
    convert_to_half_scalar(from, n, to, report);
}

std::vector<std::pair<std::string, std::string>> exr_string_attributes(const Image& image,
                                                                       bool any_half,
                                                                       const ExrWriteReport& half) {
    std::vector<std::pair<std::string, std::string>> attributes;
    for (const auto& kv : image.metadata)
        attributes.emplace_back(kExrMetadataPrefix + kv.first, kv.second);
    if (any_half) {
        char max_abs[32];
        std::snprintf(max_abs, sizeof max_abs, "%.9g", static_cast<double>(half.half_max_abs));
        attributes.emplace_back(std::string(kExrMetadataPrefix) + "half/saturated",
                                std::to_string(half.half_saturated));
        attributes.emplace_back(std::string(kExrMetadataPrefix) + "half/max_abs", max_abs);
    }
    return attributes;
}

}  // namespace kasumi
