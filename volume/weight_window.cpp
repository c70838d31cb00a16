#include "volume/weight_window.h"

#include "volume/light_cache.h"

#include <algorithm>
#include <cmath>

namespace kasumi {

float sun_importance(const MediumSet& media, const std::vector<Light>& lights,
                     const Vec3& p_world) {
    float importance = 0.0f;
    for (size_t i = 0; i < lights.size(); ++i) {
        const LightTransmittanceCache* cache = media.light_cache(i, lights[i]);
        if (cache == nullptr)
            continue;
        const auto* sun = std::get_if<DirectionalLight>(&lights[i].emitter);
        // Scattering vertices lie in the grid: outside the lattice is only its rim, taken as lit.
        const Rgb t = cache->transmittance(p_world).value_or(Rgb(1.0f));
        importance +=
            luminance(sun->illuminance) *
            (kImportanceFloor + std::pow((t.r + t.g + t.b) * (1.0f / 3.0f), kTransportExponent));
    }
    return importance > 0.0f ? importance : 1.0f;
}

float guided_expected(const GuidingField& field, const Vec3& p_world, const Vec3& wo, float sigma_s,
                      float beta) {
    const float scattered = field.scattered_radiance(p_world, wo);
    if (!(scattered >= 0.0f))
        return -1.0f;
    return beta * sigma_s * scattered;
}

float window_ratio(float expected, float centre) {
    if (!(expected >= 0.0f) || !(centre > 0.0f) || !std::isfinite(expected) ||
        !std::isfinite(centre))
        return 1.0f;
    return std::max(expected / centre, kMinSurvival);
}

SplitDecision split_decision(float q, float u) {
    if (!(q > 0.0f) || !std::isfinite(q))
        return {0, 0.0f};
    if (q >= 0.5f && q <= 2.0f)
        return {1, 1.0f};
    const float clamped = std::clamp(q, kMinSurvival, kMaxCopies);
    const float whole = std::floor(clamped);
    const int copies = static_cast<int>(whole) + (u < clamped - whole ? 1 : 0);
    return {copies, 1.0f / clamped};
}

}  // namespace kasumi
