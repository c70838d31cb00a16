#pragma once
/// PCG32 random numbers (O'Neill 2014, "PCG: A Family of Simple Fast Space-Efficient
/// Statistically Good Algorithms for Random Number Generation", pcg32 XSH-RR 64/32).
/// Streams are keyed by (pixel, sample, frame, seed) so images do not depend on thread count
/// or tile order.
#include "core/math.h"

#include <cstdint>

namespace kasumi {

class Pcg32 {
  public:
    Pcg32(uint64_t seed, uint64_t stream) { set_sequence(seed, stream); }

    void set_sequence(uint64_t seed, uint64_t stream) {
        m_state = 0u;
        m_inc = (stream << 1u) | 1u;
        next_u32();
        m_state += seed;
        next_u32();
    }

    uint32_t next_u32() {
        const uint64_t old = m_state;
        m_state = old * 6364136223846793005ULL + m_inc;
        const auto xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
        const auto rot = static_cast<uint32_t>(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31u));
    }

    /// Uniform in [0, 1): 24 random mantissa bits, so 1 is never returned.
    float next_float() { return static_cast<float>(next_u32() >> 8) * 0x1p-24f; }
    /// Uniform in [0, 1) with 53 bits.
    double next_double() {
        const uint64_t hi = next_u32() >> 5, lo = next_u32() >> 6;
        return static_cast<double>((hi << 26) | lo) * 0x1p-53;
    }
    Vec2 next_vec2() {
        const float a = next_float();
        return Vec2(a, next_float());
    }

  private:
    uint64_t m_state = 0;
    uint64_t m_inc = 1;
};

/// Mixes a key into 64 bits (SplitMix64 finaliser, Steele et al. 2014).
inline uint64_t mix64(uint64_t x) {
    x += 0x9e3779b97f4a7c15ULL;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
}

/// The generator for one pixel sample: independent of how pixels are scheduled.
inline Pcg32 pixel_rng(uint32_t x, uint32_t y, uint32_t sample, uint32_t frame, uint64_t seed) {
    const uint64_t pixel = (static_cast<uint64_t>(y) << 32) | x;
    const uint64_t key =
        mix64(pixel ^ mix64(seed)) ^ mix64((static_cast<uint64_t>(frame) << 32) | sample);
    return Pcg32(mix64(key), mix64(key ^ 0x5851f42d4c957f2dULL));
}

}  // namespace kasumi
