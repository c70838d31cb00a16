// The active edge list of the scanline renderer (surface/scanline/active_edge_list.h): on every
// scanline it gives each polygon the pixel centres that the direct crossing of all its edges
// with the scanline gives (the per-scanline edge crossing it replaced), in polygon table order,
// whichever row a band of rows starts it at. Not bit for bit: x stepped by dx/dy rounds
// differently from x evaluated on the scanline (~1e-13 pixel here), so a span end whose edge
// passes within kTie of a pixel centre may take or leave that centre (either is right: the
// centre is on the edge); those ends are counted and left out, all others must agree.
#include "core/rng.h"
#include "surface/scanline/active_edge_list.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>

namespace kasumi {
namespace {

constexpr int kHeight = 120;

/// Pixels: a span end this close to a pixel centre is a tie (the centre lies on the edge).
constexpr double kTie = 1e-9;

bool near_centre(double x) {
    return std::abs(x - 0.5 - std::round(x - 0.5)) < kTie;
}

/// The x extent of a convex polygon on the line y, every edge crossed directly (closed at
/// the ends; horizontal edges add their ends); empty when the line misses it.
std::optional<std::pair<double, double>> direct_extent(const std::vector<DVec2>& polygon,
                                                       double y) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (size_t i = 0; i < polygon.size(); ++i) {
        const DVec2& a = polygon[i];
        const DVec2& b = polygon[(i + 1) % polygon.size()];
        if (!((a.y <= y && b.y >= y) || (b.y <= y && a.y >= y)))
            continue;
        const double x = a.y == b.y ? a.x : a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x);
        lo = std::min({lo, x, a.y == b.y ? b.x : x});
        hi = std::max({hi, x, a.y == b.y ? b.x : x});
    }
    if (!(lo <= hi))
        return std::nullopt;
    return std::make_pair(lo, hi);
}

/// Pixel columns whose centre lies in [lo, hi] (x0 > x1: none).
std::pair<int, int> columns(double lo, double hi) {
    return {static_cast<int>(std::ceil(lo - 0.5)), static_cast<int>(std::floor(hi - 0.5))};
}

struct Polygons {
    std::vector<std::vector<DVec2>> screen;
    std::vector<uint32_t> rank;
};

/// Random triangles over and beyond the image, some with vertices on pixel centres and on
/// scanlines (ties), ranked in reverse order of creation.
Polygons random_triangles(int count) {
    Pcg32 rng(7, 3);
    Polygons p;
    for (int i = 0; i < count; ++i) {
        std::vector<DVec2> t;
        for (int k = 0; k < 3; ++k) {
            DVec2 v(rng.next_float() * 260.0 - 30.0, rng.next_float() * 160.0 - 20.0);
            if (i % 4 == 0)
                v = glm::floor(v) + 0.5;  // on a pixel centre and a scanline
            t.push_back(v);
        }
        p.screen.push_back(t);
        p.rank.push_back(static_cast<uint32_t>(count - 1 - i));
    }
    return p;
}

TEST(ActiveEdgeListTest, SpansEqualTheDirectEdgeCrossingAtEveryPixelCentre) {
    const Polygons p = random_triangles(400);
    const EdgeTable table(p.screen, p.rank, kHeight);
    ActiveEdgeList active(table, 0);
    std::vector<PolygonSpan> spans;
    int nonempty = 0, ties = 0;
    for (int row = 0; row < kHeight; ++row) {
        if (row > 0)
            active.next_row();
        active.spans(spans);
        // In table order, one span per polygon met.
        for (size_t i = 1; i < spans.size(); ++i)
            EXPECT_LT(p.rank[spans[i - 1].polygon], p.rank[spans[i].polygon]);
        std::vector<std::optional<std::pair<int, int>>> from_list(p.screen.size());
        for (const PolygonSpan& s : spans)
            from_list[s.polygon] = columns(s.x_lo, s.x_hi);
        for (uint32_t f = 0; f < p.screen.size(); ++f) {
            const auto extent = direct_extent(p.screen[f], row + 0.5);
            if (!extent) {
                EXPECT_FALSE(from_list[f]) << "row " << row << " polygon " << f;
                continue;
            }
            const auto direct = columns(extent->first, extent->second);
            ASSERT_TRUE(from_list[f]) << "row " << row << " polygon " << f;
            if (near_centre(extent->first))
                ++ties;
            else
                EXPECT_EQ(from_list[f]->first, direct.first) << "row " << row << " polygon " << f;
            if (near_centre(extent->second))
                ++ties;
            else
                EXPECT_EQ(from_list[f]->second, direct.second) << "row " << row << " polygon " << f;
            nonempty += direct.first <= direct.second ? 1 : 0;
        }
    }
    EXPECT_GT(nonempty, 5000);
    // The polygons with vertices on pixel centres give ties; they stay a small part.
    EXPECT_GT(ties, 0);
    EXPECT_LT(ties, nonempty / 10);
}

TEST(ActiveEdgeListTest, ABandStartedAtAnyRowGivesTheSameSpans) {
    const Polygons p = random_triangles(200);
    const EdgeTable table(p.screen, p.rank, kHeight);
    for (const int start : {8, 37, 64}) {
        ActiveEdgeList from_top(table, 0), from_band(table, start);
        for (int row = 1; row <= start; ++row)
            from_top.next_row();
        for (int row = start; row < std::min(kHeight, start + 8); ++row) {
            if (row > start) {
                from_top.next_row();
                from_band.next_row();
            }
            std::vector<PolygonSpan> a, b;
            from_top.spans(a);
            from_band.spans(b);
            ASSERT_EQ(a.size(), b.size()) << row;
            for (size_t i = 0; i < a.size(); ++i) {
                EXPECT_EQ(a[i].polygon, b[i].polygon);
                EXPECT_NEAR(a[i].x_lo, b[i].x_lo, 1e-9) << row;
                EXPECT_NEAR(a[i].x_hi, b[i].x_hi, 1e-9) << row;
                if (!near_centre(a[i].x_lo)) {
                    EXPECT_EQ(columns(a[i].x_lo, 0).first, columns(b[i].x_lo, 0).first) << row;
                }
                if (!near_centre(a[i].x_hi)) {
                    EXPECT_EQ(columns(0, a[i].x_hi).second, columns(0, b[i].x_hi).second) << row;
                }
            }
        }
    }
}

}  // namespace
}  // namespace kasumi
