#include "volume/grid/cloud_noise.h"

#include "core/error.h"
#include "core/rng.h"

#include <thread>

namespace kasumi {

namespace {

struct Puff {
    Vec3 center;
    float radius;
};

/// Hash of a lattice point to [0, 1).
float lattice(int x, int y, int z, uint64_t seed) {
    const uint64_t h = mix64(seed ^ mix64((static_cast<uint64_t>(static_cast<uint32_t>(x)) << 42) ^
                                          (static_cast<uint64_t>(static_cast<uint32_t>(y)) << 21) ^
                                          static_cast<uint32_t>(z)));
    return static_cast<float>(h >> 40) * 0x1p-24f;
}

/// Quintic fade (Perlin 2002): C2-continuous value noise.
float fade(float t) {
    return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f);
}

float value_noise(const Vec3& p, uint64_t seed) {
    const Vec3 f = glm::floor(p);
    const IVec3 i(f);
    const Vec3 w = p - f;
    const Vec3 s(fade(w.x), fade(w.y), fade(w.z));
    float c[2][2][2];
    for (int dz = 0; dz < 2; ++dz)
        for (int dy = 0; dy < 2; ++dy)
            for (int dx = 0; dx < 2; ++dx)
                c[dz][dy][dx] = lattice(i.x + dx, i.y + dy, i.z + dz, seed);
    const auto lerp = [](float a, float b, float t) { return a + t * (b - a); };
    const float y0 =
        lerp(lerp(c[0][0][0], c[0][0][1], s.x), lerp(c[0][1][0], c[0][1][1], s.x), s.y);
    const float y1 =
        lerp(lerp(c[1][0][0], c[1][0][1], s.x), lerp(c[1][1][0], c[1][1][1], s.x), s.y);
    return lerp(y0, y1, s.z);
}

/// Fractal Brownian motion in [0, 1): octaves of value noise, each double the frequency and
/// half the amplitude of the last.
float fbm(const Vec3& p, int octaves, uint64_t seed) {
    float sum = 0.0f, amplitude = 0.5f, norm = 0.0f;
    Vec3 q = p;
    for (int o = 0; o < octaves; ++o) {
        sum += amplitude * value_noise(q, seed + static_cast<uint64_t>(o) * 0x9e3779b9u);
        norm += amplitude;
        amplitude *= 0.5f;
        q *= 2.03f;  // not exactly 2: keeps octave lattices from lining up
    }
    return sum / norm;
}

float smoothstep(float a, float b, float x) {
    const float t = std::clamp((x - a) / (b - a), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

}  // namespace

DenseVoxels make_cumulus(const CloudParams& params) {
    KASUMI_CHECK(params.res >= 8 && params.octaves >= 1);
    const int n = params.res;
    Pcg32 rng(params.seed, 0x636c6f7564ULL);
    // A wide main body on a flat base, with smaller puffs piled on top and at the sides.
    std::vector<Puff> puffs{{Vec3(0.5f, 0.36f, 0.5f), 0.2f}};
    for (int i = 0; i < 10; ++i) {
        const float angle = kTwoPi * rng.next_float();
        const float reach = 0.08f + 0.14f * rng.next_float();
        const float radius = 0.09f + 0.08f * rng.next_float();
        const float height = 0.34f + 0.22f * rng.next_float() * (1.0f - reach / 0.25f);
        puffs.push_back(
            {Vec3(0.5f + reach * std::cos(angle), height, 0.5f + reach * 0.8f * std::sin(angle)),
             radius});
    }
    const float base = 0.25f;
    const uint64_t noise_seed = mix64(params.seed);
    const float noise_scale = 5.0f;
    const float erosion = 0.45f;  // how far noise can push the surface, in puff radii

    DenseVoxels voxels;
    voxels.dims = IVec3(n);
    voxels.values.assign(static_cast<size_t>(n) * n * n, 0.0f);
    auto slab = [&](int z_begin, int z_end) {
        for (int z = z_begin; z < z_end; ++z)
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x) {
                    const Vec3 p = (Vec3(x, y, z) + 0.5f) / static_cast<float>(n);
                    if (p.y < base)
                        continue;
                    // Union of puffs as 1 - distance / radius (> 0 inside).
                    float shape = -1e9f;
                    for (const Puff& puff : puffs)
                        shape = std::max(shape, 1.0f - glm::length(p - puff.center) / puff.radius);
                    if (shape < -erosion)
                        continue;  // noise cannot reach this far out: stays exactly 0
                    const float noise = fbm(p * noise_scale, params.octaves, noise_seed);
                    const float field = shape - erosion * (1.0f - noise) + 0.5f * erosion * 0.6f;
                    const float density =
                        smoothstep(0.0f, 0.25f, field) * smoothstep(base, base + 0.04f, p.y);
                    voxels.values[x + static_cast<size_t>(n) * (y + static_cast<size_t>(n) * z)] =
                        density;
                }
    };
    const int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t)
        pool.emplace_back(slab, n * t / threads, n * (t + 1) / threads);
    for (std::thread& th : pool)
        th.join();
    return voxels;
}

}  // namespace kasumi
