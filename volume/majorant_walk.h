#pragma once
/// The trackers' walk over a ray's majorant segments, lazily: segments are produced in order as
/// the walk goes and nothing past the point where it stops (a real collision, a scattering
/// event, Russian roulette) is computed. For a set that is exactly one grid medium the segments
/// are the grid's bricks (volume/density_grid.h, `DensityGrid::walk`) and each names its brick,
/// so a lookup skips the brick table; otherwise they are MediumSet::majorants (per brick,
/// overlapping media summed, listed for the whole ray).
#include "volume/medium_set.h"

#include <vector>

namespace kasumi {

/// Calls visit(const MajorantSegment& s, const BrickRef* brick) for each majorant segment of
/// [ray.t_min, ray.t_max] in order until visit returns false (then returns false). `brick` is
/// the grid brick holding s when the set is a single grid (RayMediaQuery::density_in reads it),
/// else null (use RayMediaQuery::coefficients with s.media_mask). Not re-entrant per Visit type
/// for sets other than a single grid (the segment list is thread_local).
template <class Visit>
bool walk_majorants(const MediumSet& media, const Ray& ray, Visit&& visit) {
    if (const MediumSet::FastMedium* g = media.single_grid()) {
        if (g->grid->empty() || !(max_component(g->sigma_t) > 0.0f))
            return true;
        const auto span = g->bounds_world.clip(ray);
        if (!span)
            return true;
        // The same expressions as RayMediaQuery's, so both see the same index-space ray.
        const Vec3 o_index(g->world_to_index * Vec4(ray.origin, 1.0f));
        const Vec3 d_index(g->world_to_index * Vec4(ray.direction, 0.0f));
        const Rgb sigma_t = g->sigma_t;
        return g->grid->walk(o_index, d_index, span->first, span->second,
                             [&](const BrickSpan& b, const BrickRef& brick) {
                                 const MajorantSegment s{b.t0, b.t1, sigma_t * b.density_max,
                                                         sigma_t * b.density_min, 1u};
                                 return visit(s, &brick);
                             });
    }
    thread_local std::vector<MajorantSegment> segments;
    media.majorants(ray, segments);
    for (const MajorantSegment& s : segments) {
        if (!visit(s, static_cast<const BrickRef*>(nullptr)))
            return false;
    }
    return true;
}

}  // namespace kasumi
