#include "render/sky_environment.h"

namespace kasumi {

Rgb escaped_radiance(const SceneRuntime& scene, const Ray& ray, bool sun_disc, Pcg32& rng) {
    if (const SkyRenderer* sky = scene.sky())
        return sky->environment(ray, sun_disc, rng);
    return scene.desc().background;
}

Rgb through_air(const SceneRuntime& scene, const Ray& ray, float t_end, const Rgb& behind,
                Pcg32& rng) {
    const SkyRenderer* sky = scene.sky();
    if (sky == nullptr || !(t_end < kInfinity))
        return behind;
    Rgb l_air(0.0f), t_air(1.0f);
    sky->aerial_perspective(ray, t_end, rng, l_air, t_air);
    return l_air + t_air * behind;
}

}  // namespace kasumi
