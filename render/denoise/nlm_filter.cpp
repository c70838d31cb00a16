#include "render/denoise/nlm_filter.h"

#include "render/denoise/sure_selection.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace kasumi {

namespace {

/// Keeps the colour distance finite where both variances are 0 (pixels without noise, e.g. the
/// sky): any difference there gives weight ~0 (RKZ 2012 eq. 6's epsilon), (cd/m²)².
constexpr float kEpsilon = 1e-10f;
/// Floor of the feature's variance (T is in [0, 1]): differences of T below ~k_f * 0.01 are
/// ignored even where T is exact (RMZ 2013's tau, here in units of T²).
constexpr float kFeatureTau = 1e-4f;
/// Distances beyond which a weight exp(-d²) < 1e-9 is dropped (not a bias worth a multiply).
constexpr float kNegligible = 20.7f;
/// Rows filtered together: the unit of parallel work (fixed, so the work split never changes
/// a result, and each band recomputes only 2 * patch rows of distances).
constexpr int kBandRows = 16;

/// The colour distance D(p, q) of the header for the pixels p = prow + x, q = qrow + x,
/// x in [xs, xe), into dist[x] (0 where the pair is not valid) and cnt[x] (1 valid, 0 not).
/// Restricted pointers, so the loop vectorises.
void colour_distances(const HalfImage& guide, const float* __restrict valid, size_t prow,
                      size_t qrow, int xs, int xe, float k2, float* __restrict dist,
                      float* __restrict cnt) {
    const float* __restrict u0 = guide.radiance[0].data();
    const float* __restrict u1 = guide.radiance[1].data();
    const float* __restrict u2 = guide.radiance[2].data();
    const float* __restrict v0 = guide.radiance_var[0].data();
    const float* __restrict v1 = guide.radiance_var[1].data();
    const float* __restrict v2 = guide.radiance_var[2].data();
    const auto term = [k2](float up, float uq, float vp, float vq) {
        // RKZ 2012 eq. 6 for one channel.
        const float diff = up - uq;
        return (diff * diff - (vp + std::min(vp, vq))) / (kEpsilon + k2 * (vp + vq));
    };
    for (int x = xs; x < xe; ++x) {
        const size_t p = prow + x, q = qrow + x;
        // A pair with an invalid pixel counts 0 (its variances may be infinite: masked).
        const float m = valid[p] * valid[q];
        const float d = term(u0[p], u0[q], v0[p], v0[q]) + term(u1[p], u1[q], v1[p], v1[q]) +
                        term(u2[p], u2[q], v2[p], v2[q]);
        dist[x] = m > 0.0f ? d * (1.0f / 3.0f) : 0.0f;
        cnt[x] = m;
    }
}

}  // namespace

void cross_filter_strengths(const HalfImage& guide, const HalfImage& filtered,
                            const std::vector<unsigned char>& valid, int width, int height,
                            const DenoiseSettings& settings,
                            const std::vector<StrengthScale>& scales,
                            std::vector<CrossFiltered>& out) {
    const size_t pixels = static_cast<size_t>(width) * static_cast<size_t>(height);
    const size_t strengths = scales.size();
    out.assign(strengths, CrossFiltered{});
    // The patch distance at strength k s is the one at k times 1 / s² (kEpsilon aside), and the
    // same for the feature: one distance pass serves every strength; s = 1 multiplies by
    // exactly 1 (the plain filter, bit for bit).
    std::vector<float> inv_scale2(strengths), inv_feature_scale2(strengths);
    for (size_t s = 0; s < strengths; ++s) {
        inv_scale2[s] = 1.0f / (scales[s].k * scales[s].k);
        inv_feature_scale2[s] = 1.0f / (scales[s].k_feature * scales[s].k_feature);
        for (int c = 0; c < 3; ++c)
            out[s].rgb[c].assign(pixels, 0.0f);
        out[s].weight_sum.assign(pixels, 1.0f);
    }
    const int r = settings.radius, f = settings.patch;
    const float k2 = settings.k * settings.k;
    const float kf2 = settings.k_feature * settings.k_feature;
    const int bands = (height + kBandRows - 1) / kBandRows;
    std::vector<float> valid_f(valid.begin(), valid.end());
    tbb::parallel_for(tbb::blocked_range<int>(0, bands, 1), [&](const tbb::blocked_range<int>& b) {
        // Rows of distances are padded by `f` zeros on each side, so the patch sums along a
        // row need no bounds checks (and vectorise).
        const size_t stride = static_cast<size_t>(width + 2 * f);
        const int halo_rows = kBandRows + 2 * f;
        std::vector<float> distance(halo_rows * stride), count(halo_rows * stride);
        std::vector<float> row_d(halo_rows * static_cast<size_t>(width)),
            row_n(halo_rows * static_cast<size_t>(width));
        std::vector<float> patch_d(width), patch_n(width);
        const size_t band_pixels = static_cast<size_t>(kBandRows) * width;
        std::vector<float> weight_sum(strengths * band_pixels);
        std::vector<float> value_sum[3];
        for (int band = b.begin(); band < b.end(); ++band) {
            const int y0 = band * kBandRows, y1 = std::min(height, y0 + kBandRows);
            // Distances are needed on the band's rows and `f` rows around (the patches).
            const int d0 = std::max(0, y0 - f), d1 = std::min(height, y1 + f);
            std::fill(weight_sum.begin(), weight_sum.end(), 0.0f);
            for (auto& v : value_sum)
                v.assign(strengths * band_pixels, 0.0f);
            for (int dy = -r; dy <= r; ++dy) {
                for (int dx = -r; dx <= r; ++dx) {
                    const int xs = std::max(0, -dx), xe = std::min(width, width - dx);
                    std::fill(distance.begin(), distance.end(), 0.0f);
                    std::fill(count.begin(), count.end(), 0.0f);
                    for (int y = d0; y < d1; ++y) {
                        const int qy = y + dy;
                        if (qy < 0 || qy >= height)
                            continue;
                        const size_t prow = static_cast<size_t>(y) * width;
                        const size_t qrow = static_cast<size_t>(qy) * width + dx;
                        colour_distances(guide, valid_f.data(), prow, qrow, xs, xe, k2,
                                         distance.data() + (y - d0) * stride + f,
                                         count.data() + (y - d0) * stride + f);
                    }
                    for (int y = d0; y < d1; ++y) {
                        const float* dist = distance.data() + (y - d0) * stride;
                        const float* cnt = count.data() + (y - d0) * stride;
                        float* sd = row_d.data() + static_cast<size_t>(y - d0) * width;
                        float* sn = row_n.data() + static_cast<size_t>(y - d0) * width;
                        std::fill(sd, sd + width, 0.0f);
                        std::fill(sn, sn + width, 0.0f);
                        for (int j = 0; j <= 2 * f; ++j) {
                            for (int x = 0; x < width; ++x) {
                                sd[x] += dist[x + j];
                                sn[x] += cnt[x + j];
                            }
                        }
                    }
                    for (int y = y0; y < y1; ++y) {
                        const int qy = y + dy;
                        if (qy < 0 || qy >= height)
                            continue;
                        std::fill(patch_d.begin(), patch_d.end(), 0.0f);
                        std::fill(patch_n.begin(), patch_n.end(), 0.0f);
                        for (int py = std::max(d0, y - f); py <= std::min(d1 - 1, y + f); ++py) {
                            const float* sd = row_d.data() + static_cast<size_t>(py - d0) * width;
                            const float* sn = row_n.data() + static_cast<size_t>(py - d0) * width;
                            for (int x = 0; x < width; ++x) {
                                patch_d[x] += sd[x];
                                patch_n[x] += sn[x];
                            }
                        }
                        const size_t prow = static_cast<size_t>(y) * width;
                        const size_t qrow = static_cast<size_t>(qy) * width + dx;
                        const size_t out_row = static_cast<size_t>(y - y0) * width;
                        for (int x = xs; x < xe; ++x) {
                            if (valid_f[prow + x] * valid_f[qrow + x] == 0.0f)
                                continue;  // patch_n >= 1 below: the pair itself is valid
                            const float wp = guide.feature_var[prow + x];
                            const float wq = guide.feature_var[qrow + x];
                            const float fd = guide.feature[prow + x] - guide.feature[qrow + x];
                            const float df2 = (fd * fd - (wp + std::min(wp, wq))) /
                                              (kf2 * std::max(kFeatureTau, wp + wq));
                            const float d2 = patch_d[x] / patch_n[x];
                            for (size_t s = 0; s < strengths; ++s) {
                                // min(exp(-a), exp(-b)) = exp(-max(a, b)): one exponential.
                                const float a =
                                    std::max(d2 * inv_scale2[s], df2 * inv_feature_scale2[s]);
                                if (!(a < kNegligible))
                                    continue;  // weight < 1e-9 (and no slow underflowing exp)
                                const float w = std::exp(-std::max(0.0f, a));
                                const size_t o = s * band_pixels + out_row + x;
                                weight_sum[o] += w;
                                for (int c = 0; c < 3; ++c)
                                    value_sum[c][o] += w * filtered.radiance[c][qrow + x];
                            }
                        }
                    }
                }
            }
            for (size_t s = 0; s < strengths; ++s) {
                for (int y = y0; y < y1; ++y) {
                    for (int x = 0; x < width; ++x) {
                        const size_t p = static_cast<size_t>(y) * width + x;
                        const size_t i = s * band_pixels + static_cast<size_t>(y - y0) * width + x;
                        // weight_sum >= 1 for a valid pixel (its own weight is exp(0) = 1).
                        for (int c = 0; c < 3; ++c) {
                            out[s].rgb[c][p] = valid[p] != 0 ? value_sum[c][i] / weight_sum[i]
                                                             : filtered.radiance[c][p];
                        }
                        out[s].weight_sum[p] = valid[p] != 0 ? weight_sum[i] : 1.0f;
                    }
                }
            }
        }
    });
}

std::vector<unsigned char> valid_pixels(const HalfBuffers& halves) {
    const size_t pixels =
        static_cast<size_t>(halves.width()) * static_cast<size_t>(halves.height());
    const HalfImage& a = halves.half(0);
    const HalfImage& b = halves.half(1);
    std::vector<unsigned char> valid(pixels, 0);
    for (size_t i = 0; i < pixels; ++i) {
        bool ok = a.samples[i] >= 2.0f && b.samples[i] >= 2.0f;
        for (const HalfImage* h : {&a, &b}) {
            ok = ok && std::isfinite(h->feature[i]) && std::isfinite(h->feature_var[i]);
            for (int c = 0; c < 3 && ok; ++c)
                ok = std::isfinite(h->radiance[c][i]) && std::isfinite(h->radiance_var[c][i]);
        }
        valid[i] = ok ? 1 : 0;
    }
    return valid;
}

void cross_filter(const HalfImage& guide, const HalfImage& filtered,
                  const std::vector<unsigned char>& valid, int width, int height,
                  const DenoiseSettings& settings, std::vector<float> out[3]) {
    std::vector<CrossFiltered> one;
    cross_filter_strengths(guide, filtered, valid, width, height, settings, {StrengthScale{}}, one);
    for (int c = 0; c < 3; ++c)
        out[c] = std::move(one[0].rgb[c]);
}

DenoisedBeauty denoise_beauty(const HalfBuffers& halves, const DenoiseSettings& settings) {
    const int width = halves.width(), height = halves.height();
    const size_t pixels = static_cast<size_t>(width) * static_cast<size_t>(height);
    const HalfImage& a = halves.half(0);
    const HalfImage& b = halves.half(1);
    const std::vector<unsigned char> valid = valid_pixels(halves);
    if (settings.select)
        return select_strength(halves, valid, settings);
    std::vector<float> filtered_a[3], filtered_b[3];
    cross_filter(b, a, valid, width, height, settings, filtered_a);
    cross_filter(a, b, valid, width, height, settings, filtered_b);
    DenoisedBeauty beauty;
    for (int c = 0; c < 3; ++c) {
        beauty.rgb[c].resize(pixels);
        for (size_t i = 0; i < pixels; ++i) {
            const float na = a.samples[i], nb = b.samples[i];
            beauty.rgb[c][i] =
                na + nb > 0.0f ? (na * filtered_a[c][i] + nb * filtered_b[c][i]) / (na + nb) : 0.0f;
        }
    }
    return beauty;
}

}  // namespace kasumi
