#include "lights/ies_profile.h"

#include <algorithm>

namespace kasumi {

namespace {

/// Index i with angles[i] <= x <= angles[i + 1] and the weight of angles[i + 1]; angles holds at
/// least two increasing values and x lies in their range.
std::pair<size_t, float> bracket(const std::vector<float>& angles, float x) {
    const auto it = std::upper_bound(angles.begin() + 1, angles.end() - 1, x);
    const auto i = static_cast<size_t>(it - angles.begin()) - 1;
    const float span = angles[i + 1] - angles[i];
    const float w = span > 0.0f ? std::clamp((x - angles[i]) / span, 0.0f, 1.0f) : 0.0f;
    return {i, w};
}

}  // namespace

float ies_tilt_multiplier(const IesProfile& profile, float tilt_deg) {
    const std::vector<float>& a = profile.tilt.angle_deg;
    const std::vector<float>& m = profile.tilt.multiplier;
    if (a.empty())
        return 1.0f;
    float t = std::isfinite(tilt_deg) ? std::clamp(tilt_deg, 0.0f, 180.0f) : 0.0f;
    // A table measured up to 90° at most: above 90° the lamp axis makes the angle 180° − t with
    // the vertical (Radiance's ies2rad likewise reads such tables with a second tilt function).
    if (a.back() <= 90.0f && t > 90.0f)
        t = 180.0f - t;
    if (a.size() == 1 || t <= a.front())
        return m.front();
    if (t >= a.back())
        return m.back();
    const auto [i, w] = bracket(a, t);
    return m[i] + w * (m[i + 1] - m[i]);
}

float ies_candela(const IesProfile& profile, float vertical_deg, float horizontal_deg) {
    const std::vector<float>& v = profile.vertical_deg;
    if (!(vertical_deg >= v.front() && vertical_deg <= v.back()))
        return 0.0f;
    float c = std::fmod(horizontal_deg, 360.0f);
    if (c < 0.0f)
        c += 360.0f;
    const size_t nv = v.size();
    const auto [iv, wv] = bracket(v, vertical_deg);
    const auto [ih, wh] = bracket(profile.horizontal_deg, c);
    const float* row0 = &profile.candela[ih * nv];
    const float* row1 = &profile.candela[(ih + 1) * nv];
    const float a = row0[iv] + wv * (row0[iv + 1] - row0[iv]);
    const float b = row1[iv] + wv * (row1[iv + 1] - row1[iv]);
    return a + wh * (b - a);
}

float ies_candela(const IesProfile& profile, const Vec3& direction_local) {
    // γ from the nadir (−z); C counter-clockwise from +x seen from above (+z).
    const float gamma = degrees(safe_acos(-direction_local.z));
    const float c = degrees(std::atan2(direction_local.y, direction_local.x));
    return ies_candela(profile, gamma, c);
}

double ies_flux_lm(const IesProfile& profile) {
    const std::vector<float>& v = profile.vertical_deg;
    const std::vector<float>& h = profile.horizontal_deg;
    const size_t nv = v.size();
    double flux = 0.0;
    for (size_t j = 0; j + 1 < nv; ++j) {
        const double g0 = v[j] * (kPiD / 180.0), g1 = v[j + 1] * (kPiD / 180.0);
        const double dg = g1 - g0;
        if (!(dg > 0.0))
            continue;
        // ∫ (g1 − γ)/Δ sin γ dγ and ∫ (γ − g0)/Δ sin γ dγ over [g0, g1], by parts.
        const double w0 = (dg * std::cos(g0) + std::sin(g0) - std::sin(g1)) / dg;
        const double w1 = (-dg * std::cos(g1) + std::sin(g1) - std::sin(g0)) / dg;
        for (size_t i = 0; i + 1 < h.size(); ++i) {
            const double dc = (h[i + 1] - h[i]) * (kPiD / 180.0);
            // Linear in C: the trapezoid rule is exact.
            const double i0 =
                0.5 * (profile.candela[i * nv + j] + profile.candela[(i + 1) * nv + j]);
            const double i1 =
                0.5 * (profile.candela[i * nv + j + 1] + profile.candela[(i + 1) * nv + j + 1]);
            flux += dc * (w0 * i0 + w1 * i1);
        }
    }
    return flux;
}

}  // namespace kasumi
