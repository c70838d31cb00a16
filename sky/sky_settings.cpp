#include "sky/sky_settings.h"

#include "core/json_choice.h"
#include "core/json_int.h"
#include "sky/atmosphere.h"

namespace kasumi {

const char* sky_mode_name(SkyMode mode) {
    return mode == SkyMode::Reference ? "reference" : "fast";
}

void parse_sky_render_keys(JsonObjectReader& render, SkySettings& sky) {
    if (const auto v = render.optional("sky")) {
        JsonObjectReader reader(*v);
        if (const auto m = reader.optional("mode"))
            sky.mode = parse_choice<SkyMode>(
                *m, {{"reference", SkyMode::Reference}, {"fast", SkyMode::Fast}});
        if (const auto m = reader.optional("aerial_perspective"))
            sky.aerial_table = parse_choice<bool>(*m, {{"table", true}, {"march", false}});
        if (const auto o = reader.optional("orders"))
            sky.orders = parse_int_in(*o, 1, 64);
        if (const auto s = reader.optional("view_steps"))
            sky.view_steps = parse_int_in(*s, 4, 4096);
        if (const auto s = reader.optional("sun_steps"))
            sky.sun_steps = parse_int_in(*s, 4, 4096);
        if (const auto s = reader.optional("shafts"))
            sky.shafts = s->as_bool();
        if (const auto s = reader.optional("shaft_distance_m")) {
            sky.shaft_distance_m = s->as_double();
            if (!(sky.shaft_distance_m > 0.0 && sky.shaft_distance_m <= 1e6))
                s->fail("must be a distance in (0, 1e6] m");
        }
        if (const auto s = reader.optional("shaft_samples"))
            sky.shaft_samples = parse_int_in(*s, 1, 1024);
        reader.finish();
    }
    if (const auto v = render.optional("spectral")) {
        if (v->is_string()) {
            if (v->as_string() != "rgb")
                v->fail("expected \"rgb\" or a number of wavelengths");
            sky.spectral_bands = 0;
        } else {
            const int64_t n = v->as_int();
            if (n < 4 || n > kMaxBands)
                v->fail("must be \"rgb\" or a number of wavelengths in [4, " +
                        std::to_string(kMaxBands) + "]");
            sky.spectral_bands = static_cast<int>(n);
        }
    }
    if (const auto v = render.optional("wavelengths_nm")) {
        if (!v->is_array() || v->size() != 3)
            v->fail("expected [red, green, blue] wavelengths in nm");
        for (size_t i = 0; i < 3; ++i) {
            const double nm = v->child(i).as_double();
            if (!(nm >= 360.0 && nm <= 830.0))
                v->child(i).fail("must be in [360, 830] nm");
            sky.rgb_wavelengths_nm[i] = nm;
        }
    }
}

}  // namespace kasumi
