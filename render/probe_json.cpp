#include "render/probe_json.h"

namespace kasumi {

namespace {

Json rgb_json(const Rgb& c) {
    return Json::array({c.r, c.g, c.b});
}

}  // namespace

Json probe_json(const RadianceProbe& probe) {
    return Json{{"radiance", rgb_json(probe.radiance)},
                {"stderr", rgb_json(probe.stderr_)},
                {"luminance_cd_m2", probe.luminance_cd_m2},
                {"samples", probe.samples}};
}

Json probe_json(const TransmittanceProbe& probe, Estimator estimator) {
    return Json{{"transmittance", rgb_json(probe.transmittance)},
                {"stderr", rgb_json(probe.stderr_)},
                {"estimator", estimator_name(estimator)},
                {"samples", probe.samples}};
}

Json probe_json(const IlluminanceProbe& probe) {
    Json per_light = Json::array();
    for (const LightIlluminance& l : probe.per_light) {
        Json entry{{"name", l.name}, {"lux", l.lux}, {"method", illuminance_method_name(l.method)}};
        if (l.method == IlluminanceMethod::Sampled) {
            entry["stderr"] = l.stderr_lux;
            entry["samples"] = l.samples;
        }
        per_light.push_back(entry);
    }
    return Json{{"lux", probe.lux}, {"per_light", per_light}};
}

}  // namespace kasumi
