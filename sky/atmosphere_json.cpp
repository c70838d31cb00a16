#include "sky/atmosphere_json.h"

#include "core/reference_spectra.h"
#include "core/wavelength_table_json.h"
#include "phase/phase_json.h"

#include <algorithm>
#include <array>
#include <optional>

namespace kasumi {

namespace {

constexpr double kRayleighDefault[3] = {5.802e-6, 13.558e-6, 33.1e-6};  // Hillaire 2020, 1/m
constexpr double kMieScatteringDefault = 3.996e-6;                      // Bruneton 2017
constexpr double kMieExtinctionDefault = 4.440e-6;
// Ozone: Bruneton 2017's 300 DU in the tent 25 ± 15 km with the 233 K cross sections, i.e.
// 0.650e-6, 1.881e-6, 0.085e-6 1/m at the peak at 680, 550, 440 nm (ozone_absorption_auto).
constexpr double kOzoneCenterDefault = 25000.0, kOzoneHalfWidthDefault = 15000.0;

void fill_rgb(Bands& out, const double rgb[3], const std::vector<double>& nm,
              const std::vector<double>& rgb_nm) {
    for (size_t i = 0; i < nm.size(); ++i)
        out[i] = interpolate_rgb_coefficient(rgb, rgb_nm, nm[i]);
}

enum class AutoCoefficient { None, Rayleigh };

/// A coefficient: a number, [r, g, b], a table (a CSV file path or [[nm, value], ...]),
/// {"table": <table>, "scale": s} (values times s), or (Rayleigh) "auto". Tables are linear in
/// wavelength and must cover every wavelength asked for.
Bands read_coefficient(const JsonNode& node, const std::vector<double>& nm,
                       const std::vector<double>& rgb_nm, AutoCoefficient auto_kind) {
    Bands out{};
    const bool allow_auto = auto_kind != AutoCoefficient::None;
    if (node.is_string() && node.as_string() == "auto") {
        if (!allow_auto)
            node.fail(
                "\"auto\" is not available here: expected a number, [r, g, b], a CSV file "
                "path or {\"table\": ...}");
        for (size_t i = 0; i < nm.size(); ++i)
            out[i] = rayleigh_scattering_standard_air(nm[i]);
        return out;
    }
    std::optional<JsonNode> table_node;
    double scale = 1.0;
    if (is_wavelength_table(node)) {
        table_node = node;
    } else if (node.is_object()) {
        JsonObjectReader reader(node);
        table_node = reader.required("table");
        if (const auto s = reader.optional("scale")) {
            scale = s->as_double();
            if (!(scale >= 0.0))
                s->fail("must be >= 0");
        }
        reader.finish();
    }
    if (table_node) {
        const WavelengthTable table = read_wavelength_table(*table_node);
        for (size_t i = 0; i < nm.size(); ++i)
            out[i] = scale * table.at(nm[i]);
        return out;
    }
    if (!node.is_number() && !node.is_array())
        node.fail(allow_auto ? "expected \"auto\", a number, [r, g, b], a CSV file path or "
                               "{\"table\": ...}"
                             : "expected a number, [r, g, b], a CSV file path or {\"table\": ...}");
    const Rgb rgb = node.non_negative_rgb();
    const double v[3] = {rgb.r, rgb.g, rgb.b};
    fill_rgb(out, v, nm, rgb_nm);
    return out;
}

double positive_double(const JsonNode& n) {
    const double v = n.as_double();
    if (!(v > 0.0))
        n.fail("must be > 0");
    return v;
}

}  // namespace

double interpolate_rgb_coefficient(const double rgb[3], const std::vector<double>& rgb_nm,
                                   double lambda_nm) {
    std::array<std::pair<double, double>, 3> nodes{
        {{rgb_nm[0], rgb[0]}, {rgb_nm[1], rgb[1]}, {rgb_nm[2], rgb[2]}}};
    std::sort(nodes.begin(), nodes.end());
    for (const auto& n : nodes)
        if (std::abs(n.first - lambda_nm) < 1e-9)
            return n.second;
    const size_t k = lambda_nm < nodes[1].first ? 0 : 1;  // segment [k, k+1], ends extrapolate
    const auto [w0, v0] = nodes[k];
    const auto [w1, v1] = nodes[k + 1];
    if (v0 > 0.0 && v1 > 0.0 && w1 > w0) {
        const double exponent = std::log(v1 / v0) / std::log(w1 / w0);
        return v0 * std::pow(lambda_nm / w0, exponent);
    }
    // A zero node: linear, clamped at the ends and at zero.
    const double f = std::clamp((lambda_nm - w0) / (w1 - w0), 0.0, 1.0);
    return std::max(0.0, v0 + f * (v1 - v0));
}

double ozone_peak_number_density(const DensityProfile& profile, double top_altitude_m,
                                 double column_du) {
    return column_du * kDobsonUnitPerM2 / profile.column_m(top_altitude_m);
}

Bands ozone_absorption_auto(const std::vector<double>& nm, double peak_number_density) {
    Bands out{};
    const WavelengthTable& sigma = ozone_cross_section_233k();
    for (size_t i = 0; i < nm.size(); ++i)
        out[i] = sigma.at(nm[i]) * peak_number_density;
    return out;
}

Atmosphere default_earth_atmosphere(const std::vector<double>& nm,
                                    const std::vector<double>& rgb_nm) {
    Atmosphere a;
    a.bands = static_cast<int>(nm.size());
    a.wavelengths_nm = nm;
    fill_rgb(a.rayleigh.scattering, kRayleighDefault, nm, rgb_nm);
    a.rayleigh.profile = DensityProfile::exponential(8000.0);
    for (size_t i = 0; i < nm.size(); ++i)
        a.rayleigh_depolarization[i] = rayleigh_depolarization_standard_air(nm[i]);
    for (size_t i = 0; i < nm.size(); ++i) {
        a.mie.scattering[i] = kMieScatteringDefault;
        a.mie.absorption[i] = kMieExtinctionDefault - kMieScatteringDefault;
        a.ground_albedo[i] = 0.3;
    }
    a.mie.profile = DensityProfile::exponential(1200.0);
    a.ozone.profile = DensityProfile::tent(kOzoneCenterDefault, kOzoneHalfWidthDefault);
    a.ozone.absorption = ozone_absorption_auto(
        nm, ozone_peak_number_density(a.ozone.profile, a.top_radius_m - a.ground_radius_m,
                                      kDefaultOzoneColumnDu));
    a.mie_phase = CornetteShanks{0.8f};
    return a;
}

Atmosphere parse_atmosphere(const JsonNode& node, const std::vector<double>& nm,
                            const std::vector<double>& rgb_nm) {
    JsonObjectReader reader(node);
    Atmosphere a = default_earth_atmosphere(nm, rgb_nm);
    if (const auto v = reader.optional("ground_radius_m"))
        a.ground_radius_m = positive_double(*v);
    if (const auto v = reader.optional("top_radius_m"))
        a.top_radius_m = positive_double(*v);
    if (!(a.top_radius_m > a.ground_radius_m))
        node.fail("top_radius_m must exceed ground_radius_m");
    if (const auto v = reader.optional("ground_albedo")) {
        a.ground_albedo = read_coefficient(*v, nm, rgb_nm, AutoCoefficient::None);
        for (size_t i = 0; i < nm.size(); ++i)
            if (a.ground_albedo[i] > 1.0)
                v->fail("must be in [0, 1]");
    }
    if (const auto v = reader.optional("rayleigh")) {
        JsonObjectReader r(*v);
        if (const auto s = r.optional("scattering"))
            a.rayleigh.scattering = read_coefficient(*s, nm, rgb_nm, AutoCoefficient::Rayleigh);
        const auto h = r.optional("scale_height_m");
        if (h)
            a.rayleigh.profile = DensityProfile::exponential(positive_double(*h));
        if (const auto p = r.optional("profile")) {
            const std::string name = p->as_string();
            if (name == "us_standard_1976") {
                if (h)
                    h->fail("scale_height_m goes with \"profile\": \"exponential\" only");
                a.rayleigh.profile = DensityProfile::us_standard_1976();
            } else if (name != "exponential") {
                p->fail("expected \"exponential\" or \"us_standard_1976\"");
            }
        }
        // Depolarisation factor of the phase: "auto" (default) standard air's at each
        // wavelength, the rho of the King factor of "scattering": "auto"; or one number.
        if (const auto rho = r.optional("depolarization")) {
            if (!(rho->is_string() && rho->as_string() == "auto")) {
                if (!rho->is_number())
                    rho->fail("expected \"auto\" or a number in [0, 0.999]");
                const double value = rho->as_double();
                if (!(value >= 0.0 && value <= 0.999))
                    rho->fail("must be in [0, 0.999]");
                for (size_t i = 0; i < nm.size(); ++i)
                    a.rayleigh_depolarization[i] = value;
            }
        }
        r.finish();
    }
    if (const auto v = reader.optional("mie")) {
        JsonObjectReader r(*v);
        Bands scattering = a.mie.scattering;
        Bands extinction{};
        for (size_t i = 0; i < nm.size(); ++i)
            extinction[i] = a.mie.scattering[i] + a.mie.absorption[i];
        const auto s = r.optional("scattering");
        const auto e = r.optional("extinction");
        if (s)
            scattering = read_coefficient(*s, nm, rgb_nm, AutoCoefficient::None);
        if (e)
            extinction = read_coefficient(*e, nm, rgb_nm, AutoCoefficient::None);
        else if (s)
            extinction = scattering;  // no extinction given: non-absorbing aerosols
        for (size_t i = 0; i < nm.size(); ++i) {
            if (extinction[i] < scattering[i])
                (e ? *e : *s).fail("extinction must be >= scattering at every wavelength");
            a.mie.scattering[i] = scattering[i];
            a.mie.absorption[i] = extinction[i] - scattering[i];
        }
        if (const auto h = r.optional("scale_height_m"))
            a.mie.profile = DensityProfile::exponential(positive_double(*h));
        if (const auto p = r.optional("phase"))
            a.mie_phase = parse_phase(*p);
        r.finish();
    }
    if (const auto v = reader.optional("ozone")) {
        JsonObjectReader r(*v);
        double center = kOzoneCenterDefault, half_width = kOzoneHalfWidthDefault;
        if (const auto c = r.optional("center_m"))
            center = c->as_double();
        if (const auto w = r.optional("half_width_m"))
            half_width = positive_double(*w);
        a.ozone.profile = DensityProfile::tent(center, half_width);
        const auto column = r.optional("column_du");
        const auto s = r.optional("absorption");
        const bool auto_absorption = !s || (s->is_string() && s->as_string() == "auto");
        if (column && !auto_absorption)
            column->fail("column_du goes with \"absorption\": \"auto\" (or no absorption)");
        if (auto_absorption) {
            const double du = column ? column->non_negative() : kDefaultOzoneColumnDu;
            const double thickness = a.ozone.profile.column_m(a.top_radius_m - a.ground_radius_m);
            if (!(thickness > 0.0) && du > 0.0)
                v->fail(
                    "the ozone tent lies outside the atmosphere: no altitude to hold the column");
            a.ozone.absorption = ozone_absorption_auto(
                nm, du > 0.0 ? ozone_peak_number_density(a.ozone.profile,
                                                         a.top_radius_m - a.ground_radius_m, du)
                             : 0.0);
        } else {
            a.ozone.absorption = read_coefficient(*s, nm, rgb_nm, AutoCoefficient::None);
        }
        r.finish();
    }
    reader.optional("comment");
    reader.finish();
    return a;
}

}  // namespace kasumi
