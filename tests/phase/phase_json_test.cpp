#include "phase/phase_json.h"

#include "core/error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

namespace kasumi {
namespace {

PhaseFunction parse(const std::string& text) {
    const Json json = parse_json_text(text, "scene.json");
    return parse_phase(JsonNode(json, "scene.json", "/phase"));
}

std::string error_of(const std::string& text) {
    try {
        parse(text);
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::Input) << e.what();
        return e.what();
    }
    ADD_FAILURE() << "no error for " << text;
    return "";
}

TEST(PhaseJson, ParsesEveryModel) {
    EXPECT_EQ(phase_model_name(parse(R"({"model": "isotropic"})")), "isotropic");
    EXPECT_EQ(phase_model_name(parse(R"({"model": "rayleigh"})")), "rayleigh");
    EXPECT_EQ(std::get<Rayleigh>(parse(R"({"model": "rayleigh", "rho": 0.03})")).rho, 0.03f);
    EXPECT_EQ(std::get<HenyeyGreenstein>(parse(R"({"model": "hg", "g": 0.5})")).g, 0.5f);
    const auto dhg = std::get<DoubleHenyeyGreenstein>(
        parse(R"({"model": "double-hg", "g1": 0.8, "g2": -0.3, "w": 0.7})"));
    EXPECT_EQ(dhg.w, 0.7f);
    EXPECT_EQ(phase_model_name(parse(R"({"model": "cornette-shanks", "g": 0.7})")),
              "cornette-shanks");
    EXPECT_EQ(std::get<Draine>(parse(R"({"model": "draine", "g": 0.4, "alpha": 2})")).alpha, 2.0f);
    EXPECT_EQ(std::get<JendersieDeon>(parse(R"({"model": "jendersie-deon", "diameter_um": 12})"))
                  .diameter_um,
              12.0f);
    const Mie mie = std::get<Mie>(parse(R"({"model": "mie", "x": 3, "m": [1.5, 0.01]})"));
    EXPECT_EQ(mie.summary->x, 3.0);
    const Mie sphere = std::get<Mie>(parse(R"({"model": "mie", "radius_um": 1, "m": [1.33, 0]})"));
    EXPECT_EQ(*sphere.summary->wavelength_nm, 550.0);  // the documented default
    const Mie poly = std::get<Mie>(parse(
        R"({"model": "mie", "distribution": "lognormal", "median_radius_um": 0.3, "sigma": 0.3,
            "m": [1.33, 0], "wavelength_nm": 450, "n_radii": 32})"));
    EXPECT_EQ(poly.summary->n_radii, 32);
    EXPECT_EQ(phase_model_names().size(), std::variant_size_v<PhaseFunction>);
}

TEST(PhaseJson, CopiesShareHeavyTables) {
    const PhaseFunction a = parse(R"({"model": "mie", "x": 30, "m": [1.33, 0]})");
    const PhaseFunction b = a;
    EXPECT_EQ(std::get<Mie>(a).table.get(), std::get<Mie>(b).table.get());
}

TEST(PhaseJson, RejectsOutOfRangeParametersWithLocation) {
    EXPECT_NE(error_of(R"({"model": "hg", "g": 1.0})").find("/phase/g"), std::string::npos);
    error_of(R"({"model": "hg", "g": -1.2})");
    error_of(R"({"model": "double-hg", "g1": 0.5, "g2": 0.1, "w": 1.5})");
    error_of(R"({"model": "draine", "g": 0.5, "alpha": -1})");
    error_of(R"({"model": "jendersie-deon", "diameter_um": 60})");
    error_of(R"({"model": "jendersie-deon", "diameter_um": -1})");
    error_of(R"({"model": "rayleigh", "rho": 1.5})");
    EXPECT_NE(error_of(R"({"model": "mie", "x": 3, "m": [1.5, -0.1]})").find("/phase/m/1"),
              std::string::npos);
    error_of(R"({"model": "mie", "radius_um": -2, "m": [1.5, 0]})");
    error_of(R"({"model": "mie", "x": 0, "m": [1.5, 0]})");
    error_of(R"({"model": "mie", "distribution": "weibull", "m": [1.5, 0]})");
    error_of(R"({"model": "hg", "g": 0.5, "gg": 1})");
    error_of(R"({"model": "tabulated", "file": "/nonexistent.csv"})");
    error_of(R"({"model": "mystery"})");
}

/// `kasumi phase` offers one option per key of phase_parameter_names(): every key a model reads
/// (named by the unknown-key error on each model and each Mie path) must be in it.
TEST(PhaseJson, ParameterNamesCoverEveryModel) {
    const std::vector<std::string> documents = {
        R"({"model": "isotropic")",
        R"({"model": "rayleigh")",
        R"({"model": "hg", "g": 0.5)",
        R"({"model": "double-hg", "g1": 0.8, "g2": -0.3, "w": 0.7)",
        R"({"model": "cornette-shanks", "g": 0.7)",
        R"({"model": "draine", "g": 0.4, "alpha": 2)",
        R"({"model": "jendersie-deon", "diameter_um": 12)",
        R"({"model": "mie", "x": 3, "m": [1.5, 0.01])",
        R"({"model": "mie", "radius_um": 1, "m": [1.33, 0])",
        R"({"model": "mie", "distribution": "lognormal", "median_radius_um": 0.3, "sigma": 0.3,
            "m": [1.33, 0], "n_radii": 8)",
        R"({"model": "mie", "distribution": "modified-gamma", "mode_radius_um": 0.3, "alpha": 2,
            "gamma": 1, "m": [1.33, 0], "n_radii": 8)",
    };
    std::vector<std::string> known = phase_parameter_names();
    known.push_back("model");
    size_t checked = 0;
    for (const std::string& d : documents) {
        const std::string message = error_of(d + R"(, "unknown_key_zz": 1})");
        const std::string marker = "expected one of: ";
        const size_t at = message.find(marker);
        ASSERT_NE(at, std::string::npos) << message;
        std::string list = message.substr(at + marker.size());
        list = list.substr(0, list.find(')'));
        std::stringstream keys(list);
        std::string key;
        while (std::getline(keys, key, ',')) {
            key.erase(0, key.find_first_not_of(' '));
            EXPECT_NE(std::find(known.begin(), known.end(), key), known.end())
                << key << " (read for " << d << ") is missing from phase_parameter_names()";
            ++checked;
        }
    }
    EXPECT_GT(checked, documents.size());
    EXPECT_NE(std::find(known.begin(), known.end(), "file"), known.end());  // tabulated
}

}  // namespace
}  // namespace kasumi
