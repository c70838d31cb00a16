#pragma once
/// The training of volume path guiding (volume/guiding/) before a render: passes over the image
/// whose paths record the incident radiance at their scattering vertices, each pass guided by
/// the field the previous one built (Müller, Gross & Novák 2017, sec. 5.4: train, then render
/// with the last field; only the last pass's records build it).
#include "render/render_stats.h"
#include "render/scene_runtime.h"
#include "volume/guiding/guiding_field.h"

#include <cstdint>

namespace kasumi {

/// Training samples use the sample indices from here on, which no render reaches (film.spp is at
/// most 2^20): their generators are independent of the render's.
inline constexpr uint32_t kGuidingTrainingSampleBase = 1u << 24;

/// True when render.volume.guiding is on, or render.volume.splitting is "guided", and the plan
/// runs multiple scattering in media.
bool guiding_applies(const SceneRuntime& scene);

/// render.volume.guiding's training_passes passes of training_spp samples per pixel (parallel
/// over rows in the calling task arena; each row's records in pixel order, rows concatenated
/// in image order, so the field is the same for any thread count). Their work is counted in
/// `counters`. With render.volume.splitting "guided" the field also gets the in-scattered
/// radiance tables (GuidingField::convolve, the first medium's phase function) and each pixel's
/// mean volume luminance over the passes (PixelEstimates). The passes' directions are guided
/// only when render.volume.guiding is on. An empty field when guiding does not apply.
GuidingField train_guiding_field(const SceneRuntime& scene, uint32_t frame,
                                 RenderCounters& counters);

}  // namespace kasumi
