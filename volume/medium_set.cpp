#include "volume/medium_set.h"

#include "core/error.h"
#include "lights/light.h"
#include "volume/light_cache.h"

#include <algorithm>
#include <cmath>

namespace kasumi {

namespace {

const HomogeneousMedium* homogeneous(const Medium& m) {
    return std::get_if<HomogeneousMedium>(&m.model);
}

/// The part of [ray.t_min, ray.t_max] inside the medium's bounds.
std::optional<std::pair<float, float>> overlap(const HomogeneousMedium& m, const Ray& ray) {
    if (!m.bounds)
        return std::make_pair(ray.t_min, ray.t_max);
    return m.bounds->clip(ray);
}

Rgb sigma_s_of(const Medium& medium) {
    if (const HomogeneousMedium* h = homogeneous(medium))
        return h->sigma_s;
    if (const auto* f = std::get_if<HeightFogMedium>(&medium.model))
        return f->sigma_s;  // at the reference height: zero exactly when zero everywhere
    return std::get<VdbMedium>(medium.model).sigma_s_per_density;
}

const PhaseFunction& phase_of(const Medium& medium) {
    if (const HomogeneousMedium* h = homogeneous(medium))
        return h->phase;
    if (const auto* f = std::get_if<HeightFogMedium>(&medium.model))
        return f->phase;
    return std::get<VdbMedium>(medium.model).phase;
}

float grid_density(const VdbMedium& m, const Vec3& p) {
    return m.grid->density(Vec3(m.world_to_index * Vec4(p, 1.0f)));
}

/// sigma_s of medium k at p (constant for homogeneous media in the segment's mask).
Rgb sigma_s_at(const Medium& medium, const Vec3& p) {
    if (const HomogeneousMedium* h = homogeneous(medium))
        return h->sigma_s;
    if (const auto* f = std::get_if<HeightFogMedium>(&medium.model))
        return f->sigma_s * static_cast<float>(f->relative_density(p.y));
    const VdbMedium& v = std::get<VdbMedium>(medium.model);
    return v.sigma_s_per_density * grid_density(v, p);
}

/// Beyond the part of a ray where the fog's remaining optical depth is below this, its
/// majorant segments stop (the trackers' transmittance then errs by under 1e-7 relative).
constexpr double kNegligibleFogDepth = 1e-7;
/// Most majorant segments of one height fog along a ray.
constexpr int kMaxFogSegments = 256;

/// A height fog's majorant segments along the ray: the clipped span cut into pieces over which
/// the height changes by at most one scale height H (so majorant / minorant <= e), each with the
/// exact bounds, the density at its lowest and highest point (inflated by 1e-5 relative against
/// the rounding of t to float). Parts above the height where the fog's remaining depth is below
/// kNegligibleFogDepth are left out; below the density cap (HeightFogMedium::max_e_folds) one
/// constant piece covers the rest.
void height_fog_segments(const HeightFogMedium& m, uint32_t bit, const Ray& ray,
                         std::vector<MajorantSegment>& out) {
    const Rgb sigma_t = m.sigma_t();
    const double sigma_max = max_component(sigma_t);
    if (!(sigma_max > 0.0))
        return;
    double t0 = ray.t_min, t1 = ray.t_max;
    if (m.bounds) {
        const auto span = m.bounds->clip(ray);
        if (!span)
            return;
        t0 = span->first;
        t1 = span->second;
    }
    if (!(t1 > t0))
        return;
    const double H = m.scale_height_m, oy = ray.origin.y, dy = ray.direction.y;
    // Scaled height a(t) = (y(t) - h0) / H; the density is exp(min(-a, max_e_folds)).
    auto a_at = [&](double t) { return (oy + dy * t - m.reference_height_m) / H; };
    auto density = [&](double a) { return std::exp(std::min(-a, m.max_e_folds)); };
    auto push = [&](double ta, double tb, double d_max, double d_min) {
        const float fa = static_cast<float>(ta), fb = static_cast<float>(tb);
        if (!(fb > fa) || !(d_max > 0.0))
            return;
        out.push_back({fa, fb, sigma_t * static_cast<float>(d_max * (1.0 + 1e-5)),
                       sigma_t * static_cast<float>(d_min * (1.0 - 1e-5)), bit});
    };
    const double s = dy / H;  // d a / d t, per metre
    const bool endless = !(t1 < static_cast<double>(kInfinity));
    if (s == 0.0 || (!endless && std::abs(s) * (t1 - t0) <= 1.0)) {
        const double da = density(a_at(t0)), db = endless ? da : density(a_at(t1));
        push(t0, t1, std::max(da, db), std::min(da, db));
        return;
    }
    // Leave out what lies above a_top: there the depth left is at most
    // sigma_max e^{-a_top} min(L, 1/|s|) = kNegligibleFogDepth.
    const double reach = endless ? 1.0 / std::abs(s) : std::min(t1 - t0, 1.0 / std::abs(s));
    const double a_top = std::log(sigma_max * reach / kNegligibleFogDepth);
    const double a_cap = -m.max_e_folds;  // below it the density is constant
    auto t_at = [&](double a) { return (a * H + m.reference_height_m - oy) / dy; };
    // The span's pieces in ray order: [t0, t1] split where a crosses a_top and a_cap.
    double ta = t0, tb = t1;
    if (s > 0.0) {
        if (a_at(ta) >= a_top)
            return;
        tb = std::min(tb, t_at(a_top));
        if (a_at(ta) < a_cap) {
            const double t_cap = std::min(t_at(a_cap), tb);
            push(ta, t_cap, density(a_at(ta)), density(a_at(t_cap)));
            ta = t_cap;
        }
    } else {
        if (!endless && a_at(tb) >= a_top)
            return;
        ta = std::max(ta, t_at(a_top));
    }
    double t_end = tb;  // where the e-fold pieces stop (descending: at the cap)
    if (s < 0.0 && (endless || a_at(tb) < a_cap))
        t_end = std::max(ta, t_at(a_cap));
    if (t_end > ta) {
        const double folds = std::abs(a_at(t_end) - a_at(ta));
        const int n = std::clamp(static_cast<int>(std::ceil(folds)), 1, kMaxFogSegments);
        const double step = (t_end - ta) / n;
        // Above the cap the density is e^{-a} exactly, so it changes by the same factor over
        // every piece: two exps per ray instead of two per piece (the chained product drifts by
        // at most n ulps, far inside the 1e-5 inflation; the last end is evaluated exactly).
        const double ratio = std::exp(-s * step);
        double t_prev = ta, d_prev = density(a_at(ta));
        for (int i = 1; i <= n; ++i) {
            const double t_next = i == n ? t_end : ta + step * i;
            const double d_next = i == n ? density(a_at(t_end)) : d_prev * ratio;
            push(t_prev, t_next, std::max(d_prev, d_next), std::min(d_prev, d_next));
            t_prev = t_next;
            d_prev = d_next;
        }
    }
    if (t_end < tb) {  // descending below the cap: constant
        const double d = std::exp(m.max_e_folds);
        push(t_end, tb, d, d);
    }
}

/// One medium's stretches along the ray, tagged with its bit, appended to `out`.
void medium_segments(const Medium& medium, uint32_t bit, const Ray& ray,
                     std::vector<MajorantSegment>& out) {
    if (const HomogeneousMedium* h = homogeneous(medium)) {
        const Rgb sigma_t = h->sigma_t();
        const auto span = overlap(*h, ray);
        if (span && span->second > span->first && max_component(sigma_t) > 0.0f)
            out.push_back({span->first, span->second, sigma_t, sigma_t, bit});
        return;
    }
    if (const auto* f = std::get_if<HeightFogMedium>(&medium.model)) {
        height_fog_segments(*f, bit, ray, out);
        return;
    }
    const VdbMedium& v = std::get<VdbMedium>(medium.model);
    const Rgb sigma_t = v.sigma_t_per_density();
    if (v.grid->empty() || !(max_component(sigma_t) > 0.0f))
        return;
    const auto span = v.bounds_world.clip(ray);
    if (!span)
        return;
    thread_local std::vector<BrickSpan> bricks;
    bricks.clear();
    const Vec3 o_index(v.world_to_index * Vec4(ray.origin, 1.0f));
    const Vec3 d_index(v.world_to_index * Vec4(ray.direction, 0.0f));
    v.grid->bricks_along(o_index, d_index, span->first, span->second, bricks);
    for (const BrickSpan& b : bricks)
        out.push_back({b.t0, b.t1, sigma_t * b.density_max, sigma_t * b.density_min, bit});
}

}  // namespace

MediumSet::MediumSet(std::vector<Medium> media)
    : m_media(std::move(media)),
      m_light_caches(std::make_shared<std::array<LightCacheSlot, kMaxCachedLights>>()) {
    KASUMI_CHECK(m_media.size() <= kMaxMedia);
    m_all_homogeneous = std::all_of(m_media.begin(), m_media.end(),
                                    [](const Medium& m) { return homogeneous(m) != nullptr; });
    m_closed_form = std::all_of(m_media.begin(), m_media.end(), [](const Medium& m) {
        return !std::holds_alternative<VdbMedium>(m.model);
    });
    for (const Medium& m : m_media) {
        const HomogeneousMedium* h = homogeneous(m);
        const auto* fog = std::get_if<HeightFogMedium>(&m.model);
        const Rgb t = h     ? h->sigma_t()
                      : fog ? fog->sigma_t()
                            : std::get<VdbMedium>(m.model).sigma_t_per_density();
        if (!(t.r == t.g && t.g == t.b))
            m_grey_extinction = false;
        FastMedium f;
        if (h != nullptr) {
            f.sigma_t = h->sigma_t();
            f.sigma_s = h->sigma_s;
        } else if (const VdbMedium* v = std::get_if<VdbMedium>(&m.model)) {
            m_smallest_voxel_m = std::min(m_smallest_voxel_m, v->voxel_size_m);
            f.grid = v->grid.get();
            f.world_to_index = v->world_to_index;
            f.sigma_t = v->sigma_t_per_density();
            f.sigma_s = v->sigma_s_per_density;
            f.bounds_world = v->bounds_world;
            if (v->temperature && max_component(v->sigma_a_per_density) > 0.0f)
                m_emits = true;
        } else {
            f.other = true;
        }
        m_fast.push_back(f);
    }
}

MediumSet::LightCacheSlot::~LightCacheSlot() = default;

const LightTransmittanceCache* MediumSet::light_cache(size_t light_index,
                                                      const Light& light) const {
    const auto* directional = std::get_if<DirectionalLight>(&light.emitter);
    if (directional == nullptr || light_index >= kMaxCachedLights || m_media.size() != 1)
        return nullptr;
    const VdbMedium* grid = std::get_if<VdbMedium>(&m_media[0].model);
    if (grid == nullptr || !m_light_caches)
        return nullptr;
    LightCacheSlot& slot = (*m_light_caches)[light_index];
    std::call_once(slot.once, [&] {
        slot.cache = std::make_unique<LightTransmittanceCache>(
            *grid, -glm::normalize(directional->direction));
    });
    return slot.cache.get();
}

bool MediumSet::scatters() const {
    return std::any_of(m_media.begin(), m_media.end(),
                       [](const Medium& m) { return max_component(sigma_s_of(m)) > 0.0f; });
}

Rgb MediumSet::optical_depth(const Ray& ray) const {
    Rgb tau(0.0f);
    for (const Medium& medium : m_media) {
        if (const auto* fog = std::get_if<HeightFogMedium>(&medium.model)) {
            tau += height_fog_optical_depth(*fog, ray);  // closed form (volume/height_fog.h)
            continue;
        }
        const HomogeneousMedium* m = homogeneous(medium);
        if (m == nullptr)
            continue;
        const auto span = overlap(*m, ray);
        if (!span)
            continue;
        const float length = span->second - span->first;
        // An unbounded medium along an infinite ray has infinite depth; exp(-inf) = 0 is right,
        // but 0 * inf would be NaN for a clear channel.
        const Rgb sigma_t = m->sigma_t();
        for (int c = 0; c < 3; ++c) {
            if (sigma_t[c] > 0.0f)
                tau[c] += sigma_t[c] * length;
        }
    }
    return tau;
}

void MediumSet::intervals(const Ray& ray, std::vector<MediumInterval>& out) const {
    out.clear();
    // Boundaries of all media overlaps, sorted; between consecutive ones coefficients are constant.
    float cuts[2 * kMaxMedia];
    size_t n_cuts = 0;
    for (const Medium& medium : m_media) {
        const HomogeneousMedium* m = homogeneous(medium);
        if (m == nullptr)
            continue;
        const auto span = overlap(*m, ray);
        if (!span)
            continue;
        cuts[n_cuts++] = span->first;
        cuts[n_cuts++] = span->second;
    }
    std::sort(cuts, cuts + n_cuts);
    for (size_t i = 0; i + 1 < n_cuts; ++i) {
        const float t0 = cuts[i], t1 = cuts[i + 1];
        if (!(t1 > t0))
            continue;
        const Vec3 mid = ray.at(0.5f * (t0 + t1));
        MediumInterval interval;
        interval.t0 = t0;
        interval.t1 = t1;
        bool inside_any = false;
        for (uint32_t k = 0; k < m_media.size(); ++k) {
            const HomogeneousMedium* m = homogeneous(m_media[k]);
            if (m == nullptr || (m->bounds && !m->bounds->contains(mid)))
                continue;
            inside_any = true;
            interval.sigma_t += m->sigma_t();
            interval.sigma_s += m->sigma_s;
            if (max_component(m->sigma_s) > 0.0f)
                interval.scattering_mask |= 1u << k;
        }
        if (inside_any)
            out.push_back(interval);
    }
}

Rgb MediumSet::scattering(const MediumInterval& interval, float mu) const {
    Rgb result(0.0f);
    for (uint32_t mask = interval.scattering_mask; mask != 0; mask &= mask - 1) {
        const Medium& m = m_media[__builtin_ctz(mask)];
        result += sigma_s_of(m) * eval(phase_of(m), mu);
    }
    return result;
}

void MediumSet::majorants(const Ray& ray, std::vector<MajorantSegment>& out) const {
    out.clear();
    if (m_media.size() == 1) {
        medium_segments(m_media[0], 1u, ray, out);
        return;
    }
    thread_local std::vector<MajorantSegment> all;
    all.clear();
    for (uint32_t k = 0; k < m_media.size(); ++k)
        medium_segments(m_media[k], 1u << k, ray, all);
    if (all.empty())
        return;
    // Sweep the segment ends in order; each medium's own segments are disjoint, so at most one
    // per medium is active and the sums are recomputed per elementary stretch (no drift).
    struct Event {
        float t;
        int32_t segment;  ///< ~index for an end, index for a start
    };
    thread_local std::vector<Event> events;
    events.clear();
    for (int32_t i = 0; i < static_cast<int32_t>(all.size()); ++i) {
        events.push_back({all[i].t0, i});
        events.push_back({all[i].t1, ~i});
    }
    std::sort(events.begin(), events.end(), [](const Event& a, const Event& b) {
        return a.t < b.t || (a.t == b.t && a.segment < b.segment);  // ends first
    });
    int32_t active[kMaxMedia];
    std::fill(active, active + kMaxMedia, -1);
    uint32_t mask = 0;
    for (size_t e = 0; e < events.size(); ++e) {
        const Event& ev = events[e];
        const int32_t i = ev.segment >= 0 ? ev.segment : ~ev.segment;
        const int k = __builtin_ctz(all[i].media_mask);
        if (ev.segment >= 0) {
            active[k] = i;
            mask |= 1u << k;
        } else {
            active[k] = -1;
            mask &= ~(1u << k);
        }
        if (mask == 0 || e + 1 == events.size() || !(events[e + 1].t > ev.t))
            continue;
        MajorantSegment s{ev.t, events[e + 1].t, Rgb(0.0f), Rgb(0.0f), mask};
        for (uint32_t m = mask; m != 0; m &= m - 1) {
            const MajorantSegment& a = all[active[__builtin_ctz(m)]];
            s.sigma_max += a.sigma_max;
            s.sigma_min += a.sigma_min;
        }
        out.push_back(s);
    }
}

PointCoefficients MediumSet::coefficients(const Vec3& p, uint32_t mask) const {
    PointCoefficients c;
    for (; mask != 0; mask &= mask - 1) {
        const Medium& medium = m_media[__builtin_ctz(mask)];
        if (const HomogeneousMedium* h = homogeneous(medium)) {
            c.sigma_t += h->sigma_t();
            c.sigma_s += h->sigma_s;
        } else if (const auto* f = std::get_if<HeightFogMedium>(&medium.model)) {
            const float rho = static_cast<float>(f->relative_density(p.y));
            c.sigma_t += f->sigma_t() * rho;
            c.sigma_s += f->sigma_s * rho;
        } else {
            const VdbMedium& v = std::get<VdbMedium>(medium.model);
            const float d = grid_density(v, p);
            c.sigma_t += v.sigma_t_per_density() * d;
            c.sigma_s += v.sigma_s_per_density * d;
        }
    }
    return c;
}

Rgb MediumSet::emission(const Vec3& p, uint32_t mask) const {
    Rgb result(0.0f);
    for (; mask != 0; mask &= mask - 1) {
        const VdbMedium* v = std::get_if<VdbMedium>(&m_media[__builtin_ctz(mask)].model);
        if (v == nullptr || !v->temperature)
            continue;
        const float d = grid_density(*v, p);
        if (d > 0.0f)
            result += v->sigma_a_per_density * d * v->temperature->radiance(p);
    }
    return result;
}

Rgb MediumSet::scattering(const Vec3& p, uint32_t mask, float mu) const {
    Rgb result(0.0f);
    for (; mask != 0; mask &= mask - 1) {
        const Medium& m = m_media[__builtin_ctz(mask)];
        const Rgb s = sigma_s_at(m, p);
        if (!is_black(s))
            result += s * eval(phase_of(m), mu);
    }
    return result;
}

float MediumSet::phase_value(uint32_t k, float mu) const {
    return eval(phase_of(m_media[k]), mu);
}

MixtureSample MediumSet::sample_scattering(const Vec3& p, uint32_t mask, const Vec3& wo,
                                           float u_pick, Vec2 u,
                                           const PointCoefficients* known) const {
    MixtureSample out;
    const bool one = mask != 0 && (mask & (mask - 1)) == 0;
    if (one && known != nullptr) {
        // The general path below for one medium with known coefficients, without its tables
        // (the pick always takes that medium; u_pick goes unused there too).
        if (!(std::max(luminance(known->sigma_s), 0.0f) > 0.0f))
            return out;
        const PhaseSample ps = sample(phase_of(m_media[__builtin_ctz(mask)]), wo, u);
        if (!(ps.pdf > 0.0f))
            return out;
        out.wi = ps.wi;
        out.scattering = known->sigma_s * ps.value;
        out.pdf = ps.pdf;
        return out;
    }
    Rgb sigma_s[kMaxMedia];
    float weight[kMaxMedia];
    float total = 0.0f;
    for (uint32_t m = mask; m != 0; m &= m - 1) {
        const int k = __builtin_ctz(m);
        sigma_s[k] = one && known != nullptr ? known->sigma_s : sigma_s_at(m_media[k], p);
        weight[k] = std::max(luminance(sigma_s[k]), 0.0f);
        total += weight[k];
    }
    if (!(total > 0.0f))
        return out;
    float target = u_pick * total;
    int chosen = -1;
    for (uint32_t m = mask; m != 0; m &= m - 1) {
        const int k = __builtin_ctz(m);
        if (weight[k] == 0.0f)
            continue;
        chosen = k;
        if (target < weight[k])
            break;
        target -= weight[k];
    }
    const PhaseSample ps = sample(phase_of(m_media[chosen]), wo, u);
    if (!(ps.pdf > 0.0f))
        return out;
    out.wi = ps.wi;
    if ((mask & (mask - 1)) == 0) {
        out.scattering = sigma_s[chosen] * ps.value;
        out.pdf = ps.pdf;
        return out;
    }
    // Several media: the direction's density is the pick-weighted mixture of their pdfs.
    const float mu = scattering_cosine(wo, ps.wi);
    for (uint32_t m = mask; m != 0; m &= m - 1) {
        const int k = __builtin_ctz(m);
        if (weight[k] == 0.0f)
            continue;
        const PhaseFunction& phase = phase_of(m_media[k]);
        out.scattering += sigma_s[k] * eval(phase, mu);
        out.pdf += weight[k] / total * pdf(phase, mu);
    }
    return out;
}

}  // namespace kasumi
