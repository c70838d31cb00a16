#pragma once
/// The lights of one marched camera ray (volume/march_single.cpp, volume/debiased_march_single.h):
/// per-ray records of the directional lights (their incident light and scattering cosine are the
/// same at every node; their light cache's lattice line), and the light scattered toward the eye
/// at one node, with the directional lights' transmittance left to the caller.
#include "core/occlusion_query.h"
#include "core/rng.h"
#include "lights/light.h"
#include "volume/in_scattering.h"
#include "volume/light_cache.h"
#include "volume/medium_set.h"
#include "volume/scattered_direct.h"

#include <vector>

namespace kasumi {

/// One light's record for a marched ray; for a directional light also its incident light,
/// the scattering cosine mu toward the eye and (when cached) its cache and the ray's line in it.
struct MarchLight {
    size_t index = 0;
    bool directional = false;
    IncidentLight incident;
    float mu = 0.0f;
    const LightTransmittanceCache* cache = nullptr;
    LightTransmittanceCache::Line line;
};

/// The records of every light for RAY seen from wo = -ray.direction, in the scene's order;
/// directional lights that send no light are left out. One sample_incident per directional
/// light (a delta light draws no random number). `with_cache`: look up each directional light's
/// transmittance cache (null where the set has none).
inline void collect_march_lights(const MediumSet& media, const std::vector<Light>& lights,
                                 const Ray& ray, bool with_cache, Pcg32& rng,
                                 std::vector<MarchLight>& out) {
    out.clear();
    const Vec3 wo = -ray.direction;
    for (size_t i = 0; i < lights.size(); ++i) {
        MarchLight m;
        m.index = i;
        if (std::holds_alternative<DirectionalLight>(lights[i].emitter)) {
            m.directional = true;
            m.incident = sample_incident(lights[i], ray.origin, rng);
            if (is_black(m.incident.irradiance))
                continue;
            m.mu = scattering_cosine(wo, m.incident.wi);
            if (with_cache) {
                m.cache = media.light_cache(i, lights[i]);
                if (m.cache != nullptr)
                    m.line = m.cache->line(ray.origin, ray.direction);
            }
        }
        out.push_back(m);
    }
}

/// Light scattered toward wo at node x (distance t along the ray) per unit length
/// (1/m · cd/m²): scattered_direct_one for the lights that are not directional, and for each
/// directional one `directional(m, f)` with f = sigma_s p(mu) at x (its E T V is the caller's).
/// `k`: the coefficients at x (one medium in `mask`: its sigma_s is k's, no second lookup).
template <class Directional>
Rgb march_node_light(const MediumSet& media, const std::vector<Light>& lights,
                     const std::vector<MarchLight>& march_lights, const OcclusionQuery* occlusion,
                     const Vec3& x, const PointCoefficients& k, uint32_t mask, const Vec3& wo,
                     const VolumeSettings& settings, float step, Pcg32& rng,
                     VolumeCounters& counters, Directional&& directional) {
    Rgb direct(0.0f);
    for (const MarchLight& m : march_lights) {
        if (!m.directional) {
            direct += scattered_direct_one(media, lights[m.index], m.index, occlusion, x, mask, wo,
                                           settings, step, rng, counters);
            continue;
        }
        if ((mask & (mask - 1)) != 0)
            ++counters.density_lookups;
        direct += directional(m, media.scattering(k, x, mask, m.mu));
    }
    return direct;
}

}  // namespace kasumi
