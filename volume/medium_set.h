#pragma once
/// All media of a scene, queried together: overlapping media add their coefficients and mix
/// their phase functions in proportion to their scattering coefficients.
#include "core/color.h"
#include "core/rng.h"
#include "phase/phase_sample.h"
#include "volume/medium.h"

#include <array>
#include <cstring>
#include <memory>
#include <mutex>
#include <vector>

namespace kasumi {

class LightTransmittanceCache;
struct Light;

/// A stretch [t0, t1] of a ray over which every coefficient is constant (homogeneous media).
struct MediumInterval {
    float t0 = 0.0f;
    float t1 = 0.0f;
    Rgb sigma_t{0.0f};
    Rgb sigma_s{0.0f};
    uint32_t scattering_mask = 0;  ///< bit k set: medium k scatters here
};

/// A stretch [t0, t1] of a ray with bounds on the extinction of all media over it (1/m):
/// sigma_min <= sigma_t(x) <= sigma_max per channel. Stretches not listed hold no medium.
struct MajorantSegment {
    float t0 = 0.0f;
    float t1 = 0.0f;
    Rgb sigma_max{0.0f};
    Rgb sigma_min{0.0f};
    uint32_t media_mask = 0;  ///< bit k set: medium k may be non-zero here
};

/// Coefficients of all media at one point, 1/m.
struct PointCoefficients {
    Rgb sigma_t{0.0f};
    Rgb sigma_s{0.0f};
};

/// A direction drawn from the scattering-weighted mixture of phase functions at a point.
struct MixtureSample {
    Vec3 wi{0.0f};
    Rgb scattering{0.0f};  ///< sum_m sigma_s,m p_m(mu) at wi, 1/(m sr)
    float pdf = 0.0f;      ///< per steradian; 0 when nothing scatters
};

/// Media beyond this count are rejected at load time (interval bookkeeping uses a 32-bit mask).
inline constexpr size_t kMaxMedia = 32;

class MediumSet {
  public:
    MediumSet() = default;
    explicit MediumSet(std::vector<Medium> media);

    bool empty() const { return m_media.empty(); }
    const std::vector<Medium>& media() const { return m_media; }
    /// True if any medium scatters light (sigma_s > 0 in some channel).
    bool scatters() const;
    /// True if every medium is homogeneous (then `intervals` and `optical_depth` are exact).
    bool all_homogeneous() const { return m_all_homogeneous; }
    /// True if every medium is homogeneous or height fog: `optical_depth` and `transmittance`
    /// are then exact for the whole set (closed forms).
    bool closed_form() const { return m_closed_form; }
    /// True if some medium emits light (a grid with a temperature).
    bool emits() const { return m_emits; }
    /// Emitted radiance per metre at p, sum over the media in `mask` of sigma_a,m(p) L_e,m(p),
    /// cd/m² per metre.
    Rgb emission(const Vec3& p, uint32_t mask) const;
    /// True if every medium's extinction is the same in all channels (trackers run once).
    bool grey_extinction() const { return m_grey_extinction; }
    /// Shortest voxel edge of the grid media, metres (kInfinity without grids).
    float smallest_voxel_m() const { return m_smallest_voxel_m; }

    /// Optical depth tau along the ray over [t_min, t_max], exact; homogeneous media and height
    /// fog only (grids are left out: use the transmittance estimators for them).
    Rgb optical_depth(const Ray& ray) const;
    /// Beer-Lambert transmittance exp(-tau) over [t_min, t_max]; homogeneous media and height
    /// fog only.
    Rgb transmittance(const Ray& ray) const { return exp_neg(optical_depth(ray)); }

    /// Splits [t_min, t_max] at every homogeneous medium's boundary and returns the stretches
    /// inside at least one, in order. `out` is reused to avoid allocation in the hot loop.
    void intervals(const Ray& ray, std::vector<MediumInterval>& out) const;

    /// Phase-weighted scattering sum_m sigma_s,m p_m(mu) at a point of `interval`, in 1/(m sr).
    Rgb scattering(const MediumInterval& interval, float mu) const;

    /// Majorant/minorant stretches of [t_min, t_max] in order, skipping empty space: one per
    /// homogeneous box and one per non-empty grid brick (bricks found by a DDA), overlapping
    /// media summed. `out` is reused.
    void majorants(const Ray& ray, std::vector<MajorantSegment>& out) const;

    /// Coefficients at world point p, summing the media in `mask` (a segment's media_mask).
    /// Homogeneous media in the mask count without a bounds test (the segment is inside them).
    PointCoefficients coefficients(const Vec3& p, uint32_t mask) const;
    /// sum_m sigma_s,m(p) p_m(mu) over the media in `mask`, in 1/(m sr).
    Rgb scattering(const Vec3& p, uint32_t mask, float mu) const;
    /// The same with the coefficients `k` already looked up at p (k = coefficients(p, mask)):
    /// no second lookup when `mask` holds one medium (its sigma_s is k.sigma_s).
    Rgb scattering(const PointCoefficients& k, const Vec3& p, uint32_t mask, float mu) const {
        if (mask != 0 && (mask & (mask - 1)) == 0)
            return is_black(k.sigma_s) ? Rgb(0.0f)
                                       : k.sigma_s * phase_value(__builtin_ctz(mask), mu);
        return scattering(p, mask, mu);
    }
    /// Phase function of medium k at cosine mu, 1/sr.
    float phase_value(uint32_t k, float mu) const;
    /// Picks a medium in proportion to the luminance of its sigma_s at p (with `u_pick`), samples
    /// its phase function with `u`, and returns the mixture's value and pdf for that direction.
    /// `known`: the coefficients already looked up at p (coefficients(p, mask)); when `mask`
    /// holds one medium its sigma_s is known->sigma_s (no second lookup).
    MixtureSample sample_scattering(const Vec3& p, uint32_t mask, const Vec3& wo, float u_pick,
                                    Vec2 u, const PointCoefficients* known = nullptr) const;

    /// The hot-loop view of medium k: a grid (null for a homogeneous medium), its world-to-index
    /// transform and the coefficients per unit density (or the constant ones).
    struct FastMedium {
        const DensityGrid* grid = nullptr;
        Mat4 world_to_index{1.0f};
        Rgb sigma_t{0.0f};     ///< 1/m (per unit density for a grid)
        Rgb sigma_s{0.0f};     ///< 1/m (per unit density for a grid)
        bool other = false;    ///< another kind of medium: queried through coefficients()
        Bounds3 bounds_world;  ///< a grid's world box holding every non-zero density
        /// The trackers' lookups in the grid pick one voxel with probability equal to its
        /// trilinear weight (render.volume.density_filter "stochastic"; RayMediaQuery::density_in).
        bool stochastic_filter = false;
    };
    const FastMedium& fast(uint32_t k) const { return m_fast[k]; }
    /// render.volume.density_filter: "stochastic" (true) makes the trackers' lookups in every
    /// grid medium one-voxel stochastic trilinear lookups (docs/volumes.md); false: trilinear.
    void set_stochastic_filter(bool on) {
        for (FastMedium& f : m_fast)
            f.stochastic_filter = on && f.grid != nullptr;
    }
    /// The medium when the set is exactly one grid medium, else null: the trackers then walk
    /// the grid's bricks lazily (volume/majorant_walk.h).
    const FastMedium* single_grid() const {
        return m_fast.size() == 1 && m_fast[0].grid != nullptr ? &m_fast[0] : nullptr;
    }

    /// Lights whose transmittance can be cached (render.volume.light_cache).
    static constexpr size_t kMaxCachedLights = 8;
    /// The cached transmittance toward directional light number `light_index` (built on first
    /// use, thread-safe; volume/light_cache.h states its bias), or null when the set is not
    /// exactly one grid medium, the light is not directional or light_index is too large.
    const LightTransmittanceCache* light_cache(size_t light_index, const Light& light) const;

  private:
    std::vector<Medium> m_media;
    std::vector<FastMedium> m_fast;
    struct LightCacheSlot {
        std::once_flag once;
        std::unique_ptr<LightTransmittanceCache> cache;
        ~LightCacheSlot();
    };
    /// Shared by copies of the set (they hold the same media).
    std::shared_ptr<std::array<LightCacheSlot, kMaxCachedLights>> m_light_caches;
    bool m_all_homogeneous = true;
    bool m_closed_form = true;
    bool m_grey_extinction = true;
    bool m_emits = false;
    float m_smallest_voxel_m = kInfinity;
};

/// Point queries of a MediumSet along one ray by distance t: each grid's index-space ray is
/// computed once here, so a lookup costs three multiply-adds and the trilinear read (instead of
/// a 4x4 transform per point). Same values as MediumSet::coefficients(ray.at(t), mask) up to
/// rounding. Lives on the stack of one estimator call.
class RayMediaQuery {
  public:
    RayMediaQuery(const MediumSet& media, const Ray& ray) : m_media(media), m_ray(ray) {
        const size_t n = media.media().size();
        for (uint32_t k = 0; k < n; ++k) {
            const MediumSet::FastMedium& m = media.fast(k);
            if (m.grid == nullptr)
                continue;
            m_origin[k] = Vec3(m.world_to_index * Vec4(ray.origin, 1.0f));
            m_direction[k] = Vec3(m.world_to_index * Vec4(ray.direction, 0.0f));
            m_stochastic = m_stochastic || m.stochastic_filter;
        }
        if (m_stochastic)
            m_seed = stochastic_seed(ray);
    }

    /// The ray this query was made for.
    const Ray& ray() const { return m_ray; }
    /// Grid medium k's ray in its index space, o + t d with the query's t: the origin (index
    /// units) and the direction (index units per unit of t). Unset for other media.
    const Vec3& origin_index(uint32_t k) const { return m_origin[k]; }
    const Vec3& direction_index(uint32_t k) const { return m_direction[k]; }

    /// Density of grid medium k at distance t (0 for a homogeneous medium).
    float density(uint32_t k, float t) const {
        const MediumSet::FastMedium& m = m_media.fast(k);
        return m.grid->density(m_origin[k] + t * m_direction[k]);
    }

    /// Density of grid medium k at distance t, a point inside `brick` of its grid (a walk's
    /// visit names it): no brick-table read.
    /// With the medium's stochastic_filter set: one voxel picked with probability equal to its
    /// trilinear weight (DensityGrid::density_in_stochastic), unbiased for the trilinear value.
    float density_in(uint32_t k, const BrickRef& brick, float t) const {
        if (m_stochastic && m_media.fast(k).stochastic_filter)
            return DensityGrid::density_in_stochastic(brick, m_origin[k] + t * m_direction[k],
                                                      stochastic_bits(t));
        return DensityGrid::density_in(brick, m_origin[k] + t * m_direction[k]);
    }

    /// sigma_t and sigma_s at distance t, summing the media in `mask` (a segment's media_mask).
    PointCoefficients coefficients(float t, uint32_t mask) const {
        PointCoefficients c;
        for (; mask != 0; mask &= mask - 1) {
            const uint32_t k = static_cast<uint32_t>(__builtin_ctz(mask));
            const MediumSet::FastMedium& m = m_media.fast(k);
            if (m.other) {
                const PointCoefficients o = m_media.coefficients(m_ray.at(t), 1u << k);
                c.sigma_t += o.sigma_t;
                c.sigma_s += o.sigma_s;
            } else if (m.grid == nullptr) {
                c.sigma_t += m.sigma_t;
                c.sigma_s += m.sigma_s;
            } else {
                const float d = m.grid->density(m_origin[k] + t * m_direction[k]);
                c.sigma_t += m.sigma_t * d;
                c.sigma_s += m.sigma_s * d;
            }
        }
        return c;
    }

  private:
    /// The stochastic lookups' random bits come from a hash of the ray (origin and direction),
    /// the lookup's distance t and its ordinal in this query: deterministic for a given path
    /// (images do not depend on the thread count), and as random as the path's own numbers
    /// (the trackers' distances are drawn from the sampler; the ordinal separates lookups at
    /// the same t). No generator is threaded through the trackers' signatures.
    static uint64_t stochastic_seed(const Ray& ray) {
        uint32_t b[6];
        std::memcpy(b, &ray.origin[0], sizeof(float));
        std::memcpy(b + 1, &ray.origin[1], sizeof(float));
        std::memcpy(b + 2, &ray.origin[2], sizeof(float));
        std::memcpy(b + 3, &ray.direction[0], sizeof(float));
        std::memcpy(b + 4, &ray.direction[1], sizeof(float));
        std::memcpy(b + 5, &ray.direction[2], sizeof(float));
        uint64_t h = 0x2545f4914f6cdd1dULL;
        for (uint32_t x : b)
            h = mix64(h ^ x);
        return h;
    }
    uint64_t stochastic_bits(float t) const {
        uint32_t tb = 0;
        std::memcpy(&tb, &t, sizeof(float));
        return mix64(m_seed ^ mix64((static_cast<uint64_t>(tb) << 32) | m_lookups++));
    }

    const MediumSet& m_media;
    Ray m_ray;
    Vec3 m_origin[kMaxMedia];
    Vec3 m_direction[kMaxMedia];
    bool m_stochastic = false;
    uint64_t m_seed = 0;
    mutable uint32_t m_lookups = 0;
};

}  // namespace kasumi
