#include "gi/form_factor.h"

#include "core/error.h"

#include <cmath>

namespace kasumi {

namespace {

/// Sutherland-Hodgman: the part of the polygon where dot(n, y - x) >= 0. At most count + 1
/// vertices for a convex polygon (one plane cuts at most two edges).
int clip_to_hemisphere(const DVec3& x, const DVec3& n, const DVec3* in, int count, DVec3* out) {
    int m = 0;
    for (int i = 0; i < count; ++i) {
        const DVec3& a = in[i];
        const DVec3& b = in[(i + 1) % count];
        const double da = glm::dot(n, a - x), db = glm::dot(n, b - x);
        if (da >= 0.0)
            out[m++] = a;
        if ((da >= 0.0) != (db >= 0.0)) {
            const double t = da / (da - db);
            out[m++] = a + t * (b - a);
        }
    }
    return m;
}

}  // namespace

double point_to_polygon_form_factor(const DVec3& x, const DVec3& n, const DVec3* vertices,
                                    int count) {
    // The polygon's front must face x (one-sided surfaces exchange light from their fronts).
    DVec3 newell(0.0);
    for (int i = 0; i < count; ++i)
        newell += glm::cross(vertices[i], vertices[(i + 1) % count]);
    if (!(glm::dot(newell, x - vertices[0]) > 0.0))
        return 0.0;
    // Clipping a convex polygon adds at most one vertex.
    KASUMI_CHECK(count >= 3 && count <= kMaxFormFactorVertices);
    DVec3 clipped[kMaxFormFactorVertices + 1];
    const int m = clip_to_hemisphere(x, n, vertices, count, clipped);
    if (m < 3)
        return 0.0;
    double sum = 0.0;
    for (int i = 0; i < m; ++i) {
        const DVec3 a = glm::normalize(clipped[i] - x);
        const DVec3 b = glm::normalize(clipped[(i + 1) % m] - x);
        const DVec3 c = glm::cross(a, b);
        const double s = glm::length(c);
        if (!(s > 0.0))
            continue;
        // Θ by atan2 of sine and cosine: accurate for small and near-π angles alike.
        const double theta = std::atan2(s, glm::dot(a, b));
        sum += theta * glm::dot(n, c) / s;
    }
    // The sign follows the winding as seen from x; the magnitude is the form factor.
    return std::min(1.0, std::abs(sum) / (2.0 * kPiD));
}

FormFactorPatch make_form_factor_patch(const Vec3* vertices, int count) {
    FormFactorPatch p;
    p.count = count;
    DVec3 newell(0.0);
    for (int i = 0; i < count; ++i)
        p.vertices[i] = DVec3(vertices[i]);
    for (int i = 0; i < count; ++i)
        newell += glm::cross(p.vertices[i], p.vertices[(i + 1) % count]);
    const double twice_area = glm::length(newell);
    p.area = 0.5 * twice_area;
    p.normal = twice_area > 0.0 ? newell / twice_area : DVec3(0.0, 0.0, 1.0);
    return p;
}

DVec3 patch_point(const FormFactorPatch& p, double u, double v) {
    if (p.count == 3) {
        if (u + v > 1.0) {
            u = 1.0 - u;
            v = 1.0 - v;
        }
        return p.vertices[0] + u * (p.vertices[1] - p.vertices[0]) +
               v * (p.vertices[2] - p.vertices[0]);
    }
    return (1.0 - u) * (1.0 - v) * p.vertices[0] + u * (1.0 - v) * p.vertices[1] +
           u * v * p.vertices[2] + (1.0 - u) * v * p.vertices[3];
}

double form_factor(const FormFactorPatch& i, const FormFactorPatch& j, int n,
                   const std::function<bool(const DVec3&, const DVec3&)>& visible,
                   const std::function<double()>& jitter) {
    const int strata = n * n;
    double sum = 0.0;
    for (int k = 0; k < strata; ++k) {
        const int a = k % n, b = k / n;
        const double ju = jitter ? jitter() : 0.5, jv = jitter ? jitter() : 0.5;
        const DVec3 x = patch_point(i, (a + ju) / n, (b + jv) / n);
        const double f = point_to_polygon_form_factor(x, i.normal, j.vertices, j.count);
        if (!(f > 0.0))
            continue;
        if (visible) {
            // A different stratum of j for each point of i (37 is prime to n² for n < 37).
            const int kj = (k * 37 + 11) % strata;
            const double wu = jitter ? jitter() : 0.5, wv = jitter ? jitter() : 0.5;
            const DVec3 y = patch_point(j, (kj % n + wu) / n, (kj / n + wv) / n);
            if (!visible(x, y))
                continue;
        }
        sum += f;
    }
    return sum / strata;
}

}  // namespace kasumi
