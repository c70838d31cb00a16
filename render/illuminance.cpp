#include "render/illuminance.h"

namespace kasumi {

namespace {

bool visible(const OcclusionQuery& occlusion, const Vec3& origin, const IncidentLight& in) {
    return in.distance >= kInfinity ? !occlusion.occluded_direction(origin, in.wi)
                                    : !occlusion.occluded(origin, in.light_position);
}

LightIlluminance sampled(const OcclusionQuery& occlusion, const Light& light, size_t index,
                         const Vec3& at, const Vec3& normal, int samples, uint64_t seed) {
    LightIlluminance result;
    result.method = IlluminanceMethod::Sampled;
    result.samples = samples;
    Pcg32 rng(mix64(seed ^ mix64(index)), 0x1e1e1e1eu + index);
    double sum = 0.0, sum_sq = 0.0;
    for (int k = 0; k < samples; ++k) {
        const IncidentLight in = sample_incident(light, at, rng.next_vec2());
        const float cos_theta = glm::dot(normal, in.wi);
        double x = 0.0;
        if (cos_theta > 0.0f && !is_black(in.irradiance) &&
            visible(occlusion, offset_ray_origin(at, normal, in.wi), in)) {
            x = static_cast<double>(luminance(in.irradiance)) * cos_theta;
        }
        sum += x;
        sum_sq += x * x;
    }
    result.lux = sum / samples;
    if (samples > 1) {
        const double var = std::max(0.0, sum_sq / samples - result.lux * result.lux);
        result.stderr_lux = std::sqrt(var / (samples - 1));
    }
    return result;
}

}  // namespace

IlluminanceProbe probe_illuminance(const SceneRuntime& scene, const Vec3& at, const Vec3& normal,
                                   bool shadows, int samples) {
    IlluminanceProbe probe;
    const std::vector<Light>& lights = scene.desc().lights;
    const OcclusionQuery* occlusion = scene.occlusion();
    for (size_t i = 0; i < lights.size(); ++i) {
        const Light& light = lights[i];
        LightIlluminance l;
        if (!shadows || occlusion == nullptr || light.shadows == ShadowMode::None) {
            l.lux = luminance(unshadowed_irradiance(light, at, normal));
        } else if (is_delta(light)) {
            l.method = IlluminanceMethod::Ray;
            l.samples = 1;
            const IncidentLight in = incident_light(light, at);
            if (visible(*occlusion, offset_ray_origin(at, normal, in.wi), in))
                l.lux = luminance(in.irradiance) * std::max(0.0f, glm::dot(normal, in.wi));
        } else {
            l = sampled(*occlusion, light, i, at, normal, samples, scene.desc().render.seed);
        }
        l.name = light.name;
        probe.lux += l.lux;
        probe.per_light.push_back(l);
    }
    return probe;
}

std::string illuminance_method_name(IlluminanceMethod method) {
    switch (method) {
        case IlluminanceMethod::Analytic:
            return "analytic";
        case IlluminanceMethod::Ray:
            return "ray";
        case IlluminanceMethod::Sampled:
            return "sampled";
    }
    return "analytic";
}

}  // namespace kasumi
