#include "lights/light_samples.h"

namespace kasumi {

namespace {

uint32_t reverse_bits(uint32_t x) {
    x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
    x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
    x = ((x >> 4) & 0x0F0F0F0Fu) | ((x & 0x0F0F0F0Fu) << 4);
    x = ((x >> 8) & 0x00FF00FFu) | ((x & 0x00FF00FFu) << 8);
    return (x >> 16) | (x << 16);
}

/// Burley 2020, listing 3 (improved Laine-Karras hash): a random permutation of 32-bit words in
/// which bit k of the result depends only on bits 0..k of x, i.e. a nested uniform scramble of
/// x read least significant digit first.
uint32_t laine_karras_permutation(uint32_t x, uint32_t seed) {
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return x;
}

/// Owen scrambling of a binary fraction: the permutation above applied to its reversed digits.
uint32_t nested_uniform_scramble(uint32_t x, uint32_t seed) {
    return reverse_bits(laine_karras_permutation(reverse_bits(x), seed));
}

/// Sobol's second dimension (primitive polynomial x + 1): direction numbers v_1 = 2^31,
/// v_k = v_{k−1} ^ (v_{k−1} >> 1).
uint32_t sobol_dimension_1(uint32_t index) {
    uint32_t result = 0;
    for (uint32_t v = 1u << 31; index != 0; index >>= 1, v ^= v >> 1)
        if (index & 1u)
            result ^= v;
    return result;
}

float to_unit_float(uint32_t x) {
    return static_cast<float>(x >> 8) * 0x1p-24f;
}

}  // namespace

Vec2 owen_sobol_2d(uint32_t index, uint32_t seed0, uint32_t seed1) {
    // Dimension 0 is reverse_bits(index); scrambling it reverses the bits back first.
    const uint32_t x = reverse_bits(laine_karras_permutation(index, seed0));
    const uint32_t y = nested_uniform_scramble(sobol_dimension_1(index), seed1);
    return Vec2(to_unit_float(x), to_unit_float(y));
}

float StratifiedLightSamples::rotation() const {
    // A third hash of the seeds (not a Sobol dimension): uniform over the scramble.
    return to_unit_float(laine_karras_permutation(m_seed0 ^ 0x9e3779b9u, m_seed1));
}

PointLightSampler::PointLightSampler(const Light& light, const Vec3& p) : m_light(light), m_p(p) {
    if (const auto* sphere = std::get_if<SphereLight>(&light.emitter))
        m_cone.emplace(*sphere, p);
}

double outline_probe_bound(int k) {
    const double alpha = 2.0 * kPiD / k;
    return (alpha - std::sin(alpha)) / (2.0 * kPiD);
}

}  // namespace kasumi
