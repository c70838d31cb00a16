#include "surface/shadows/shadow_polygons.h"

#include "surface/shadows/weiler_atherton.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>

namespace kasumi {

namespace {

/// Splits the convex lit pieces by the shadow `probe` (the part of the face inside every line
/// of `edges`): pieces outside an edge stay lit, the part inside all of them is shadowed.
void split_pieces(std::vector<ConvexPolygon>& lit, std::vector<ConvexPolygon>& shadowed,
                  const ConvexPolygon& probe, const std::vector<HalfPlane>& edges,
                  double tolerance) {
    std::vector<ConvexPolygon> next;
    // Only pieces whose bounding rectangle meets the shadow's (within the face) can be cut.
    DVec2 lo = probe.vertices.front(), hi = lo;
    for (const DVec2& p : probe.vertices) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    lo -= DVec2(tolerance);
    hi += DVec2(tolerance);
    for (ConvexPolygon& piece : lit) {
        DVec2 piece_lo = piece.vertices.front(), piece_hi = piece_lo;
        for (const DVec2& p : piece.vertices) {
            piece_lo = glm::min(piece_lo, p);
            piece_hi = glm::max(piece_hi, p);
        }
        const bool apart =
            piece_hi.x < lo.x || piece_lo.x > hi.x || piece_hi.y < lo.y || piece_lo.y > hi.y;
        if (apart) {
            next.push_back(std::move(piece));
            continue;
        }
        ConvexPolygon inside = piece;
        for (const HalfPlane& h : edges) {
            PolygonSplit s = split(inside, h, tolerance);
            if (!s.outside.vertices.empty())
                next.push_back(std::move(s.outside));
            inside = std::move(s.inside);
            if (inside.vertices.empty())
                break;
        }
        if (!inside.vertices.empty())
            shadowed.push_back(std::move(inside));
    }
    lit.swap(next);
}

FaceDetail clip_face(const std::array<DVec3, 3>& v, uint32_t shape, uint32_t primitive,
                     const std::vector<PolygonOccluder>& occluders, const LightCentre& light,
                     ShadowClipper clipper, size_t& clipped_pairs) {
    FaceDetail detail;
    const Receiver receiver = make_receiver(v, light);
    if (receiver.degenerate) {
        detail.faces_light = false;
        return detail;
    }
    detail.frame = receiver.frame;
    for (const DVec3& p : v)
        detail.face.vertices.push_back(to_frame(detail.frame, p));
    if (area(detail.face) < 0.0)
        std::reverse(detail.face.vertices.begin(), detail.face.vertices.end());
    if (!receiver.faces_light) {
        detail.faces_light = false;
        detail.shadowed.push_back(region_of(detail.face));
        return detail;
    }
    const double size = receiver.size;
    const double tolerance = kOnLine * size;
    std::vector<ConvexPolygon> lit{detail.face}, shadowed;
    PolygonRegion shadow;
    const LightView view = light_view(v, light);
    for (const PolygonOccluder& o : occluders) {
        if ((o.shape == shape && o.primitive == primitive) || !may_overlap(view, o.view, light))
            continue;
        const std::vector<HalfPlane> edges = shadow_on_plane(o, receiver, light);
        if (edges.empty())
            continue;
        // The shadow meets the face at all? (Its part inside every edge line.)
        ConvexPolygon probe = detail.face;
        for (const HalfPlane& h : edges) {
            probe = split(probe, h, tolerance).inside;
            if (probe.vertices.empty())
                break;
        }
        if (probe.vertices.empty() || !(area(probe) > 0.0))
            continue;
        ++clipped_pairs;
        if (clipper == ShadowClipper::ConvexSplit)
            split_pieces(lit, shadowed, probe, edges, tolerance);
        else
            shadow = unite(shadow, region_of(probe), tolerance);
    }
    if (clipper == ShadowClipper::ConvexSplit) {
        for (const ConvexPolygon& p : lit)
            detail.lit.push_back(region_of(p));
        for (const ConvexPolygon& p : shadowed)
            detail.shadowed.push_back(region_of(p));
        return detail;
    }
    const RegionClip clip = weiler_atherton(region_of(detail.face), shadow, tolerance);
    detail.lit = polygons_with_holes(clip.outside);
    detail.shadowed = polygons_with_holes(clip.inside);
    return detail;
}

}  // namespace

ShadowPolygons build_shadow_polygons(const std::vector<Shape>& shapes, const LightCentre& light,
                                     ShadowClipper clipper) {
    std::vector<std::vector<std::array<DVec3, 3>>> triangles;
    const std::vector<PolygonOccluder> occluders = collect_occluders(shapes, light, triangles);
    ShadowPolygons out;
    out.faces.resize(shapes.size());
    struct Job {
        uint32_t shape, primitive;
    };
    std::vector<Job> jobs;
    for (size_t s = 0; s < triangles.size(); ++s) {
        out.faces[s].resize(triangles[s].size());
        for (size_t i = 0; i < triangles[s].size(); ++i)
            jobs.push_back({static_cast<uint32_t>(s), static_cast<uint32_t>(i)});
    }
    std::vector<size_t> pairs(jobs.size(), 0);
    tbb::parallel_for(size_t(0), jobs.size(), [&](size_t j) {
        const Job& job = jobs[j];
        out.faces[job.shape][job.primitive] =
            clip_face(triangles[job.shape][job.primitive], job.shape, job.primitive, occluders,
                      light, clipper, pairs[j]);
    });
    for (size_t p : pairs)
        out.clipped_pairs += p;
    return out;
}

}  // namespace kasumi
