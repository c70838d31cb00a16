#include "surface/scanline/scanline_shadows.h"

#include "surface/scanline/active_edge_list.h"
#include "surface/shadows/shadow_projection.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>

namespace kasumi {

namespace {

/// Metres in front of the eye where polygons are cut (the near plane).
constexpr double kNear = 1e-4;

/// Rows per parallel band (the grain of the row loop).
constexpr int kBandRows = 8;

struct Face {
    std::array<DVec3, 3> vertices;
    int32_t shape = 0, primitive = 0;
    DVec3 normal{0.0};                 ///< unit, the triangle's winding
    std::vector<DVec2> screen;         ///< the near-clipped polygon in pixels
    int first_row = 0, last_row = -1;  ///< scanlines whose centre it covers
};

/// A line of the face's shadow pulled back to the scanline: inside where α + β X ≥ 0, X the
/// pixel coordinate (pixel centres at x + 0.5).
struct SpanLine {
    double alpha = 0.0, beta = 0.0;
};

struct Camera {
    DVec3 eye, forward, right, up;
    double half_width, half_height;
    int width, height;
    /// The (unnormalised) ray direction through image point (X, Y).
    DVec3 direction(double x, double y) const {
        const double sx = (2.0 * x / width - 1.0) * half_width;
        const double sy = (1.0 - 2.0 * y / height) * half_height;
        return forward + sx * right + sy * up;
    }
};

std::vector<DVec2> project(const std::array<DVec3, 3>& v, const Camera& c) {
    std::vector<DVec3> polygon;  // camera space: (right, up, forward) coordinates
    for (const DVec3& p : v) {
        const DVec3 d = p - c.eye;
        polygon.emplace_back(glm::dot(d, c.right), glm::dot(d, c.up), glm::dot(d, c.forward));
    }
    // Sutherland–Hodgman against z >= kNear.
    std::vector<DVec3> clipped;
    for (size_t i = 0; i < polygon.size(); ++i) {
        const DVec3& a = polygon[i];
        const DVec3& b = polygon[(i + 1) % polygon.size()];
        if (a.z >= kNear)
            clipped.push_back(a);
        if ((a.z >= kNear) != (b.z >= kNear))
            clipped.push_back(a + ((kNear - a.z) / (b.z - a.z)) * (b - a));
    }
    std::vector<DVec2> screen;
    for (const DVec3& p : clipped)
        screen.emplace_back((p.x / (p.z * c.half_width) + 1.0) * 0.5 * c.width,
                            (1.0 - p.y / (p.z * c.half_height)) * 0.5 * c.height);
    return screen;
}

/// One face's pixels on a row: centres x0..x1 lie in its projection; h = n·(v0 − eye).
struct RowSpan {
    uint32_t face = 0;
    int x0 = 0, x1 = -1;
    double h = 0.0;
};

/// Per-span depth on one row (Watkins 1970, "A real-time visible surface algorithm"; the
/// depth comparison of Bouknight & Kelley's scanline): the spans' ends cut the row into
/// segments over which the set of covering faces is constant. Along a row the inverse depth
/// 1/t = n·d(X)/h of each face's plane is linear in the pixel coordinate X, so the nearest face
/// (the largest of linear functions) is the same over a whole segment when it is the same at
/// both of its ends; otherwise the segment is halved until it is, down to single pixels.
/// Depths are the exact ray–plane distances at pixel centres; ties go to the face first in the
/// active list. Fills winner[x] (−1: no face) and returns the depth evaluations made.
class RowVisibility {
  public:
    RowVisibility(const std::vector<Face>& faces, const Camera& cam, double y)
        : m_faces(faces), m_cam(cam), m_y(y) {}

    size_t resolve(const std::vector<RowSpan>& spans, std::vector<int64_t>& winner) {
        m_spans = &spans;
        m_winner = &winner;
        m_evaluations = 0;
        std::fill(winner.begin(), winner.end(), -1);
        std::vector<int> cuts;
        for (const RowSpan& s : spans) {
            cuts.push_back(s.x0);
            cuts.push_back(s.x1 + 1);
        }
        std::sort(cuts.begin(), cuts.end());
        cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
        for (size_t k = 0; k + 1 < cuts.size(); ++k) {
            const int lo = cuts[k], hi = cuts[k + 1] - 1;
            m_covering.clear();
            for (uint32_t i = 0; i < spans.size(); ++i)
                if (spans[i].x0 <= lo && spans[i].x1 >= hi)
                    m_covering.push_back(i);
            if (m_covering.empty())
                continue;
            fill(lo, hi, nearest(lo), lo == hi ? -2 : nearest(hi));
        }
        return m_evaluations;
    }

  private:
    /// The nearest covering face in front of the eye at pixel x (−1: none).
    int64_t nearest(int x) {
        ++m_evaluations;
        double best = std::numeric_limits<double>::infinity();
        int64_t w = -1;
        const DVec3 d = m_cam.direction(x + 0.5, m_y);
        for (uint32_t i : m_covering) {
            const RowSpan& s = (*m_spans)[i];
            const double t = s.h / glm::dot(m_faces[s.face].normal, d);
            if (t > 0.0 && t < best) {
                best = t;
                w = s.face;
            }
        }
        return w;
    }

    /// Pixels lo..hi, whose end winners are known (w_hi = −2 when hi = lo).
    void fill(int lo, int hi, int64_t w_lo, int64_t w_hi) {
        std::vector<int64_t>& winner = *m_winner;
        if (hi == lo) {
            winner[lo] = w_lo;
            return;
        }
        if (w_lo == w_hi) {
            std::fill(winner.begin() + lo, winner.begin() + hi + 1, w_lo);
            return;
        }
        if (hi - lo == 1) {
            winner[lo] = w_lo;
            winner[hi] = w_hi;
            return;
        }
        const int mid = lo + (hi - lo) / 2;
        const int64_t w_mid = nearest(mid);
        fill(lo, mid, w_lo, w_mid);
        fill(mid, hi, w_mid, w_hi);
    }

    const std::vector<Face>& m_faces;
    const Camera& m_cam;
    double m_y;
    const std::vector<RowSpan>* m_spans = nullptr;
    std::vector<int64_t>* m_winner = nullptr;
    std::vector<uint32_t> m_covering;
    size_t m_evaluations = 0;
};

/// The scanline pass; shadows for `light` when given, else visibility alone.
ScanlineImage scanline_pass(const std::vector<Shape>& shapes, const LightCentre* light_or_null,
                            const ScanlineCamera& camera) {
    // Without a light the occluders are not used: any centre lists the triangles.
    const LightCentre light = light_or_null != nullptr ? *light_or_null : LightCentre{};
    const Camera cam{DVec3(camera.eye),   DVec3(camera.forward),
                     DVec3(camera.right), DVec3(camera.up),
                     camera.half_width,   camera.half_width * camera.height / camera.width,
                     camera.width,        camera.height};
    ScanlineImage image;
    image.width = camera.width;
    image.height = camera.height;
    const size_t pixels = size_t(camera.width) * camera.height;
    image.shape.assign(pixels, -1);
    image.primitive.assign(pixels, -1);
    image.shadowed.assign(pixels, 0);

    std::vector<std::vector<std::array<DVec3, 3>>> triangles;
    const std::vector<PolygonOccluder> occluders = collect_occluders(shapes, light, triangles);
    std::vector<Face> faces;
    for (size_t s = 0; s < triangles.size(); ++s)
        for (size_t i = 0; i < triangles[s].size(); ++i) {
            Face f;
            f.vertices = triangles[s][i];
            f.shape = static_cast<int32_t>(s);
            f.primitive = static_cast<int32_t>(i);
            const DVec3 n =
                glm::cross(f.vertices[1] - f.vertices[0], f.vertices[2] - f.vertices[0]);
            if (!(glm::length(n) > 0.0))
                continue;
            f.normal = glm::normalize(n);
            f.screen = project(f.vertices, cam);
            if (f.screen.size() < 3)
                continue;
            double y_min = f.screen[0].y, y_max = y_min;
            for (const DVec2& p : f.screen) {
                y_min = std::min(y_min, p.y);
                y_max = std::max(y_max, p.y);
            }
            f.first_row = std::max(0, static_cast<int>(std::ceil(y_min - 0.5)));
            f.last_row = std::min(camera.height - 1, static_cast<int>(std::floor(y_max - 0.5)));
            if (f.first_row <= f.last_row)
                faces.push_back(std::move(f));
        }
    // The polygon table: faces sorted by their first scanline; a face's rank there orders the
    // spans of a scanline (and breaks depth ties). Its edges go into the edge table.
    std::vector<uint32_t> table(faces.size());
    for (uint32_t i = 0; i < table.size(); ++i)
        table[i] = i;
    std::stable_sort(table.begin(), table.end(), [&](uint32_t a, uint32_t b) {
        return faces[a].first_row < faces[b].first_row;
    });
    std::vector<uint32_t> rank(faces.size());
    for (uint32_t i = 0; i < table.size(); ++i)
        rank[table[i]] = i;
    std::vector<std::vector<DVec2>> polygons(faces.size());
    for (size_t f = 0; f < faces.size(); ++f)
        polygons[f] = faces[f].screen;
    const EdgeTable edge_table(polygons, rank, camera.height);

    // Shadow pairs per face, found the first time the face is seen (by whichever band of rows
    // sees it first: the list is the same whoever builds it).
    std::vector<std::vector<std::vector<HalfPlane>>> pairs(faces.size());
    std::vector<Receiver> receivers(faces.size());
    const std::unique_ptr<std::once_flag[]> found(new std::once_flag[faces.size()]);
    std::atomic<size_t> shadow_pair_count{0}, span_count{0}, covered_count{0}, evaluation_count{0};
    const auto shadow_pairs = [&](uint32_t f) -> const std::vector<std::vector<HalfPlane>>& {
        std::call_once(found[f], [&] {
            receivers[f] = make_receiver(faces[f].vertices, light);
            std::vector<std::vector<HalfPlane>> list;
            const LightView view = light_view(faces[f].vertices, light);
            if (receivers[f].faces_light)
                for (const PolygonOccluder& o : occluders) {
                    if ((int32_t(o.shape) == faces[f].shape &&
                         int32_t(o.primitive) == faces[f].primitive) ||
                        !may_overlap(view, o.view, light))
                        continue;
                    std::vector<HalfPlane> edges = shadow_on_plane(o, receivers[f], light);
                    if (!edges.empty())
                        list.push_back(std::move(edges));
                }
            shadow_pair_count += list.size();
            pairs[f] = std::move(list);
        });
        return pairs[f];
    };

    // Bands of kBandRows rows in parallel, starting at fixed rows. Each band starts its active
    // edge list at its first row (x evaluated there, then stepped by dx/dy), so a row's spans
    // and their order do not depend on which thread ran the band, nor on how many there are.
    const int bands = (camera.height + kBandRows - 1) / kBandRows;
    tbb::parallel_for(
        tbb::blocked_range<int>(0, bands, 1), [&](const tbb::blocked_range<int>& band_range) {
            for (int band = band_range.begin(); band < band_range.end(); ++band) {
                const int first = band * kBandRows;
                const int last = std::min(camera.height, first + kBandRows);
                ActiveEdgeList active(edge_table, first);
                std::vector<PolygonSpan> polygon_spans;
                std::vector<int64_t> winner(camera.width);
                size_t spans = 0, covered = 0, evaluations = 0;
                for (int row = first; row < last; ++row) {
                    if (row > first)
                        active.next_row();
                    const double y = row + 0.5;
                    active.spans(polygon_spans);
                    std::vector<RowSpan> row_spans;
                    for (const PolygonSpan& span : polygon_spans) {
                        const uint32_t f = span.polygon;
                        const int x0 = std::max(0, static_cast<int>(std::ceil(span.x_lo - 0.5)));
                        const int x1 = std::min(camera.width - 1,
                                                static_cast<int>(std::floor(span.x_hi - 0.5)));
                        if (x0 <= x1)
                            row_spans.push_back(
                                {f, x0, x1,
                                 glm::dot(faces[f].normal, faces[f].vertices[0] - cam.eye)});
                        covered += x0 <= x1 ? size_t(x1 - x0 + 1) : 0;
                    }
                    evaluations += RowVisibility(faces, cam, y).resolve(row_spans, winner);
                    // Spans: runs of pixels won by one face.
                    for (int x = 0; x < camera.width;) {
                        const int64_t f = winner[x];
                        int end = x + 1;
                        while (end < camera.width && winner[end] == f)
                            ++end;
                        if (f >= 0) {
                            const Face& face = faces[f];
                            ++spans;
                            if (light_or_null == nullptr) {
                                for (int k = x; k < end; ++k) {
                                    const size_t p = size_t(row) * camera.width + k;
                                    image.shape[p] = face.shape;
                                    image.primitive[p] = face.primitive;
                                }
                                x = end;
                                continue;
                            }
                            const auto& list = shadow_pairs(static_cast<uint32_t>(f));
                            const Receiver& r = receivers[f];
                            // The eye on the other side of the face than the light: self-shadowed.
                            const bool away =
                                glm::dot(r.frame.normal, cam.eye - r.frame.origin) <= 0.0;
                            const DVec3 d0 = cam.direction(0.0, y), d1 = cam.direction(1.0, y) - d0;
                            const double h = glm::dot(r.frame.normal, r.frame.origin - cam.eye);
                            for (int k = x; k < end; ++k) {
                                const size_t p = size_t(row) * camera.width + k;
                                image.shape[p] = face.shape;
                                image.primitive[p] = face.primitive;
                                image.shadowed[p] = !r.faces_light || away ? 1 : 0;
                            }
                            if (r.faces_light && !away) {
                                for (const std::vector<HalfPlane>& edges : list) {
                                    // Each edge line f(P) = m·P + c >= 0 on the plane; along the
                                    // row P(X) = eye + h d(X) / (n·d(X)), and n·d(X) has the sign
                                    // of h for points in front of the eye, so f >= 0 iff sign(h)
                                    // ((m·eye + c) n·d(X) + h m·d(X)) >= 0: linear in X.
                                    double lo = x + 0.5, hi = end - 0.5;
                                    for (const HalfPlane& e : edges) {
                                        const DVec3 m =
                                            e.normal.x * r.frame.e_u + e.normal.y * r.frame.e_v;
                                        const double c = e.offset - glm::dot(m, r.frame.origin);
                                        const double at_eye = glm::dot(m, cam.eye) + c;
                                        const double sign = h < 0.0 ? -1.0 : 1.0;
                                        const SpanLine line{
                                            sign * (at_eye * glm::dot(r.frame.normal, d0) +
                                                    h * glm::dot(m, d0)),
                                            sign * (at_eye * glm::dot(r.frame.normal, d1) +
                                                    h * glm::dot(m, d1))};
                                        if (line.beta > 0.0)
                                            lo = std::max(lo, -line.alpha / line.beta);
                                        else if (line.beta < 0.0)
                                            hi = std::min(hi, -line.alpha / line.beta);
                                        else if (line.alpha < 0.0)
                                            hi = -std::numeric_limits<double>::infinity();
                                        if (!(lo <= hi))
                                            break;
                                    }
                                    if (!(lo <= hi))
                                        continue;
                                    // Pixels whose centre X = k + 0.5 lies in [lo, hi].
                                    const int k0 =
                                        std::max(x, static_cast<int>(std::ceil(lo - 0.5)));
                                    const int k1 =
                                        std::min(end - 1, static_cast<int>(std::floor(hi - 0.5)));
                                    for (int k = k0; k <= k1; ++k)
                                        image.shadowed[size_t(row) * camera.width + k] = 1;
                                }
                            }
                        }
                        x = end;
                    }
                }
                span_count += spans;
                covered_count += covered;
                evaluation_count += evaluations;
            }
        });
    image.spans = span_count;
    image.shadow_pairs = shadow_pair_count;
    image.covered_pixels = covered_count;
    image.depth_evaluations = evaluation_count;
    return image;
}

}  // namespace

ScanlineImage render_scanline_shadows(const std::vector<Shape>& shapes, const LightCentre& light,
                                      const ScanlineCamera& camera) {
    return scanline_pass(shapes, &light, camera);
}

ScanlineImage render_scanline_visibility(const std::vector<Shape>& shapes,
                                         const ScanlineCamera& camera) {
    return scanline_pass(shapes, nullptr, camera);
}

}  // namespace kasumi
