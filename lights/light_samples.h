#pragma once
/// Stratified light samples for one shading point: the first N points of the 2-D Sobol sequence
/// with Owen scrambling, and the adaptive probe rule that skips the rest of a shading point's
/// shadow rays when its first probes agree (docs/lights.md, "Stratified and adaptive samples").
#include "core/math.h"
#include "core/rng.h"
#include "lights/light.h"
#include "lights/sphere_light.h"

#include <cstdint>
#include <optional>

namespace kasumi {

/// Point `index` of the first two dimensions of Sobol's sequence (dimension 0 is van der
/// Corput's radical inverse in base 2, dimension 1 has the direction numbers v_k = v_{k−1} ^
/// (v_{k−1} >> 1)), each Owen-scrambled (a nested uniform random permutation of its binary
/// digits) by the hash of Burley 2020, "Practical Hash-based Owen Scrambling", JCGT 9(4),
/// keyed by seed0 and seed1. Every aligned block of 2^m consecutive indices is a (0, m, 2)-net:
/// each of the 2^m elementary intervals of area 2^−m (1 × 2^−m, 2 × 2^−(m−1), …) holds exactly
/// one point; over the random scramble each point is uniform in [0, 1)² (so estimates stay
/// unbiased), and integrands smooth except along curves (a shadow's edge) have variance
/// O(N^−3/2) instead of O(N^−1) (Owen 1997).
Vec2 owen_sobol_2d(uint32_t index, uint32_t seed0, uint32_t seed1);

/// The light samples of one shading point: u_k = owen_sobol_2d(k, ...) with seeds drawn once
/// from the caller's stream.
class StratifiedLightSamples {
  public:
    explicit StratifiedLightSamples(Pcg32& rng)
        : m_seed0(rng.next_u32()), m_seed1(rng.next_u32()) {}
    StratifiedLightSamples(uint32_t seed0, uint32_t seed1) : m_seed0(seed0), m_seed1(seed1) {}
    Vec2 operator[](int k) const {
        return owen_sobol_2d(static_cast<uint32_t>(k), m_seed0, m_seed1);
    }
    /// A number in [0, 1) drawn from the seeds without consuming the caller's stream: the
    /// rotation of a shading point's outline probes (OutlineProbes).
    float rotation() const;

  private:
    uint32_t m_seed0, m_seed1;
};

/// What became of one light sample at a shading point.
enum class LightSampleOutcome : uint8_t {
    Ignored,  ///< carries no light to this point (below the horizon, behind the light): not a vote
    Lit,      ///< reached the light
    Blocked,  ///< occluded (by a surface, the shading point's own geometry, or opaque media)
};

/// The adaptive rule (POV-Ray's `adaptive` area lights in spirit, with random stratified probes
/// instead of a fixed grid): after the first `probes` samples, stop when every one that voted
/// agreed (all lit or all blocked) and at least two voted; otherwise take all `samples`.
/// probes = 0 (or ≥ samples) never stops early. Biased: an occluder (or a gap) that no probe
/// sees is missed; the bias vanishes as probes → samples (tested).
class ProbeRule {
  public:
    ProbeRule(int samples, int probes) : m_samples(samples), m_probes(probes) {}
    /// Records sample k's outcome (k counted from 0); true when the remaining samples are to
    /// be skipped.
    bool record(int k, LightSampleOutcome outcome) {
        if (outcome == LightSampleOutcome::Lit)
            ++m_lit;
        else if (outcome == LightSampleOutcome::Blocked)
            ++m_blocked;
        if (m_probes <= 0 || m_probes >= m_samples || k + 1 != m_probes)
            return false;
        return (m_lit == 0 || m_blocked == 0) && m_lit + m_blocked >= 2;
    }

  private:
    int m_samples, m_probes;
    int m_lit = 0, m_blocked = 0;
};

/// One extended light's samples at one shading point p: sphere lights set up their cone once
/// (SphereLightCone) instead of per sample; other lights call sample_incident(light, p, u).
/// sample(u) equals sample_incident(light, p, u) bit for bit.
class PointLightSampler {
  public:
    PointLightSampler(const Light& light, const Vec3& p);
    IncidentLight sample(Vec2 u) const {
        return m_cone ? m_cone->sample(u) : sample_incident(m_light, m_p, u);
    }
    /// The sphere light's cone at p, or null for other lights.
    const SphereLightCone* sphere_cone() const { return m_cone ? &*m_cone : nullptr; }

  private:
    const Light& m_light;
    Vec3 m_p;
    std::optional<SphereLightCone> m_cone;
};

/// Outline probes (`outline_probes`, docs/lights.md): K shadow rays toward points evenly spaced
/// on the outline of a sphere light as seen from p (the boundary of the cone it subtends, at
/// azimuths (j + r) 2π/K for j = 0..K−1 and one random rotation r per point). They are not
/// samples: when they all agree, the point is taken as entirely lit or entirely in umbra and
/// its light is the closed-form unshadowed value or zero, with no samples traced; otherwise
/// the light's `samples` are traced as usual (the probes are not part of the estimate).
///
/// Why the outline: a straight occluder edge that covers part of the light's disc crosses its
/// outline twice, so it is missed only when both crossings fall between two neighbouring
/// probes, i.e. when it cuts off less than a circular segment of angle α = 2π/K. That bounds
/// the light missed (or wrongly taken) at a point by the segment's share of the disc,
/// (α − sin α) / (2π): 9.1% for K = 4, 2.9% for 6, 1.2% for 8, 0.37% for 12, 0.16% for 16
/// (outline_probe_bound). Probes at stratified points inside the disc have no such bound (a
/// sliver along the rim passes between them). Not bounded: an occluder whose shadow on the
/// light lies wholly inside the disc (a thin bar, a small ball) or a curved edge that bulges
/// in between probes; both are missed as POV-Ray's `adaptive` corner tests miss them.
struct OutlineProbes {
    /// The azimuth of probe j of k, rotation r in [0, 1).
    static float azimuth(int j, int k, float r) {
        return (static_cast<float>(j) + r) * (kTwoPi / static_cast<float>(k));
    }
};

/// What a point's outline probes say about the light.
enum class OutlineVerdict : uint8_t {
    Mixed,     ///< they disagree, or part of the cone is below a horizon: trace the samples
    Lit,       ///< none is blocked: taken as entirely lit
    Shadowed,  ///< all are blocked: taken as the umbra
};

/// Casts the k outline probes of a sphere light's cone at a point of geometric normal ng and
/// shading normal ns (both facing the viewer), rotated by r in [0, 1); `blocked(in)` traces one
/// probe (an IncidentLight from cone.outline) and returns true when a surface blocks it. Stops
/// at the first disagreement. Mixed, without casting a ray, unless the whole cone lies above
/// both planes (so every sample would count, and the closed form holds unclipped).
template <class Blocked>
OutlineVerdict outline_verdict(const SphereLightCone& cone, const Vec3& ng, const Vec3& ns, int k,
                               float r, Blocked&& blocked) {
    if (k <= 0 || !cone.above_plane(ng) || !cone.above_plane(ns))
        return OutlineVerdict::Mixed;
    int n_blocked = 0;
    for (int j = 0; j < k; ++j) {
        n_blocked += blocked(cone.outline(OutlineProbes::azimuth(j, k, r))) ? 1 : 0;
        if (n_blocked != 0 && n_blocked != j + 1)
            return OutlineVerdict::Mixed;
    }
    return n_blocked == 0 ? OutlineVerdict::Lit : OutlineVerdict::Shadowed;
}

/// (α − sin α) / (2π) with α = 2π/k: the largest share of a disc's area that a straight line
/// can cut off without separating two of k points evenly spaced on its circle.
double outline_probe_bound(int k);

}  // namespace kasumi
