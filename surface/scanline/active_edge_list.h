#pragma once
/// The edge table and active edge list of a scanline renderer of polygons (Bouknight & Kelley
/// 1970; Foley, van Dam, Feiner & Hughes, "Computer Graphics", 2nd ed., §3.6): every
/// non-horizontal edge of the projected polygons goes into an edge table sorted by its first
/// scanline; the active edge list holds the edges that cross the current scanline, each with
/// its x at the scanline's centre, advanced by dx/dy from one scanline to the next; a polygon's
/// span on a scanline is [min x, max x] over its active edges (two for a convex polygon, three
/// or four on a scanline through a vertex: the same x twice).
///
/// Coordinates are pixels from the top left corner of the image, y down; scanline `row` is the
/// line y = row + 0.5 through its pixel centres. An edge from (x_a, y_a) to (x_b, y_b), y_a < y_b,
/// crosses the scanlines whose centre lies in [y_a, y_b] (closed: a scanline through a vertex
/// meets both edges there). Horizontal edges are left out: their ends are the ends of the
/// neighbouring edges, so spans are unchanged, except for a polygon of zero height (seen edge
/// on), which has no span and covers no pixel centre.
#include "surface/shadows/convex_polygon.h"

#include <cstdint>
#include <vector>

namespace kasumi {

/// One polygon's extent on one scanline, in pixels (x at the scanline's centre).
struct PolygonSpan {
    uint32_t polygon = 0;
    double x_lo = 0.0, x_hi = 0.0;
};

/// The edge table: the polygons' non-horizontal edges sorted by (first scanline, the polygon's
/// rank in the polygon table, edge order).
class EdgeTable {
  public:
    /// `polygons[i]`: polygon i's vertices in pixels, in order; `rank[i]`: its place in the
    /// polygon table (spans come out in rank order); scanlines 0 .. height − 1.
    EdgeTable(const std::vector<std::vector<DVec2>>& polygons, const std::vector<uint32_t>& rank,
              int height);

    size_t size() const { return m_edges.size(); }

  private:
    friend class ActiveEdgeList;
    struct Edge {
        uint32_t polygon = 0, rank = 0;
        int first_row = 0, last_row = -1;
        double x_top = 0.0, y_top = 0.0;  ///< the upper end (smaller y)
        double dx_dy = 0.0;               ///< x step per scanline
        /// x where the edge crosses scanline `row` (evaluated directly, not stepped).
        double x_at(int row) const { return x_top + ((row + 0.5) - y_top) * dx_dy; }
    };
    std::vector<Edge> m_edges;
};

/// The edges crossing one scanline, moved down one scanline at a time. A list started at row r
/// and stepped to row s holds the same x as any other list started at r and stepped to s: bands
/// of rows that start at fixed rows give the same spans for any number of threads.
class ActiveEdgeList {
  public:
    /// The list at scanline `row`: the edges crossing it, x evaluated there.
    ActiveEdgeList(const EdgeTable& table, int row);

    /// Moves to the next scanline: drops the edges that ended, advances x by dx/dy, and merges
    /// in the edges of the table that start there (x evaluated directly).
    void next_row();

    int row() const { return m_row; }
    /// The spans of the polygons crossing the current scanline, in polygon table order.
    void spans(std::vector<PolygonSpan>& out) const;

  private:
    struct Active {
        uint32_t edge = 0;
        double x = 0.0;
    };
    /// Active-list order: the polygon's rank, then the edge's place in the table.
    bool before(const Active& a, const Active& b) const;

    const EdgeTable& m_table;
    int m_row = 0;
    size_t m_next = 0;  ///< the first table edge not yet entered
    std::vector<Active> m_active, m_entering, m_merged;
};

}  // namespace kasumi
