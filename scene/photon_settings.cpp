#include "scene/photon_settings.h"

#include "core/json_choice.h"
#include "core/json_int.h"

#include <string>

namespace kasumi {

namespace {

uint64_t parse_count(const JsonNode& node) {
    return static_cast<uint64_t>(parse_int_in(node, 0, 100000000));
}

}  // namespace

const char* photon_filter_name(PhotonFilter filter) {
    switch (filter) {
        case PhotonFilter::Box:
            return "box";
        case PhotonFilter::Cone:
            return "cone";
        case PhotonFilter::Epanechnikov:
            return "epanechnikov";
    }
    return "cone";
}

PhotonSettings parse_photon_settings(const JsonNode& node) {
    JsonObjectReader reader(node);
    PhotonSettings s;
    if (auto v = reader.optional("global_count"))
        s.global_count = parse_count(*v);
    if (auto v = reader.optional("caustic_count"))
        s.caustic_count = parse_count(*v);
    if (auto v = reader.optional("volume_count"))
        s.volume_count = parse_count(*v);
    if (auto v = reader.optional("k"))
        s.k = parse_int_in(*v, 1, 10000);
    if (auto v = reader.optional("max_radius_m"))
        s.max_radius_m = v->positive();
    if (auto v = reader.optional("final_gather_samples"))
        s.final_gather_samples = parse_int_in(*v, 0, 4096);
    if (auto v = reader.optional("max_bounces"))
        s.max_bounces = parse_int_in(*v, 1, 1024);
    if (auto v = reader.optional("shadow_count"))
        s.shadow_count = parse_count(*v);
    if (auto v = reader.optional("shadow_k"))
        s.shadow_k = parse_int_in(*v, 1, 1000);
    if (auto v = reader.optional("filter"))
        s.filter = parse_choice<PhotonFilter>(*v, {{"box", PhotonFilter::Box},
                                                   {"cone", PhotonFilter::Cone},
                                                   {"epanechnikov", PhotonFilter::Epanechnikov}});
    reader.finish();
    return s;
}

}  // namespace kasumi
