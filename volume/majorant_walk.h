#pragma once
/// The trackers' walk over a ray's majorant segments, lazily: segments are produced in order as
/// the walk goes and nothing past the point where it stops (a real collision, a scattering
/// event, Russian roulette) is computed. For a set that is exactly one grid medium the segments
/// are the grid's bricks (volume/grid/density_grid.h, `DensityGrid::walk`) and each names its
/// brick, so a lookup skips the brick table; otherwise they are MediumSet::majorants (per brick,
/// overlapping media summed, listed for the whole ray).
#include "volume/medium_set.h"

#include <algorithm>
#include <vector>

namespace kasumi {

/// A brick span whose majorant optical depth exceeds this is walked cell by cell instead: the
/// trackers' tentative collisions number about the majorant depth, and one dense voxel made a
/// brick's whole span cost that many (density_scale 1e6 on a cloud never finished), also where
/// the ray crosses the brick's empty part. Ordinary clouds (depth per brick of order 1) never
/// reach it, so their walks and random numbers are unchanged.
constexpr float kDenseBrickDepth = 64.0f;

/// Calls visit(t0, t1, density_max, density_min) for the voxel cells of `brick` that the
/// index-space ray o + t d crosses within [t0, t1] (in order, 3D DDA), skipping cells whose eight
/// corner voxels are all 0 (no density anywhere inside). The bounds are the cell's corner
/// extremes, which bound trilinear interpolation inside the cell exactly; a rounding sliver left
/// past the last cell gets the brick's bounds. Returns false as soon as visit does.
template <class Visit>
bool walk_brick_cells(const BrickRef& brick, const Vec3& o, const Vec3& d, float t0, float t1,
                      float brick_max, float brick_min, Visit&& visit) {
    constexpr int n = DensityGrid::kBrick, stride = DensityGrid::kStored;
    const Vec3 p = o - brick.lower;  // brick-local index space: cell c covers [c, c + 1)
    // The cell holding t0, clamped: the span lies in the brick up to rounding.
    IVec3 cell = glm::clamp(IVec3(glm::floor(p + d * t0)), IVec3(0), IVec3(n - 1));
    IVec3 step(0);
    Vec3 t_next(kInfinity), t_delta(kInfinity);
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
    float t = t0;
    for (int guard = 0; guard < 3 * n + 3 && t < t1; ++guard) {
        const int axis =
            t_next.x <= t_next.y ? (t_next.x <= t_next.z ? 0 : 2) : (t_next.y <= t_next.z ? 1 : 2);
        const float t_exit = std::min(std::max(t_next[axis], t), t1);
        const float* v = brick.voxels + (cell.x + stride * (cell.y + stride * cell.z));
        float hi = v[0], lo = v[0];
        for (int k = 1; k < 8; ++k) {
            const float x = v[(k & 1) + stride * (((k >> 1) & 1) + stride * (k >> 2))];
            hi = std::max(hi, x);
            lo = std::min(lo, x);
        }
        if (hi > 0.0f && t_exit > t && !visit(t, t_exit, hi, lo))
            return false;
        t = t_exit;
        cell[axis] += step[axis];
        if (cell[axis] < 0 || cell[axis] >= n)
            break;
        t_next[axis] += t_delta[axis];
    }
    // Rounding can leave a sliver of the span past the last cell: the brick's bounds cover it.
    if (t < t1)
        return visit(t, t1, brick_max, brick_min);
    return true;
}

/// walk_majorants for a set that is the one grid medium `g`, whose index-space ray (o + t d, the
/// transform of `ray`) the caller has computed: the grid's bricks in order, a dense brick cell
/// by cell.
template <class Visit>
bool walk_grid_majorants(const MediumSet::FastMedium& g, const Ray& ray, const Vec3& o_index,
                         const Vec3& d_index, Visit&& visit) {
    if (g.grid->empty() || !(max_component(g.sigma_t) > 0.0f))
        return true;
    const auto span = g.bounds_world.clip(ray);
    if (!span)
        return true;
    const Rgb sigma_t = g.sigma_t;
    return g.grid->walk(
        o_index, d_index, span->first, span->second,
        [&](const BrickSpan& b, const BrickRef& brick) {
            const MajorantSegment s{b.t0, b.t1, sigma_t * b.density_max, sigma_t * b.density_min,
                                    1u};
            if (!(max_component(s.sigma_max) * (b.t1 - b.t0) > kDenseBrickDepth))
                return visit(s, &brick);
            return walk_brick_cells(
                brick, o_index, d_index, b.t0, b.t1, b.density_max, b.density_min,
                [&](float t0, float t1, float hi, float lo) {
                    return visit(MajorantSegment{t0, t1, sigma_t * hi, sigma_t * lo, 1u}, &brick);
                });
        });
}

/// The segments of a set other than a single grid (MediumSet::majorants, listed for the whole
/// ray first), in order, until visit returns false. Not re-entrant per Visit type (the segment
/// list is thread_local).
template <class Visit>
bool walk_listed_majorants(const MediumSet& media, const Ray& ray, Visit&& visit) {
    thread_local std::vector<MajorantSegment> segments;
    media.majorants(ray, segments);
    for (const MajorantSegment& s : segments) {
        if (!visit(s, static_cast<const BrickRef*>(nullptr)))
            return false;
    }
    return true;
}

/// Calls visit(const MajorantSegment& s, const BrickRef* brick) for each majorant segment of
/// [ray.t_min, ray.t_max] in order until visit returns false (then returns false). `brick` is
/// the grid brick holding s when the set is a single grid (RayMediaQuery::density_in reads it),
/// else null (use RayMediaQuery::coefficients with s.media_mask). Not re-entrant per Visit type
/// for sets other than a single grid (the segment list is thread_local).
template <class Visit>
bool walk_majorants(const MediumSet& media, const Ray& ray, Visit&& visit) {
    if (const MediumSet::FastMedium* g = media.single_grid()) {
        // The same expressions as RayMediaQuery's, so both see the same index-space ray.
        const Vec3 o_index(g->world_to_index * Vec4(ray.origin, 1.0f));
        const Vec3 d_index(g->world_to_index * Vec4(ray.direction, 0.0f));
        return walk_grid_majorants(*g, ray, o_index, d_index, visit);
    }
    return walk_listed_majorants(media, ray, visit);
}

/// walk_majorants along query.ray(), reusing the index-space ray the query has computed (the
/// same values: one transform per ray instead of two).
template <class Visit>
bool walk_majorants(const MediumSet& media, const RayMediaQuery& query, Visit&& visit) {
    if (const MediumSet::FastMedium* g = media.single_grid())
        return walk_grid_majorants(*g, query.ray(), query.origin_index(0), query.direction_index(0),
                                   visit);
    return walk_listed_majorants(media, query.ray(), visit);
}

/// sigma_t and sigma_s at distance t on segment s of a walk: from the brick the walk named (one
/// grid medium: no brick-table read), else summed over the segment's media.
__attribute__((always_inline)) inline PointCoefficients coefficients_at(const MediumSet& media,
                                                                        const RayMediaQuery& query,
                                                                        const MajorantSegment& s,
                                                                        const BrickRef* brick,
                                                                        float t) {
    if (brick != nullptr) {
        const MediumSet::FastMedium& m = media.fast(0);
        const float d = query.density_in(0, *brick, t);
        return {m.sigma_t * d, m.sigma_s * d};
    }
    return query.coefficients(t, s.media_mask);
}

}  // namespace kasumi
