#pragma once
/// Stratified light samples for one shading point: the first N points of the 2-D Sobol sequence
/// with Owen scrambling, and the adaptive probe rule that skips the rest of a shading point's
/// shadow rays when its first probes agree (docs/lights.md, "Stratified and adaptive samples").
#include "core/math.h"
#include "core/rng.h"

#include <cstdint>

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

}  // namespace kasumi
