#include "volume/guiding/guided_scattering.h"

#include "phase/phase_sample.h"

#include <algorithm>
#include <array>
#include <variant>

namespace kasumi {

namespace {

const PhaseFunction& phase_of(const MediumSet& media, uint32_t medium) {
    return std::visit([](const auto& m) -> const PhaseFunction& { return m.phase; },
                      media.media()[medium].model);
}

/// The bin centres of DirectionalHistogram, computed once.
const std::array<Vec3, DirectionalHistogram::kBins>& bin_centres() {
    static const auto centres = [] {
        std::array<Vec3, DirectionalHistogram::kBins> c{};
        for (int i = 0; i < DirectionalHistogram::kBins; ++i)
            c[static_cast<size_t>(i)] = DirectionalHistogram::in_bin(i, Vec2(0.5f));
        return c;
    }();
    return centres;
}

/// The guide times the phase function at each bin's centre, as a running sum: the
/// piecewise-constant product distribution of the learnt incident radiance and the phase
/// function for this wo (Herholz et al. 2019 sample the product of guide and phase; here it is
/// exact to sample and evaluate because it is constant per bin).
struct ProductBins {
    std::array<float, DirectionalHistogram::kBins> cdf{};
    float total = 0.0f;
};

ProductBins product_bins(const PhaseFunction& phase, const DirectionalHistogram& guide,
                         const Vec3& wo) {
    ProductBins p;
    const auto& centres = bin_centres();
    float running = 0.0f;
    for (int i = 0; i < DirectionalHistogram::kBins; ++i) {
        running +=
            guide.mass(i) * eval(phase, scattering_cosine(wo, centres[static_cast<size_t>(i)]));
        p.cdf[static_cast<size_t>(i)] = running;
    }
    p.total = running;
    return p;
}

/// Density of `wi` under the product distribution, per steradian.
float product_pdf(const ProductBins& p, const PhaseFunction& phase,
                  const DirectionalHistogram& guide, const Vec3& wo, const Vec3& wi) {
    if (!(p.total > 0.0f))
        return 0.0f;
    const int bin = DirectionalHistogram::bin_of(wi);
    const float value = guide.mass(bin) *
                        eval(phase, scattering_cosine(wo, bin_centres()[static_cast<size_t>(bin)]));
    return value / (p.total * DirectionalHistogram::kBinSolidAngle);
}

}  // namespace

float guided_pdf(const MediumSet& media, uint32_t medium, const DirectionalHistogram& guide,
                 float mix, const Vec3& wo, const Vec3& wi) {
    const PhaseFunction& phase = phase_of(media, medium);
    const ProductBins bins = product_bins(phase, guide, wo);
    return mix * product_pdf(bins, phase, guide, wo, wi) +
           (1.0f - mix) * pdf(phase, scattering_cosine(wo, wi));
}

MixtureSample sample_guided_scattering(const MediumSet& media, uint32_t medium,
                                       const DirectionalHistogram& guide, float mix,
                                       const PointCoefficients& k, const Vec3& wo, float u_choose,
                                       Vec2 u) {
    MixtureSample out;
    if (is_black(k.sigma_s))
        return out;
    const PhaseFunction& phase = phase_of(media, medium);
    const ProductBins bins = product_bins(phase, guide, wo);
    if (u_choose < mix && bins.total > 0.0f) {
        const float target = u.x * bins.total;
        const int i =
            std::min(static_cast<int>(std::upper_bound(bins.cdf.begin(), bins.cdf.end(), target) -
                                      bins.cdf.begin()),
                     DirectionalHistogram::kBins - 1);
        const float below = i > 0 ? bins.cdf[static_cast<size_t>(i - 1)] : 0.0f;
        const float share = bins.cdf[static_cast<size_t>(i)] - below;
        // The offset of the target inside the bin's share is uniform: it places z in the band.
        const float t = share > 0.0f ? std::clamp((target - below) / share, 0.0f, 1.0f) : 0.5f;
        out.wi = DirectionalHistogram::in_bin(i, Vec2(t, u.y));
    } else {
        const PhaseSample ps = sample(phase, wo, u);
        if (!(ps.pdf > 0.0f))
            return out;
        out.wi = ps.wi;
    }
    const float mu = scattering_cosine(wo, out.wi);
    out.pdf = mix * product_pdf(bins, phase, guide, wo, out.wi) + (1.0f - mix) * pdf(phase, mu);
    out.scattering = k.sigma_s * eval(phase, mu);
    return out;
}

}  // namespace kasumi
