#include "surface/shadows/polygon_grid.h"

#include <algorithm>
#include <cmath>

namespace kasumi {

namespace {

struct Rect {
    DVec2 min, max;
};

Rect bounds(const PolygonRegion& polygon) {
    Rect r{polygon.rings.front().front(), polygon.rings.front().front()};
    for (const Ring& ring : polygon.rings)
        for (const DVec2& v : ring) {
            r.min = glm::min(r.min, v);
            r.max = glm::max(r.max, v);
        }
    return r;
}

}  // namespace

PolygonGrid::PolygonGrid(const std::vector<PolygonRegion>& polygons) : m_polygons(&polygons) {
    if (polygons.empty())
        return;
    std::vector<Rect> rects;
    Rect all = bounds(polygons.front());
    for (const PolygonRegion& p : polygons) {
        rects.push_back(bounds(p));
        all.min = glm::min(all.min, rects.back().min);
        all.max = glm::max(all.max, rects.back().max);
    }
    const int side =
        std::clamp(static_cast<int>(std::ceil(std::sqrt(double(polygons.size())))), 1, 64);
    m_nu = m_nv = side;
    m_min = all.min;
    // A little wider than the bounds, so that the maximum maps into the last cell.
    m_cell = glm::max((all.max - all.min) * (1.0 + 1e-9) / double(side), DVec2(1e-300));
    const auto cell_range = [&](const Rect& r, int& u0, int& u1, int& v0, int& v1) {
        u0 = std::clamp(static_cast<int>((r.min.x - m_min.x) / m_cell.x), 0, m_nu - 1);
        u1 = std::clamp(static_cast<int>((r.max.x - m_min.x) / m_cell.x), 0, m_nu - 1);
        v0 = std::clamp(static_cast<int>((r.min.y - m_min.y) / m_cell.y), 0, m_nv - 1);
        v1 = std::clamp(static_cast<int>((r.max.y - m_min.y) / m_cell.y), 0, m_nv - 1);
    };
    std::vector<uint32_t> count(size_t(m_nu) * m_nv + 1, 0);
    for (const Rect& r : rects) {
        int u0, u1, v0, v1;
        cell_range(r, u0, u1, v0, v1);
        for (int v = v0; v <= v1; ++v)
            for (int u = u0; u <= u1; ++u)
                ++count[size_t(v) * m_nu + u];
    }
    m_first.assign(count.size(), 0);
    for (size_t c = 0; c + 1 < count.size(); ++c)
        m_first[c + 1] = m_first[c] + count[c];
    m_items.resize(m_first.back());
    std::vector<uint32_t> fill(m_first.begin(), m_first.end() - 1);
    for (size_t i = 0; i < rects.size(); ++i) {
        int u0, u1, v0, v1;
        cell_range(rects[i], u0, u1, v0, v1);
        for (int v = v0; v <= v1; ++v)
            for (int u = u0; u <= u1; ++u)
                m_items[fill[size_t(v) * m_nu + u]++] = static_cast<uint32_t>(i);
    }
}

bool PolygonGrid::contains(const DVec2& p) const {
    if (m_nu == 0)
        return false;
    const double fu = (p.x - m_min.x) / m_cell.x, fv = (p.y - m_min.y) / m_cell.y;
    if (!(fu >= 0.0 && fv >= 0.0 && fu < m_nu && fv < m_nv))
        return false;
    const size_t c = size_t(fv) * m_nu + size_t(fu);
    for (uint32_t k = m_first[c]; k < m_first[c + 1]; ++k)
        if (kasumi::contains((*m_polygons)[m_items[k]], p))
            return true;
    return false;
}

}  // namespace kasumi
