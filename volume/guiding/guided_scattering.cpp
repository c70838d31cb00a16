#include "volume/guiding/guided_scattering.h"

#include "phase/phase_sample.h"

#include <variant>

namespace kasumi {

namespace {

const PhaseFunction& phase_of(const MediumSet& media, uint32_t medium) {
    return std::visit([](const auto& m) -> const PhaseFunction& { return m.phase; },
                      media.media()[medium].model);
}

}  // namespace

float guided_pdf(const MediumSet& media, uint32_t medium, const DirectionalHistogram& guide,
                 float mix, const Vec3& wo, const Vec3& wi) {
    return mix * guide.pdf(wi) +
           (1.0f - mix) * pdf(phase_of(media, medium), scattering_cosine(wo, wi));
}

MixtureSample sample_guided_scattering(const MediumSet& media, uint32_t medium,
                                       const DirectionalHistogram& guide, float mix,
                                       const PointCoefficients& k, const Vec3& wo, float u_choose,
                                       Vec2 u) {
    MixtureSample out;
    if (is_black(k.sigma_s))
        return out;
    const PhaseFunction& phase = phase_of(media, medium);
    float guide_pdf = 0.0f, phase_pdf = 0.0f;
    if (u_choose < mix) {
        out.wi = guide.sample(u, guide_pdf);
        phase_pdf = pdf(phase, scattering_cosine(wo, out.wi));
    } else {
        const PhaseSample ps = sample(phase, wo, u);
        if (!(ps.pdf > 0.0f))
            return out;
        out.wi = ps.wi;
        phase_pdf = ps.pdf;
        guide_pdf = guide.pdf(out.wi);
    }
    out.pdf = mix * guide_pdf + (1.0f - mix) * phase_pdf;
    out.scattering = k.sigma_s * eval(phase, scattering_cosine(wo, out.wi));
    return out;
}

}  // namespace kasumi
