#pragma once
/// For tests: one camera ray traced through two scenes with generators of the same seed and
/// stream, so that their samples can be compared bit for bit.
#include "render/integrator.h"

namespace kasumi {

struct TracedPair {
    PixelSample a, b;
    RenderCounters counters_a, counters_b;
};

inline TracedPair trace_pair(const SceneRuntime& scene_a, const SceneRuntime& scene_b,
                             const Ray& ray, uint64_t seed, uint64_t stream) {
    TracedPair p;
    Pcg32 rng_a(seed, stream), rng_b(seed, stream);
    p.a = trace_camera_ray(scene_a, ray, rng_a, p.counters_a);
    p.b = trace_camera_ray(scene_b, ray, rng_b, p.counters_b);
    return p;
}

}  // namespace kasumi
