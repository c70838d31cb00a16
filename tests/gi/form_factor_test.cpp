// Form factors of the radiosity code (gi/form_factor.h) against closed forms from Howell's
// catalogue of radiation configuration factors (J. R. Howell, "A Catalog of Radiation Heat
// Transfer Configuration Factors", 3rd ed., cases B-3, C-11 and C-14; the same formulas are in
// Siegel & Howell, "Thermal Radiation Heat Transfer", appendix C). Deterministic (no sampling
// noise without occluders): the point-to-polygon rule is the midpoint rule on an exact inner
// integral, so the only error is quadrature error, O(h²).
#include "gi/form_factor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace kasumi {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// Howell C-11: parallel, directly opposed rectangles a × b at distance c; X = a/c, Y = b/c.
///   F = 2/(π X Y) { ln sqrt[(1+X²)(1+Y²)/(1+X²+Y²)] + X sqrt(1+Y²) atan(X/sqrt(1+Y²))
///                   + Y sqrt(1+X²) atan(Y/sqrt(1+X²)) − X atan X − Y atan Y }
double howell_c11(double a, double b, double c) {
    const double x = a / c, y = b / c;
    const double x2 = x * x, y2 = y * y;
    return 2.0 / (kPi * x * y) *
           (std::log(std::sqrt((1 + x2) * (1 + y2) / (1 + x2 + y2))) +
            x * std::sqrt(1 + y2) * std::atan(x / std::sqrt(1 + y2)) +
            y * std::sqrt(1 + x2) * std::atan(y / std::sqrt(1 + x2)) - x * std::atan(x) -
            y * std::atan(y));
}

/// Howell C-14: rectangles sharing an edge of length l at 90°: surface 1 of width w, surface 2
/// of height h; H = h/l, W = w/l.
///   F_12 = 1/(π W) { W atan(1/W) + H atan(1/H) − sqrt(H²+W²) atan(1/sqrt(H²+W²))
///          + 1/4 ln( (1+W²)(1+H²)/(1+W²+H²) · [W²(1+W²+H²)/((1+W²)(W²+H²))]^(W²)
///                                            · [H²(1+H²+W²)/((1+H²)(H²+W²))]^(H²) ) }
double howell_c14(double w, double h, double l) {
    const double W = w / l, H = h / l, W2 = W * W, H2 = H * H;
    const double r = std::sqrt(H2 + W2);
    const double log_term = std::log((1 + W2) * (1 + H2) / (1 + W2 + H2)) +
                            W2 * std::log(W2 * (1 + W2 + H2) / ((1 + W2) * (W2 + H2))) +
                            H2 * std::log(H2 * (1 + H2 + W2) / ((1 + H2) * (H2 + W2)));
    return 1.0 / (kPi * W) *
           (W * std::atan(1 / W) + H * std::atan(1 / H) - r * std::atan(1 / r) + 0.25 * log_term);
}

/// Howell B-3: differential area to a parallel rectangle a × b at distance c, the normal
/// through one corner; X = a/c, Y = b/c.
///   F = 1/(2π) { X/sqrt(1+X²) atan(Y/sqrt(1+X²)) + Y/sqrt(1+Y²) atan(X/sqrt(1+Y²)) }
double howell_b3(double a, double b, double c) {
    const double x = a / c, y = b / c;
    return 1.0 / (2.0 * kPi) *
           (x / std::sqrt(1 + x * x) * std::atan(y / std::sqrt(1 + x * x)) +
            y / std::sqrt(1 + y * y) * std::atan(x / std::sqrt(1 + y * y)));
}

/// Rectangle a × b in the plane z = z0, wound counter-clockwise about +z (facing up) or -z.
FormFactorPatch horizontal(double a, double b, double z0, bool facing_up) {
    Vec3 v[4] = {Vec3(0, 0, z0), Vec3(a, 0, z0), Vec3(a, b, z0), Vec3(0, b, z0)};
    if (!facing_up)
        std::swap(v[1], v[3]);
    return make_form_factor_patch(v, 4);
}

TEST(FormFactorTest, TheQuadratureConstantsMatchPublishedValues) {
    // Sanity of the transcribed formulas: unit squares one apart, F = 0.1998 (Howell C-11
    // table); unit squares at 90°, F = 0.2000 (C-14 table).
    EXPECT_NEAR(howell_c11(1, 1, 1), 0.1998, 1e-4);
    EXPECT_NEAR(howell_c14(1, 1, 1), 0.2000, 1e-4);
}

TEST(FormFactorTest, PointToRectangleIsHowellB3) {
    for (const auto& [a, b, c] : {std::array<double, 3>{1, 1, 1}, {2, 0.5, 1}, {0.3, 3, 2}}) {
        const DVec3 rect[4] = {DVec3(0, 0, c), DVec3(0, b, c), DVec3(a, b, c), DVec3(a, 0, c)};
        const double f = point_to_polygon_form_factor(DVec3(0), DVec3(0, 0, 1), rect, 4);
        EXPECT_NEAR(f, howell_b3(a, b, c), 1e-9) << a << " " << b << " " << c;
    }
}

/// Howell's catalogue, section B, "plane element dA1 to plane parallel circular disk A2" (the
/// normal of dA1 through the centre, and offset; also Siegel & Howell, appendix C): a disk of
/// radius r at height h, the element's normal a distance a from the disk's axis; H = h/a,
/// R = r/a, Z = 1 + H² + R²:  F = 1/2 [1 − (1 + H² − R²) / sqrt(Z² − 4R²)].
/// On the axis (a → 0) it is r² / (r² + h²).
double howell_parallel_disk(double a, double h, double r) {
    if (a == 0.0)
        return r * r / (r * r + h * h);
    const double hh = h / a, rr = r / a, z = 1.0 + hh * hh + rr * rr;
    return 0.5 * (1.0 - (1.0 + hh * hh - rr * rr) / std::sqrt(z * z - 4.0 * rr * rr));
}

TEST(FormFactorTest, PointToParallelDiskMatchesHowellsClosedForms) {
    // Lambert's formula is additive over a fan of thin triangles: the sum over a 4096-gon
    // inscribed in the disk must equal the disk's closed form up to the area the polygon misses,
    // (2π/N)²/6 ≈ 4e-7 relative. The element at the origin faces +z; the disk at height h faces
    // down (clockwise seen from above), its centre offset by a along x. Cases on the axis, under
    // the disk, beside it.
    const int n = 4096;
    for (const auto& [a, h, r] :
         {std::array<double, 3>{0, 1, 1}, {0.5, 1, 1}, {2, 1, 1}, {3, 2, 1.5}, {0.2, 0.1, 5}}) {
        double f = 0.0;
        for (int i = 0; i < n; ++i) {
            const double t0 = 2.0 * kPi * i / n, t1 = 2.0 * kPi * (i + 1) / n;
            const DVec3 fan[3] = {DVec3(a, 0, h), DVec3(a + r * std::cos(t1), r * std::sin(t1), h),
                                  DVec3(a + r * std::cos(t0), r * std::sin(t0), h)};
            f += point_to_polygon_form_factor(DVec3(0), DVec3(0, 0, 1), fan, 3);
        }
        const double expected = howell_parallel_disk(a, h, r);
        EXPECT_NEAR(f, expected, 2e-6 * expected) << a << " " << h << " " << r;
    }
}

TEST(FormFactorTest, ManySidedPolygonEqualsTheSumOfItsFan) {
    // Lambert's formula is additive: a convex 16- or 64-gon (tilted so the receiver's horizon
    // cuts it) must give the sum over its fan triangles, each clipped on its own. The clip
    // buffer once held 8 vertices and silently used only the first 7.
    for (const int n : {16, 64}) {
        std::vector<DVec3> polygon;
        for (int i = n - 1; i >= 0; --i) {  // clockwise seen from +z: faces down
            const double t = 2.0 * kPi * i / n;
            polygon.emplace_back(0.3 + std::cos(t), std::sin(t), 0.5 + 0.6 * std::cos(t));
        }
        const DVec3 x(0.0), normal = glm::normalize(DVec3(0.3, 0.0, 1.0));
        double fan = 0.0;
        for (int i = 1; i + 1 < n; ++i) {
            const DVec3 tri[3] = {polygon[0], polygon[i], polygon[i + 1]};
            fan += point_to_polygon_form_factor(x, normal, tri, 3);
        }
        ASSERT_GT(fan, 0.05);
        EXPECT_NEAR(point_to_polygon_form_factor(x, normal, polygon.data(), n), fan, 1e-12) << n;
    }
}

TEST(FormFactorTest, PointBehindOrTangentPolygonSeesNothing) {
    // The rectangle faces +z (counter-clockwise about +z): a point below sees its back.
    const DVec3 rect[4] = {DVec3(0, 0, 1), DVec3(1, 0, 1), DVec3(1, 1, 1), DVec3(0, 1, 1)};
    EXPECT_EQ(point_to_polygon_form_factor(DVec3(0.5, 0.5, 0), DVec3(0, 0, 1), rect, 4), 0.0);
    // A point looking away from it (normal -z) sees nothing even from the front.
    EXPECT_EQ(point_to_polygon_form_factor(DVec3(0.5, 0.5, 2), DVec3(0, 0, 1), rect, 4), 0.0);
}

TEST(FormFactorTest, ParallelRectanglesMatchHowellC11Within0p5Percent) {
    for (const auto& [a, b, c] :
         {std::array<double, 3>{1, 1, 1}, {1, 2, 0.5}, {0.556, 0.556, 0.548}, {2, 1, 3}}) {
        const FormFactorPatch bottom = horizontal(a, b, 0.0, true);
        const FormFactorPatch top = horizontal(a, b, c, false);
        const double expected = howell_c11(a, b, c);
        const double f = form_factor(bottom, top, 32);
        EXPECT_NEAR(f, expected, 0.005 * expected) << a << " x " << b << " at " << c;
        // Reciprocity with equal areas: the same factor from the other side.
        EXPECT_NEAR(form_factor(top, bottom, 32), expected, 0.005 * expected);
    }
}

TEST(FormFactorTest, PerpendicularRectanglesMatchHowellC14Within0p5Percent) {
    for (const auto& [w, h, l] :
         {std::array<double, 3>{1, 1, 1}, {0.5, 2, 1}, {2, 0.5, 1}, {1, 1, 3}}) {
        // Surface 1: z = 0, x in [0, l], y in [0, w], facing +z. Surface 2: y = 0, x in [0, l],
        // z in [0, h], facing +y. They share the edge x in [0, l].
        const Vec3 s1[4] = {Vec3(0, 0, 0), Vec3(l, 0, 0), Vec3(l, w, 0), Vec3(0, w, 0)};
        const Vec3 s2[4] = {Vec3(0, 0, 0), Vec3(0, 0, h), Vec3(l, 0, h), Vec3(l, 0, 0)};
        const FormFactorPatch p1 = make_form_factor_patch(s1, 4);
        const FormFactorPatch p2 = make_form_factor_patch(s2, 4);
        const double f12 = howell_c14(w, h, l);
        EXPECT_NEAR(form_factor(p1, p2, 32), f12, 0.005 * f12) << w << " " << h << " " << l;
        // Reciprocity: A1 F12 = A2 F21.
        const double f21 = f12 * (w * l) / (h * l);
        EXPECT_NEAR(form_factor(p2, p1, 32), f21, 0.005 * f21);
    }
}

TEST(FormFactorTest, VisibilityScalesTheFactor) {
    const FormFactorPatch bottom = horizontal(1, 1, 0.0, true);
    const FormFactorPatch top = horizontal(1, 1, 1.0, false);
    const auto blocked = [](const DVec3&, const DVec3&) { return false; };
    EXPECT_EQ(form_factor(bottom, top, 8, blocked), 0.0);
    // A blocker over the half x < 0.5 of the receiver's points: the rays from points of the
    // emitter with x < 0.5 are blocked; the factor is the part from the other half.
    const auto half = [](const DVec3& x, const DVec3&) { return x.x >= 0.5; };
    const Vec3 right[4] = {Vec3(0.5, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0.5, 1, 0)};
    const double expected = 0.5 * form_factor(make_form_factor_patch(right, 4), top, 32);
    EXPECT_NEAR(form_factor(bottom, top, 32, half), expected, 1e-3 * expected);
}

}  // namespace
}  // namespace kasumi
