// Weiler–Atherton clipping of concave polygons with holes (surface/shadows/weiler_atherton.h):
// closed-form areas of the inside and outside results, inside ∪ outside = subject with no
// cracks (areas within 1e-9 relative, point sampling), holes in either operand, the hard cases
// (coincident edges both ways, vertices on edges, touching vertices, slivers thinner and
// thicker than epsilon), random concave polygons against point sampling, and random convex
// ones against the convex split of the first object-space clipper.
#include "surface/shadows/weiler_atherton.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <algorithm>

#include <cmath>
#include <random>

namespace kasumi {
namespace {

constexpr double kEpsilon = 1e-9;

PolygonRegion rect(double x0, double y0, double x1, double y1) {
    return {{{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}}};
}

/// The clockwise ring of a rectangle: a hole.
Ring hole(double x0, double y0, double x1, double y1) {
    return {{x0, y0}, {x0, y1}, {x1, y1}, {x1, y0}};
}

const PolygonRegion kL{{{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}}};

/// Inside and outside areas sum to the subject's within 1e-9 relative.
void expect_sums(const RegionClip& c, const PolygonRegion& subject) {
    EXPECT_NEAR(area(c.inside) + area(c.outside), area(subject), 1e-9 * area(subject));
}

TEST(WeilerAthertonTest, ConcaveSubjectAgainstASquare) {
    const RegionClip c = weiler_atherton(kL, rect(0.5, 0.5, 1.5, 1.5), kEpsilon);
    // The square minus its quarter [1, 1.5]² outside the L.
    EXPECT_NEAR(area(c.inside), 0.75, 1e-15);
    EXPECT_NEAR(area(c.outside), 2.25, 1e-15);
    EXPECT_EQ(polygons_with_holes(c.inside).size(), 1u);  // one concave hexagon
    EXPECT_EQ(polygons_with_holes(c.outside).size(), 1u);
    EXPECT_EQ(c.intersections, 2u);
    EXPECT_TRUE(contains(c.inside, {0.75, 0.75}));
    EXPECT_FALSE(contains(c.inside, {1.25, 1.25}));
    EXPECT_TRUE(contains(c.outside, {1.75, 0.5}));
}

TEST(WeilerAthertonTest, SubjectWithAHole) {
    PolygonRegion subject = rect(0, 0, 4, 4);
    subject.rings.push_back(hole(1, 1, 3, 3));
    ASSERT_DOUBLE_EQ(area(subject), 12.0);
    // The right half: a C shape each side.
    const RegionClip c = weiler_atherton(subject, rect(2, -1, 5, 5), kEpsilon);
    EXPECT_NEAR(area(c.inside), 6.0, 1e-14);
    EXPECT_NEAR(area(c.outside), 6.0, 1e-14);
    EXPECT_EQ(polygons_with_holes(c.inside).size(), 1u);
    EXPECT_EQ(polygons_with_holes(c.outside).size(), 1u);
    EXPECT_FALSE(contains(c.inside, {2.5, 2.0}));  // the hole stays empty
    EXPECT_TRUE(contains(c.inside, {3.5, 2.0}));
}

TEST(WeilerAthertonTest, ClipInsideTheSubjectLeavesAHole) {
    const RegionClip c = weiler_atherton(rect(0, 0, 4, 4), rect(1, 1, 3, 3), kEpsilon);
    EXPECT_EQ(c.intersections, 0u);
    EXPECT_NEAR(area(c.inside), 4.0, 1e-15);
    EXPECT_NEAR(area(c.outside), 12.0, 1e-15);
    const std::vector<PolygonRegion> out = polygons_with_holes(c.outside);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].rings.size(), 2u);  // the outer ring and its hole
    EXPECT_FALSE(contains(c.outside, {2, 2}));
}

TEST(WeilerAthertonTest, ClipWithAHole) {
    PolygonRegion annulus = rect(-1, -1, 5, 5);
    annulus.rings.push_back(hole(1, 1, 3, 3));
    const RegionClip c = weiler_atherton(rect(0, 0, 4, 4), annulus, kEpsilon);
    EXPECT_NEAR(area(c.inside), 12.0, 1e-14);
    EXPECT_NEAR(area(c.outside), 4.0, 1e-14);
    const std::vector<PolygonRegion> in = polygons_with_holes(c.inside);
    ASSERT_EQ(in.size(), 1u);
    EXPECT_EQ(in[0].rings.size(), 2u);
}

TEST(WeilerAthertonTest, CoincidentEdges) {
    const PolygonRegion subject = rect(0, 0, 2, 2);
    // Same direction along the left edge, partly along the top and bottom.
    const RegionClip same = weiler_atherton(subject, rect(0, 0, 1, 2), kEpsilon);
    EXPECT_NEAR(area(same.inside), 2.0, 1e-15);
    EXPECT_NEAR(area(same.outside), 2.0, 1e-15);
    EXPECT_EQ(polygons_with_holes(same.inside).size(), 1u);
    EXPECT_EQ(same.outside.rings.size(), 1u);
    // Opposite direction: touching along x = 2 only, and overlapping part of that edge.
    for (const PolygonRegion& clip : {rect(2, 0, 3, 2), rect(2, 0.5, 3, 1.5), rect(2, -1, 3, 3)}) {
        const RegionClip opposite = weiler_atherton(subject, clip, kEpsilon);
        EXPECT_NEAR(area(opposite.inside), 0.0, 1e-15);
        EXPECT_NEAR(area(opposite.outside), 4.0, 1e-15);
    }
    // The clip equal to the subject: all inside.
    const RegionClip equal = weiler_atherton(subject, subject, kEpsilon);
    EXPECT_NEAR(area(equal.inside), 4.0, 1e-15);
    EXPECT_TRUE(equal.outside.rings.empty());
}

TEST(WeilerAthertonTest, VerticesOnEdgesAndTouchingVertices) {
    const PolygonRegion subject = rect(0, 0, 2, 2);
    // T-junctions: two clip vertices on the subject's bottom and top edges.
    const PolygonRegion triangle{{{{1, 0}, {3, 1}, {1, 2}}}};
    const RegionClip t = weiler_atherton(subject, triangle, kEpsilon);
    EXPECT_NEAR(area(t.inside), 1.5, 1e-15);  // the trapezoid of the triangle over x ∈ [1, 2]
    EXPECT_NEAR(area(t.outside), 2.5, 1e-15);
    expect_sums(t, subject);
    // A subject vertex on a clip edge: the square's corner (2, 2) on the diagonal x + y = 4.
    const PolygonRegion wedge{{{{4, 0}, {4, 4}, {0, 4}}}};
    const RegionClip w = weiler_atherton(subject, wedge, kEpsilon);
    EXPECT_NEAR(area(w.inside), 0.0, 1e-15);
    EXPECT_NEAR(area(w.outside), 4.0, 1e-15);
    // Corners touching.
    const RegionClip corner = weiler_atherton(subject, rect(2, 2, 3, 3), kEpsilon);
    EXPECT_NEAR(area(corner.inside), 0.0, 1e-15);
    EXPECT_NEAR(area(corner.outside), 4.0, 1e-15);
    // A clip vertex within epsilon of a subject vertex is that vertex.
    const RegionClip near = weiler_atherton(subject, rect(1, 1, 2 + 1e-12, 2 - 1e-12), kEpsilon);
    EXPECT_NEAR(area(near.inside), 1.0, 1e-11);
    expect_sums(near, subject);
}

TEST(WeilerAthertonTest, Slivers) {
    const PolygonRegion subject = rect(0, 0, 2, 2);
    // Thinner than epsilon: collapses onto the edge; the results still sum to the subject.
    const RegionClip thin = weiler_atherton(subject, rect(0.5, -1, 1.5, 1e-12), kEpsilon);
    EXPECT_LT(area(thin.inside), 2e-12);
    expect_sums(thin, subject);
    // Thicker than epsilon: kept, with its exact area.
    const RegionClip kept = weiler_atherton(subject, rect(0.5, -1, 1.5, 1e-7), kEpsilon);
    EXPECT_NEAR(area(kept.inside), 1e-7, 1e-15);
    expect_sums(kept, subject);
    // A needle crossing the whole square at a shallow angle.
    const PolygonRegion needle{{{{-1, 1}, {3, 1 + 1e-6}, {3, 1 + 2e-6}}}};
    const RegionClip n = weiler_atherton(subject, needle, kEpsilon);
    expect_sums(n, subject);
    EXPECT_GT(area(n.inside), 0.0);
    EXPECT_LT(area(n.inside), area(needle));
}

// A concave polygon given as its triangles (coincident edges between them, opposite
// directions) unites into one polygon: what the object-space pass does with a mesh's shadow.
TEST(WeilerAthertonTest, TrianglesUniteIntoOneConcavePolygon) {
    const std::vector<Ring> fan = {{{0, 0}, {2, 0}, {2, 1}},
                                   {{0, 0}, {2, 1}, {1, 1}},
                                   {{0, 0}, {1, 1}, {1, 2}},
                                   {{0, 0}, {1, 2}, {0, 2}}};
    PolygonRegion united;
    for (const Ring& t : fan)
        united = unite(united, PolygonRegion{{t}}, kEpsilon);
    EXPECT_EQ(united.rings.size(), 1u);
    EXPECT_NEAR(area(united), 3.0, 1e-15);
    const RegionClip c = weiler_atherton(rect(-1, -1, 3, 3), united, kEpsilon);
    EXPECT_EQ(polygons_with_holes(c.inside).size(), 1u);
    EXPECT_NEAR(area(c.inside), 3.0, 1e-15);
    EXPECT_NEAR(area(c.outside), 13.0, 1e-14);
}

/// A random star-shaped (generally concave) counter-clockwise polygon around `centre`.
Ring random_star(std::mt19937& rng, const DVec2& centre, int n) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    Ring ring;
    for (int i = 0; i < n; ++i) {
        const double angle = 2.0 * M_PI * (i + 0.8 * u(rng)) / n;
        const double radius = 0.3 + 0.7 * u(rng);
        ring.push_back(centre + radius * DVec2(std::cos(angle), std::sin(angle)));
    }
    return ring;
}

/// A random convex counter-clockwise polygon: points on an ellipse at sorted angles.
Ring random_convex(std::mt19937& rng, const DVec2& centre, int n) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const double a = 0.4 + 0.6 * u(rng), b = 0.4 + 0.6 * u(rng);
    std::vector<double> angles(n);
    for (double& t : angles)
        t = 2.0 * M_PI * u(rng);
    std::sort(angles.begin(), angles.end());
    Ring ring;
    for (double t : angles)
        ring.push_back(centre + DVec2(a * std::cos(t), b * std::sin(t)));
    return ring;
}

/// Point samples of the box [-1.5, 1.5]² farther than 1e-7 from both operands' edges: the
/// results hold exactly the points of subject ∩ clip, subject \ clip and subject ∪ clip.
void expect_by_sampling(const PolygonRegion& s, const PolygonRegion& c, const RegionClip& r,
                        const PolygonRegion& united, std::mt19937& rng) {
    std::uniform_real_distribution<double> u(-1.5, 1.5);
    int tested = 0;
    for (int k = 0; k < 2000; ++k) {
        const DVec2 p(u(rng), u(rng));
        if (distance_to_boundary(s, p) < 1e-7 || distance_to_boundary(c, p) < 1e-7)
            continue;
        ++tested;
        const bool in_s = contains(s, p), in_c = contains(c, p);
        ASSERT_EQ(contains(r.inside, p), in_s && in_c) << "(" << p.x << ", " << p.y << ")";
        ASSERT_EQ(contains(r.outside, p), in_s && !in_c) << "(" << p.x << ", " << p.y << ")";
        ASSERT_EQ(contains(united, p), in_s || in_c) << "(" << p.x << ", " << p.y << ")";
    }
    EXPECT_GT(tested, 1900);
}

TEST(WeilerAthertonTest, RandomConcavePolygonsMatchPointSampling) {
    std::mt19937 rng(20261204);
    std::uniform_real_distribution<double> offset(-0.6, 0.6);
    for (int trial = 0; trial < 200; ++trial) {
        PolygonRegion s{{random_star(rng, DVec2(0.0), 5 + trial % 17)}};
        const PolygonRegion c{{random_star(rng, DVec2(offset(rng), offset(rng)), 4 + trial % 13)}};
        if (trial % 3 == 0) {  // a hole in the subject: a small clockwise star
            Ring h = random_star(rng, DVec2(0.0), 6);
            for (DVec2& p : h)
                p *= 0.25;
            std::reverse(h.begin(), h.end());
            s.rings.push_back(h);
        }
        const RegionClip r = weiler_atherton(s, c, kEpsilon);
        expect_sums(r, s);
        const PolygonRegion united = unite(s, c, kEpsilon);
        EXPECT_NEAR(area(united), area(s) + area(c) - area(r.inside), 1e-9 * area(united));
        expect_by_sampling(s, c, r, united, rng);
        if (HasFatalFailure())
            return;
    }
}

// Convex operands: the convex split (each edge line of the clip in turn, keeping both sides;
// surface/shadows/convex_polygon.h) gives the same areas and the same points.
TEST(WeilerAthertonTest, RandomConvexPolygonsMatchTheConvexSplit) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> offset(-0.8, 0.8);
    for (int trial = 0; trial < 200; ++trial) {
        const Ring s = random_convex(rng, DVec2(0.0), 3 + trial % 10);
        const Ring c = random_convex(rng, DVec2(offset(rng), offset(rng)), 3 + trial % 7);
        const RegionClip r = weiler_atherton(PolygonRegion{{s}}, PolygonRegion{{c}}, kEpsilon);
        ConvexPolygon inside{s};
        std::vector<ConvexPolygon> outside;
        for (size_t i = 0; i < c.size() && !inside.vertices.empty(); ++i) {
            const DVec2 e = glm::normalize(c[(i + 1) % c.size()] - c[i]);
            const HalfPlane h{DVec2(-e.y, e.x), -(-e.y * c[i].x + e.x * c[i].y)};
            PolygonSplit split_i = split(inside, h, kEpsilon);
            if (!split_i.outside.vertices.empty())
                outside.push_back(split_i.outside);
            inside = split_i.inside;
        }
        double outside_area = 0.0;
        for (const ConvexPolygon& p : outside)
            outside_area += area(p);
        const double whole = signed_area(s);
        EXPECT_NEAR(area(r.inside), inside.vertices.empty() ? 0.0 : area(inside), 1e-9 * whole);
        EXPECT_NEAR(area(r.outside), outside_area, 1e-9 * whole);
        expect_sums(r, PolygonRegion{{s}});
        // At most one convex inside piece, and never more outside polygons than convex pieces.
        EXPECT_LE(polygons_with_holes(r.outside).size(), std::max<size_t>(outside.size(), 1));
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        for (int k = 0; k < 300; ++k) {
            const DVec2 p(u(rng), u(rng));
            const bool clear = !inside.vertices.empty() &&
                               distance_to_boundary(PolygonRegion{{inside.vertices}}, p) > 1e-7 &&
                               distance_to_boundary(PolygonRegion{{s}}, p) > 1e-7;
            if (clear) {
                EXPECT_EQ(contains(r.inside, p), contains(inside, p, 0.0));
            }
        }
    }
}

}  // namespace
}  // namespace kasumi
