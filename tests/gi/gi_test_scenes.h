#pragma once
/// Scenes with closed-form answers for the global-illumination methods (render.gi), as JSON
/// text, and the list of methods every GI test runs: a new method adds itself to gi_cases().
#include "scene/gi_settings.h"

#include <sstream>
#include <string>
#include <vector>

namespace kasumi {

/// One GI method under test: its render.gi name, extra render settings (a JSON object's members,
/// e.g. "\"path\": {...}"), the probe samples to average and the relative error allowed on top
/// of the statistical bound (4 standard errors). The bound's reason is in the comment of each
/// entry.
struct GiCase {
    std::string gi;
    std::string settings;
    int spp = 1;
    double relative_tolerance = 0.0;
};

inline std::vector<GiCase> gi_cases() {
    return {
        // Radiosity: deterministic up to the jitter of the form-factor points; its error is
        // discretisation (form-factor quadrature, piecewise-constant patches, Gouraud
        // interpolation), a few tenths of a percent at these patch sizes: 2% allowed.
        {"radiosity",
         "\"radiosity\": {\"patch_size_m\": 0.125, \"max_subdivision\": 0, "
         "\"form_factor_samples\": 64, \"tolerance\": 1e-6}",
         1, 0.02},
        // Path tracing: unbiased; only the statistical bound (plus 0.2% for float sums).
        {"path", "\"path\": {\"max_depth\": 200}", 4000, 0.002},
        // The photon-map method adds its entry here.
    };
}

/// Six inward-facing 1 m quads closing the cube [-0.5, 0.5]³ (the front of each faces the
/// inside), all of material `material`.
inline std::string closed_cube_shapes(const std::string& material) {
    std::ostringstream out;
    bool first = true;
    for (int axis = 0; axis < 3; ++axis) {
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        for (int side = 0; side < 2; ++side) {
            const float w = side ? 0.5f : -0.5f;
            float c[4][3];
            const float uv[4][2] = {{-0.5f, -0.5f}, {0.5f, -0.5f}, {0.5f, 0.5f}, {-0.5f, 0.5f}};
            for (int k = 0; k < 4; ++k) {
                c[k][axis] = w;
                c[k][u] = uv[k][0];
                c[k][v] = uv[k][1];
            }
            // (u, v) order winds counter-clockwise toward +axis: inward at the min side only.
            const int order[2][4] = {{0, 1, 2, 3}, {0, 3, 2, 1}};
            out << (first ? "" : ",\n") << "{\"type\": \"quad\", \"material\": \"" << material
                << "\", \"vertices\": [";
            for (int k = 0; k < 4; ++k) {
                const float* p = c[order[side][k]];
                out << (k ? ", " : "") << "[" << p[0] << ", " << p[1] << ", " << p[2] << "]";
            }
            out << "]}";
            first = false;
        }
    }
    return out.str();
}

/// The furnace: the closed cube whose every face emits `le` cd/m² and reflects `rho`
/// (Lambertian). Radiance everywhere inside is L_e / (1 − ρ).
inline std::string furnace_scene(const GiCase& c, double le, double rho) {
    std::ostringstream out;
    out << "{\"camera\": {\"position\": [0, 0, 0], \"look_at\": [0, 0, -1]},"
        << "\"materials\": {\"wall\": {\"type\": \"phong\", \"kd\": " << rho
        << ", \"emission_cd_m2\": " << le << "}},"
        << "\"shapes\": [" << closed_cube_shapes("wall") << "],"
        << "\"render\": {\"gi\": \"" << c.gi << "\"" << (c.settings.empty() ? "" : ", ")
        << c.settings << "}}";
    return out.str();
}

/// A 1 m emitting square (luminance `le`, black: it reflects nothing) facing down at height
/// `height` over a 1 m receiving square (reflectance `rho`) facing up, both centred on the y
/// axis; nothing else. The receiver's centre has radiance ρ F L_e, F the form factor from a
/// point to the emitter (Howell B-3, four corner rectangles).
inline std::string facing_squares_scene(const GiCase& c, double le, double rho, double height) {
    std::ostringstream out;
    out << "{\"camera\": {\"position\": [2, 0.5, 0], \"look_at\": [0, 0, 0]},"
        << "\"materials\": {\"receiver\": {\"type\": \"phong\", \"kd\": " << rho << "},"
        << "\"emitter\": {\"type\": \"phong\", \"kd\": 0, \"emission_cd_m2\": " << le << "}},"
        << "\"shapes\": ["
        << "{\"type\": \"quad\", \"material\": \"receiver\", \"vertices\": "
           "[[-0.5, 0, -0.5], [-0.5, 0, 0.5], [0.5, 0, 0.5], [0.5, 0, -0.5]]},"
        << "{\"type\": \"quad\", \"material\": \"emitter\", \"vertices\": [[-0.5, " << height
        << ", -0.5], [0.5, " << height << ", -0.5], [0.5, " << height << ", 0.5], [-0.5, " << height
        << ", 0.5]]}],"
        << "\"render\": {\"gi\": \"" << c.gi << "\"" << (c.settings.empty() ? "" : ", ")
        << c.settings << "}}";
    return out.str();
}

}  // namespace kasumi
