#pragma once
/// The camera ray of one pixel sample and the generator that continues it, both from the key
/// (pixel, sample, frame, seed): what makes images independent of thread count and tile order.
#include "core/rng.h"
#include "render/scene_runtime.h"

namespace kasumi {

struct CameraSample {
    Ray ray;
    Pcg32 rng;
};

/// Sample `sample` of pixel (x, y): jittered in the pixel unless film.jitter is false.
inline CameraSample camera_sample(const SceneRuntime& scene, int x, int y, int sample,
                                  uint32_t frame) {
    Pcg32 rng = pixel_rng(static_cast<uint32_t>(x), static_cast<uint32_t>(y),
                          static_cast<uint32_t>(sample), frame, scene.desc().render.seed);
    Vec2 jitter = rng.next_vec2();
    if (!scene.desc().film.jitter)
        jitter = Vec2(0.5f);
    const Ray ray = scene.camera().generate_ray(static_cast<float>(x) + jitter.x,
                                                static_cast<float>(y) + jitter.y);
    return {ray, rng};
}

}  // namespace kasumi
