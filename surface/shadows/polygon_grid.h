#pragma once
/// Point location among a face's detail polygons: a uniform grid over the face's bounding
/// rectangle whose cells list the polygons overlapping them (by bounding rectangle), so that a
/// query tests the few polygons of one cell instead of all of them. The polygons may be concave
/// and have holes (surface/shadows/polygon_region.h).
#include "surface/shadows/polygon_region.h"

#include <cstdint>
#include <vector>

namespace kasumi {

class PolygonGrid {
  public:
    PolygonGrid() = default;
    /// About one polygon per cell, at most 64 × 64 cells. `polygons` must outlive the grid.
    explicit PolygonGrid(const std::vector<PolygonRegion>& polygons);

    /// True when p (metres, the polygons' frame) lies in one of the polygons (nonzero winding; a
    /// point on an edge takes either side's answer).
    bool contains(const DVec2& p) const;

  private:
    const std::vector<PolygonRegion>* m_polygons = nullptr;
    DVec2 m_min{0.0}, m_cell{1.0};
    int m_nu = 0, m_nv = 0;
    std::vector<uint32_t> m_first;  ///< cell c lists m_items[m_first[c], m_first[c + 1])
    std::vector<uint32_t> m_items;
};

}  // namespace kasumi
