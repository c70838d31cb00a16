#pragma once
/// The probes' reports as JSON objects: what `kasumi probe` prints and what the Python module's
/// Scene.probe_* return, one shape for both.
#include "core/json_text.h"
#include "render/illuminance.h"
#include "render/probe.h"
#include "volume/transmittance.h"

namespace kasumi {

/// {"radiance": [R, G, B] (cd/m²), "stderr": [R, G, B], "luminance_cd_m2", "samples"}.
Json probe_json(const RadianceProbe& probe);

/// {"transmittance": [R, G, B], "stderr": [R, G, B], "estimator": its name, "samples"}.
Json probe_json(const TransmittanceProbe& probe, Estimator estimator);

/// {"lux", "per_light": [{"name", "lux", "method", and for sampled lights "stderr" (lux) and
/// "samples"}]}.
Json probe_json(const IlluminanceProbe& probe);

}  // namespace kasumi
