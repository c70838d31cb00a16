#pragma once
/// Russian roulette and splitting of volume paths by a weight window on their expected
/// contribution (Vorba & Křivánek 2016, "Adjoint-driven Russian roulette and splitting in light
/// transport simulation", sec. 4; in media, Herholz et al. 2019, "Volume path guiding based on
/// zero-variance random walk theory", sec. 5.3). A path at a scattering vertex x with
/// throughput beta expects to bring back about beta I(x), I an importance estimate of the light
/// scattered at x; against the window's centre W (fixed at the path's first scattering vertex)
/// the ratio q = beta I(x) / W becomes n copies with E[n] = q' (q clamped), each weighted 1 / q':
/// E[n / q'] = 1, so the estimate stays unbiased for any I > 0 and W > 0 (render.volume.splitting
/// "sun"; docs/volumes.md, "Multiple scattering in clouds").
#include "lights/light.h"
#include "volume/guiding/guiding_field.h"
#include "volume/medium_set.h"

#include <vector>

namespace kasumi {

/// Importance of scattering vertex `p_world` (metres): the sum over directional lights of
/// luminance(illuminance) (kImportanceFloor + T(p)^kTransportExponent), T the mean-channel
/// transmittance toward the light from its cache (volume/light_cache.h: biased, which only
/// steers the window and never enters an estimate). The power stands for the light scattered
/// many times, which decays with the transport optical depth tau (1 - g) rather than tau
/// (similarity relation, van de Hulst 1980; g = 0.8 for clouds gives 0.2); the floor for the
/// core no beam reaches. 1 when no light has a cache (the window then acts on the throughput
/// alone). lux; only ratios matter. Never throws.
float sun_importance(const MediumSet& media, const std::vector<Light>& lights, const Vec3& p_world);

/// render.volume.splitting "guided": the expected contribution of continuing a path of mean
/// throughput `beta` (after the free flight, 1/(1/m)) from scattering vertex `p_world` (metres)
/// whose arriving path points back along `wo`: beta sigma_s I(x, wo), I the field's learnt
/// in-scattered radiance (GuidingField::scattered_radiance, cd/m²; biased, it only steers),
/// sigma_s the mean scattering coefficient there (1/m). Negative where the field has no value
/// (the window then keeps the path as it is).
float guided_expected(const GuidingField& field, const Vec3& p_world, const Vec3& wo, float sigma_s,
                      float beta);

/// The window's ratio q for an expected contribution against the window's centre: 1 (keep)
/// when either is negative or the centre is not positive (no centre yet); else expected /
/// centre, raised to kMinSurvival when the estimate is 0 (a path the field calls dark may
/// still carry light: it survives at the floor, so the estimate stays unbiased).
float window_ratio(float expected, float centre);

/// How a path continues: `copies` independent continuations (0: killed), each weighted by
/// `weight` (1 / q', so E[copies x weight] = 1).
struct SplitDecision {
    int copies = 1;
    float weight = 1.0f;
};

/// The window's decision for ratio q = beta I(x) / W (>= 0; not finite or <= 0: killed) and a
/// uniform u in [0, 1): q in [1/2, 2] keeps the path as it is; otherwise q' = q clamped to
/// [kMinSurvival, kMaxCopies] and copies = floor(q') + (u < frac(q')) (stochastic rounding,
/// E[copies] = q'), weight 1 / q'.
SplitDecision split_decision(float q, float u);

/// The survival probability's floor: a path whose q falls lower is still continued this often.
inline constexpr float kMinSurvival = 0.05f;
/// At most this many copies from one vertex (bounds the work one path can spawn per vertex).
inline constexpr float kMaxCopies = 8.0f;
/// I's floor relative to a fully lit point, and the power of T (sun_importance; chosen on
/// data/scenes/cloud.json, HG g = 0.8: floor 0.1 and T^1 were worse, docs/volumes.md).
inline constexpr float kImportanceFloor = 0.02f;
inline constexpr float kTransportExponent = 0.2f;

}  // namespace kasumi
