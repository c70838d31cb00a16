#include "surface/scanline/active_edge_list.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace kasumi {

EdgeTable::EdgeTable(const std::vector<std::vector<DVec2>>& polygons,
                     const std::vector<uint32_t>& rank, int height) {
    for (uint32_t p = 0; p < polygons.size(); ++p) {
        const std::vector<DVec2>& polygon = polygons[p];
        for (size_t i = 0; i < polygon.size(); ++i) {
            DVec2 a = polygon[i], b = polygon[(i + 1) % polygon.size()];
            if (a.y == b.y)
                continue;
            if (b.y < a.y)
                std::swap(a, b);
            Edge e;
            e.polygon = p;
            e.rank = rank[p];
            e.first_row = std::max(0, static_cast<int>(std::ceil(a.y - 0.5)));
            e.last_row = std::min(height - 1, static_cast<int>(std::floor(b.y - 0.5)));
            if (e.first_row > e.last_row)
                continue;
            e.x_top = a.x;
            e.y_top = a.y;
            e.dx_dy = (b.x - a.x) / (b.y - a.y);
            m_edges.push_back(e);
        }
    }
    std::stable_sort(m_edges.begin(), m_edges.end(), [](const Edge& a, const Edge& b) {
        return a.first_row != b.first_row ? a.first_row < b.first_row : a.rank < b.rank;
    });
}

bool ActiveEdgeList::before(const Active& a, const Active& b) const {
    const uint32_t ra = m_table.m_edges[a.edge].rank, rb = m_table.m_edges[b.edge].rank;
    return ra != rb ? ra < rb : a.edge < b.edge;
}

ActiveEdgeList::ActiveEdgeList(const EdgeTable& table, int row) : m_table(table), m_row(row) {
    const auto& edges = table.m_edges;
    while (m_next < edges.size() && edges[m_next].first_row <= row) {
        if (edges[m_next].last_row >= row)
            m_active.push_back({static_cast<uint32_t>(m_next), edges[m_next].x_at(row)});
        ++m_next;
    }
    std::sort(m_active.begin(), m_active.end(),
              [&](const Active& a, const Active& b) { return before(a, b); });
}

void ActiveEdgeList::next_row() {
    ++m_row;
    const auto& edges = m_table.m_edges;
    m_active.erase(std::remove_if(m_active.begin(), m_active.end(),
                                  [&](const Active& a) { return edges[a.edge].last_row < m_row; }),
                   m_active.end());
    for (Active& a : m_active)
        a.x += edges[a.edge].dx_dy;
    // The table is sorted by first scanline, then rank: the entering edges are in list order.
    m_entering.clear();
    while (m_next < edges.size() && edges[m_next].first_row <= m_row) {
        m_entering.push_back({static_cast<uint32_t>(m_next), edges[m_next].x_at(m_row)});
        ++m_next;
    }
    if (m_entering.empty())
        return;
    m_merged.clear();
    std::merge(m_active.begin(), m_active.end(), m_entering.begin(), m_entering.end(),
               std::back_inserter(m_merged),
               [&](const Active& a, const Active& b) { return before(a, b); });
    m_active.swap(m_merged);
}

void ActiveEdgeList::spans(std::vector<PolygonSpan>& out) const {
    out.clear();
    const auto& edges = m_table.m_edges;
    for (const Active& a : m_active) {
        const uint32_t polygon = edges[a.edge].polygon;
        if (out.empty() || out.back().polygon != polygon)
            out.push_back({polygon, a.x, a.x});
        else {
            out.back().x_lo = std::min(out.back().x_lo, a.x);
            out.back().x_hi = std::max(out.back().x_hi, a.x);
        }
    }
}

}  // namespace kasumi
