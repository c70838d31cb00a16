#include "render/probe.h"

#include "render/integrator.h"
#include "volume/transmittance.h"

namespace kasumi {

namespace {

/// Running mean and standard error of RGB samples, accumulated in double.
class MeanAccumulator {
  public:
    void add(const Rgb& x) {
        m_sum += glm::dvec3(x);
        m_sum_sq += glm::dvec3(x) * glm::dvec3(x);
        ++m_n;
    }
    Rgb mean() const { return m_n > 0 ? Rgb(m_sum / static_cast<double>(m_n)) : Rgb(0.0f); }
    Rgb standard_error() const {
        if (m_n < 2)
            return Rgb(0.0f);
        const double n = static_cast<double>(m_n);
        const glm::dvec3 mu = m_sum / n;
        const glm::dvec3 var = glm::max(m_sum_sq / n - mu * mu, glm::dvec3(0.0)) * (n / (n - 1));
        return Rgb(glm::sqrt(var / n));
    }

  private:
    glm::dvec3 m_sum{0.0}, m_sum_sq{0.0};
    int64_t m_n = 0;
};

}  // namespace

RadianceProbe probe_radiance(const SceneRuntime& scene, const Vec3& origin, const Vec3& direction,
                             int spp) {
    RenderCounters counters;
    MeanAccumulator mean;
    const Ray ray{origin, glm::normalize(direction), 0.0f, kInfinity};
    for (int s = 0; s < spp; ++s) {
        Pcg32 rng = pixel_rng(0xffffffffu, 0xffffffffu, static_cast<uint32_t>(s), 0u,
                              scene.desc().render.seed);
        mean.add(trace_camera_ray(scene, ray, rng, counters).radiance);
    }
    RadianceProbe probe;
    probe.samples = spp;
    probe.radiance = mean.mean();
    probe.stderr_ = mean.standard_error();
    probe.luminance_cd_m2 = luminance(probe.radiance);
    return probe;
}

TransmittanceProbe probe_transmittance(const SceneRuntime& scene, const Vec3& from, const Vec3& to,
                                       Estimator estimator, int samples) {
    TransmittanceProbe probe;
    probe.samples = samples;
    // The atmosphere: deterministic quadrature in double precision (no estimator noise).
    const Rgb t_sky = scene.sky() != nullptr ? scene.sky()->transmittance(from, to) : Rgb(1.0f);
    probe.transmittance = t_sky;
    const float distance = glm::length(to - from);
    if (scene.media().empty() || !(distance > 0.0f))
        return probe;
    const Ray ray{from, (to - from) / distance, 0.0f, distance};
    const float step = march_step_m(scene.media(), scene.desc().render.volume);
    MeanAccumulator mean;
    VolumeCounters counters;
    for (int s = 0; s < samples; ++s) {
        Pcg32 rng = pixel_rng(0xfffffffeu, 0xfffffffeu, static_cast<uint32_t>(s), 0u,
                              scene.desc().render.seed);
        mean.add(estimate_transmittance(scene.media(), ray, estimator, step, rng, counters));
    }
    probe.transmittance = mean.mean() * t_sky;
    probe.stderr_ = mean.standard_error() * t_sky;
    return probe;
}

}  // namespace kasumi
