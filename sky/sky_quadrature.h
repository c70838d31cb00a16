#pragma once
/// The quadrature every sky integral shares: midpoint nodes over [t0, t1] of a ray, crowded
/// toward the point nearest the planet centre (where the air along a straight ray is densest).
#include "sky/atmosphere.h"

namespace kasumi {

/// Calls f(t, dt) for `steps` midpoint nodes over [t0, t1] in increasing t. The interval is
/// split at tc, the point nearest the planet centre; on each side t = tc -/+ L u² with u
/// uniform, so dt = 2 L u du and the nodes crowd toward tc (the substitution is exact: the
/// rule stays second order in du and integrates constants exactly).
template <class F>
void for_each_sky_node(const Atmosphere& a, const DVec3& p, const DVec3& d, double t0, double t1,
                       int steps, F&& f) {
    if (!(t1 > t0) || steps < 1)
        return;
    const double tc = std::clamp(-glm::dot(p - a.center(), d), t0, t1);
    const double l1 = tc - t0, l2 = t1 - tc;
    int n1 = static_cast<int>(std::lround(steps * l1 / (t1 - t0)));
    if (l1 > 0.0)
        n1 = std::max(n1, 1);
    if (l2 > 0.0)
        n1 = std::min(n1, steps - 1);
    n1 = std::max(n1, 0);
    const int n2 = steps - n1;
    for (int k = n1 - 1; k >= 0; --k) {
        const double u = (k + 0.5) / n1;
        f(tc - l1 * u * u, 2.0 * l1 * u / n1);
    }
    for (int k = 0; k < n2; ++k) {
        const double u = (k + 0.5) / n2;
        f(tc + l2 * u * u, 2.0 * l2 * u / n2);
    }
}

}  // namespace kasumi
