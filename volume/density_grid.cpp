#include "volume/density_grid.h"

#include "core/error.h"

#include <algorithm>
#include <limits>

namespace kasumi {

DensityGrid::DensityGrid(IVec3 index_min, IVec3 index_max) {
    KASUMI_CHECK(index_min.x <= index_max.x && index_min.y <= index_max.y &&
                 index_min.z <= index_max.z);
    // Cells whose lower corner lies in [index_min - 1, index_max] touch a stored voxel.
    m_origin = index_min - IVec3(1);
    const IVec3 cells = index_max - index_min + IVec3(2);
    m_bricks = (cells + IVec3(kBrick - 1)) / kBrick;
    m_origin_f = Vec3(m_origin);
    m_cells_f = Vec3(m_bricks * kBrick);
    const size_t slots = static_cast<size_t>(m_bricks.x) * m_bricks.y * m_bricks.z;
    m_brick_index.assign(slots, -1);
    m_brick_max.assign(slots, 0.0f);
    m_brick_min.assign(slots, 0.0f);
}

float* DensityGrid::brick_voxels(IVec3 b) {
    int32_t& index = m_brick_index[brick_slot(b)];
    if (index < 0) {
        index = static_cast<int32_t>(m_allocated++);
        m_voxels.resize(m_allocated * kBrickVoxels, 0.0f);
    }
    return &m_voxels[static_cast<size_t>(index) * kBrickVoxels];
}

void DensityGrid::set(IVec3 index, float value) {
    if (value == 0.0f)
        return;
    const IVec3 local = index - m_origin;
    KASUMI_CHECK(local.x >= 1 && local.y >= 1 && local.z >= 1 && local.x < m_bricks.x * kBrick &&
                 local.y < m_bricks.y * kBrick && local.z < m_bricks.z * kBrick);
    // A voxel on a brick's lower face is also the apron (position kBrick) of the brick below.
    IVec3 first = local >> 3, count(1);
    for (int a = 0; a < 3; ++a) {
        if ((local[a] & (kBrick - 1)) == 0) {
            first[a] -= 1;
            count[a] = 2;
        }
    }
    for (int dz = 0; dz < count.z; ++dz)
        for (int dy = 0; dy < count.y; ++dy)
            for (int dx = 0; dx < count.x; ++dx) {
                const IVec3 b = first + IVec3(dx, dy, dz);
                const IVec3 l = local - b * kBrick;
                brick_voxels(b)[l.x + kStored * (l.y + kStored * l.z)] = value;
            }
}

void DensityGrid::finalize() {
    m_max_density = 0.0f;
    for (size_t slot = 0; slot < m_brick_index.size(); ++slot) {
        if (m_brick_index[slot] < 0)
            continue;
        const float* v = &m_voxels[static_cast<size_t>(m_brick_index[slot]) * kBrickVoxels];
        // Trilinear interpolation is a convex combination of the 8 corners, so the extremes of
        // the stored 9³ voxels bound the density everywhere inside the brick exactly.
        const auto [lo, hi] = std::minmax_element(v, v + kBrickVoxels);
        m_brick_min[slot] = *lo;
        m_brick_max[slot] = *hi;
        m_max_density = std::max(m_max_density, *hi);
    }
}

void DensityGrid::bricks_along(const Vec3& o_index, const Vec3& d_index, float t0, float t1,
                               std::vector<BrickSpan>& out) const {
    if (m_allocated == 0 || !(t1 > t0))
        return;
    // Brick space: brick b covers [b, b + 1) per axis.
    const Vec3 p = (o_index - m_origin_f) * (1.0f / kBrick);
    const Vec3 d = d_index * (1.0f / kBrick);
    const Vec3 n(m_bricks);
    float ta = t0, tb = t1;
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0.0f) {
            if (!(p[a] >= 0.0f && p[a] < n[a]))
                return;
            continue;
        }
        const float inv = 1.0f / d[a];
        float near = (0.0f - p[a]) * inv, far = (n[a] - p[a]) * inv;
        if (near > far)
            std::swap(near, far);
        ta = std::max(ta, near);
        tb = std::min(tb, far);
    }
    if (!(tb > ta))
        return;
    // The brick holding the midpoint of the first step decides the start cell robustly when
    // the entry point lies on a face.
    const Vec3 start = p + d * ta;
    IVec3 cell = glm::clamp(IVec3(glm::floor(start)), IVec3(0), m_bricks - IVec3(1));
    IVec3 step(0);
    Vec3 t_next(std::numeric_limits<float>::infinity()), t_delta(0.0f);
    for (int a = 0; a < 3; ++a) {
        if (d[a] > 0.0f) {
            step[a] = 1;
            t_next[a] = (static_cast<float>(cell[a] + 1) - p[a]) / d[a];
            t_delta[a] = 1.0f / d[a];
        } else if (d[a] < 0.0f) {
            step[a] = -1;
            t_next[a] = (static_cast<float>(cell[a]) - p[a]) / d[a];
            t_delta[a] = -1.0f / d[a];
        }
    }
    float t = ta;
    while (t < tb) {
        const int axis =
            t_next.x <= t_next.y ? (t_next.x <= t_next.z ? 0 : 2) : (t_next.y <= t_next.z ? 1 : 2);
        const float t_exit = std::min(t_next[axis], tb);
        const size_t slot = brick_slot(cell);
        if (m_brick_index[slot] >= 0 && t_exit > t) {
            if (!out.empty() && out.back().t1 == t && out.back().density_max == m_brick_max[slot] &&
                out.back().density_min == m_brick_min[slot]) {
                out.back().t1 = t_exit;  // merge equal neighbours: fewer spans to walk
            } else {
                out.push_back({t, t_exit, m_brick_max[slot], m_brick_min[slot]});
            }
        }
        t = std::max(t, t_exit);
        cell[axis] += step[axis];
        if (cell[axis] < 0 || cell[axis] >= m_bricks[axis])
            break;
        t_next[axis] += t_delta[axis];
    }
}

}  // namespace kasumi
