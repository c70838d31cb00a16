#include "phase/phase_json.h"

#include "core/error.h"

namespace kasumi {

namespace {

float read_g(JsonObjectReader& reader, const std::string& key) {
    return reader.required(key).in_open(-1.0f, 1.0f);
}

/// `m` as [re, im] with re > 0 and im >= 0 (Bohren & Huffman's m = n + ik).
Complex read_index(JsonObjectReader& reader) {
    const JsonNode node = reader.required("m");
    if (node.is_number()) {
        const double re = node.as_double();
        if (!(re > 0.0))
            node.fail("real part of the refractive index must be > 0");
        return Complex(re, 0.0);
    }
    if (!node.is_array() || node.size() != 2)
        node.fail("expected [re, im] (or a real number)");
    const double re = node.child(size_t{0}).as_double();
    const double im = node.child(size_t{1}).as_double();
    if (!(re > 0.0))
        node.child(size_t{0}).fail("real part of the refractive index must be > 0");
    if (!(im >= 0.0))
        node.child(size_t{1}).fail(
            "imaginary part must be >= 0 (absorption is m = n + ik with k >= 0)");
    return Complex(re, im);
}

double read_positive(JsonObjectReader& reader, const std::string& key) {
    const JsonNode node = reader.required(key);
    const double v = node.as_double();
    if (!(v > 0.0))
        node.fail("must be > 0");
    return v;
}

double read_positive_or(JsonObjectReader& reader, const std::string& key, double fallback) {
    return reader.has(key) ? read_positive(reader, key) : fallback;
}

std::string resolve_path(const JsonNode& at, const std::string& path) {
    if (path.empty() || path[0] == '/')
        return path;
    const auto slash = at.file().find_last_of('/');
    return slash == std::string::npos ? path : at.file().substr(0, slash + 1) + path;
}

Mie parse_mie(JsonObjectReader& reader) {
    const Complex m = read_index(reader);
    if (reader.has("x")) {
        const JsonNode x_node = reader.required("x");
        const double x = x_node.as_double();
        if (!(x > 0.0 && x <= 1e5))
            x_node.fail("size parameter must be in (0, 1e5]");
        return make_mie(x, m);
    }
    const double wavelength_nm = read_positive_or(reader, "wavelength_nm", 550.0);
    const double medium_index = read_positive_or(reader, "medium_index", 1.0);
    if (!reader.has("distribution"))
        return make_mie_sphere(read_positive(reader, "radius_um"), wavelength_nm, m, medium_index);
    const JsonNode dist_node = reader.required("distribution");
    const std::string dist = dist_node.as_string();
    SizeDistribution sizes;
    if (dist == "lognormal") {
        sizes = LogNormalSizes{read_positive(reader, "median_radius_um"),
                               read_positive(reader, "sigma")};
    } else if (dist == "modified-gamma") {
        sizes = ModifiedGammaSizes{read_positive(reader, "mode_radius_um"),
                                   read_positive(reader, "alpha"), read_positive(reader, "gamma")};
    } else {
        dist_node.fail("unknown size distribution (expected lognormal or modified-gamma)");
    }
    int n_radii = 0;
    if (const auto node = reader.optional("n_radii")) {
        const int64_t n = node->as_int();
        if (n < 2 || n > 100000)
            node->fail("must be in [2, 100000]");
        n_radii = static_cast<int>(n);
    }
    return make_mie_polydisperse(sizes, wavelength_nm, m, medium_index, n_radii);
}

}  // namespace

const std::vector<std::string>& phase_model_names() {
    static const std::vector<std::string> names = {"isotropic",      "rayleigh",        "hg",
                                                   "double-hg",      "cornette-shanks", "draine",
                                                   "jendersie-deon", "tabulated",       "mie"};
    return names;
}

const std::vector<std::string>& phase_parameter_names() {
    static const std::vector<std::string> names = {"g",
                                                   "rho",
                                                   "g1",
                                                   "g2",
                                                   "w",
                                                   "alpha",
                                                   "diameter_um",
                                                   "file",
                                                   "m",
                                                   "x",
                                                   "radius_um",
                                                   "wavelength_nm",
                                                   "medium_index",
                                                   "distribution",
                                                   "median_radius_um",
                                                   "sigma",
                                                   "mode_radius_um",
                                                   "gamma",
                                                   "n_radii"};
    return names;
}

PhaseFunction parse_phase(const JsonNode& node) {
    JsonObjectReader reader(node);
    const std::string model = reader.required("model").as_string();
    PhaseFunction result;
    if (model == "isotropic") {
        result = Isotropic{};
    } else if (model == "hg") {
        result = HenyeyGreenstein{read_g(reader, "g")};
    } else if (model == "rayleigh") {
        const auto rho = reader.optional("rho");
        result = Rayleigh{rho ? rho->in_closed(0.0f, 0.999f) : 0.0f};
    } else if (model == "double-hg") {
        const float g1 = read_g(reader, "g1");
        const float g2 = read_g(reader, "g2");
        result = DoubleHenyeyGreenstein{g1, g2, reader.required("w").in_closed(0.0f, 1.0f)};
    } else if (model == "cornette-shanks") {
        result = CornetteShanks{read_g(reader, "g")};
    } else if (model == "draine") {
        const float g = read_g(reader, "g");
        const JsonNode alpha = reader.required("alpha");
        const float a = alpha.as_float();
        if (!(a >= 0.0f && a <= 1e4f))
            alpha.fail("must be in [0, 1e4]");
        result = Draine{g, a};
    } else if (model == "jendersie-deon") {
        const JsonNode d = reader.required("diameter_um");
        const float diameter = d.as_float();
        if (!(diameter > 0.0f && diameter <= 50.0f))
            d.fail("droplet diameter must be in (0, 50] µm (the range of the published fit)");
        result = make_jendersie_deon(diameter);
    } else if (model == "tabulated") {
        const JsonNode file = reader.required("file");
        const std::string path = resolve_path(node, file.as_string());
        try {
            result =
                Tabulated{std::make_shared<const PhaseTable>(read_phase_table_csv(path)), path};
        } catch (const Error& e) {
            file.fail(e.what());  // the file's own error, located in the scene
        }
    } else if (model == "mie") {
        try {
            result = parse_mie(reader);
        } catch (const Error& e) {
            // Located already when it came from a JsonNode; otherwise add the object's location.
            if (std::string(e.what()).rfind(node.file(), 0) == 0)
                throw;
            node.fail(e.what());
        }
    } else {
        reader.required("model").fail(
            "unknown phase model (expected isotropic, rayleigh, hg, double-hg, cornette-shanks, "
            "draine, jendersie-deon, tabulated or mie)");
    }
    reader.finish();
    return result;
}

std::string phase_model_name(const PhaseFunction& p) {
    struct Name {
        std::string operator()(const Isotropic&) const { return "isotropic"; }
        std::string operator()(const HenyeyGreenstein&) const { return "hg"; }
        std::string operator()(const Rayleigh&) const { return "rayleigh"; }
        std::string operator()(const DoubleHenyeyGreenstein&) const { return "double-hg"; }
        std::string operator()(const CornetteShanks&) const { return "cornette-shanks"; }
        std::string operator()(const Draine&) const { return "draine"; }
        std::string operator()(const JendersieDeon&) const { return "jendersie-deon"; }
        std::string operator()(const Tabulated&) const { return "tabulated"; }
        std::string operator()(const Mie&) const { return "mie"; }
    };
    return std::visit(Name{}, p);
}

}  // namespace kasumi
