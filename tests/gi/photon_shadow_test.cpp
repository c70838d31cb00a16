// Shadow photons (Jensen & Christensen 1995): the shadow map's per-light decisions against the
// exact visibility of a point light behind a square occluder, and the rendered image against the
// shadow-ray image. The decisions are deterministic for a fixed seed; what is asserted holds for
// any photon sample (a wrong decision lies within the k-th neighbour's distance of the shadow
// boundary, by the segment argument in gi/photon/photon_shadow.h), except the bounds on how many
// decisions are made, which are stated with their margins below.
#include "gi/photon/photon_shadow.h"
#include "gi/photon/photon_gi.h"
#include "gi/photon/photon_tracer.h"
#include "render/renderer.h"
#include "tests/gi/gi_test_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace kasumi {
namespace {

// A point light at height 2 over a 4 m × 4 m floor; a square occluder of half-width w at height
// 1 (a two-sided quad) casts the exact shadow |x|, |z| <= 2w on the floor (similar triangles).
constexpr float kFloorHalf = 2.0f;

std::string occluder_scene(float w, const std::string& render) {
    const std::string ws = std::to_string(w);
    return R"({
        "camera": {"position": [0, 4.5, 0.001], "look_at": [0, 0, 0], "fov_deg": 50},
        "film": {"width": 64, "height": 64, "spp": 1},
        "materials": {"white": {"type": "phong", "kd": 0.6}},
        "shapes": [
          {"type": "quad", "material": "white",
           "vertices": [[-2, 0, -2], [-2, 0, 2], [2, 0, 2], [2, 0, -2]]},
          {"type": "quad", "material": "white",
           "vertices": [[-)" +
           ws + ", 1, -" + ws + "], [-" + ws + ", 1, " + ws + "], [" + ws + ", 1, " + ws + "], [" +
           ws + ", 1, -" + ws + R"(]]}],
        "lights": [{"type": "point", "position": [0, 2, 0], "intensity_cd": 50}],
        "render": {)" +
           render + "}}";
}

/// Distance in the floor plane from (x, z) to the boundary of the shadow square |x|, |z| <= s.
float distance_to_shadow_edge(float x, float z, float s) {
    const float dx = std::abs(x) - s, dz = std::abs(z) - s;
    if (dx <= 0.0f && dz <= 0.0f)
        return std::min(-dx, -dz);  // inside: to the nearer side
    return std::hypot(std::max(dx, 0.0f), std::max(dz, 0.0f));
}

PhotonMap shadow_map(const SceneRuntime& scene, uint64_t count) {
    PhotonEmitter emitter(scene.desc().lights, scene_bounding_sphere(scene));
    emitter.allot(count);
    return PhotonMap(trace_photons(scene, emitter, PhotonPass::Shadow, 32, 7, 0));
}

TEST(ShadowPhotons, DepositedAtTheFirstHitAndBehindIt) {
    // Every line from the light meets the occluder or the floor first. Lines through the
    // occluder (w = 0.5: its solid angle from the light is 4 arctan(w² / (h √(2w² + h²))) with
    // h = 1, i.e. 1.231 sr, 9.80% of the sphere) leave a direct photon on it and a shadow photon
    // on the floor below; no photon is stored twice on one line's first surface.
    const auto scene = gi_runtime_from_text(occluder_scene(0.5f, R"("gi": "none")"));
    const uint64_t n = 200000;
    const PhotonMap map = shadow_map(*scene, n);
    size_t occluder_direct = 0, occluder_shadow = 0, floor_shadow = 0;
    for (const Photon& p : map.photons()) {
        EXPECT_EQ(p.light, 0u);
        EXPECT_TRUE(is_black(p.power));
        EXPECT_NEAR(glm::length(p.wi), 1.0f, 1e-5f);
        if (p.position.y > 0.5f) {
            ++(p.shadow ? occluder_shadow : occluder_direct);
        } else if (p.shadow) {
            ++floor_shadow;
            // Behind the occluder: inside its exact shadow on the floor.
            EXPECT_LE(std::max(std::abs(p.position.x), std::abs(p.position.z)), 1.0f + 1e-4f);
        } else {
            EXPECT_GE(std::max(std::abs(p.position.x), std::abs(p.position.z)), 1.0f - 1e-4f);
        }
    }
    EXPECT_EQ(occluder_shadow, 0u);
    EXPECT_EQ(floor_shadow, occluder_direct);
    // Binomial(n, 0.0980): σ = 133; 6σ bounds (false-failure rate ~2e-9).
    const double expected = n * 4.0 * std::atan(0.25 / std::sqrt(1.5)) / (4.0 * kPiD);
    EXPECT_NEAR(static_cast<double>(occluder_direct), expected, 6.0 * std::sqrt(expected * 0.902));
}

TEST(ShadowPhotons, DecisionsAreWrongOnlyWithinTheNeighbourRadiusOfTheShadowEdge) {
    // Floor points on a 120 × 120 grid: the decision from the 16 nearest shadow-map photons
    // against the exact visibility (shadowed iff |x|, |z| <= 1). A wrong Lit or Shadowed must lie
    // within r_16 (the 16th neighbour's distance) of the shadow edge; points farther than 0.15 m
    // from the edge must almost all be decided. Photons deposited at the first hit instead of
    // behind it (or not at all) leave no shadow photon on the floor: every umbra point is then
    // Unknown or wrongly Lit, and the umbra bound below fails.
    const auto scene = gi_runtime_from_text(occluder_scene(0.5f, R"("gi": "none")"));
    const PhotonMap map = shadow_map(*scene, 200000);
    const int k = 16;
    const float max_radius = 0.25f;
    PhotonQueryScratch scratch;
    std::vector<PhotonNeighbour> neighbours;
    int wrong_far = 0, lit_far = 0, lit_decided = 0, umbra_far = 0, umbra_decided = 0;
    int decided_near = 0, wrong_near = 0;
    const int grid = 120;
    for (int i = 0; i < grid; ++i) {
        for (int j = 0; j < grid; ++j) {
            const float x = -1.95f + 3.9f * (i + 0.5f) / grid;
            const float z = -1.95f + 3.9f * (j + 0.5f) / grid;
            const Vec3 p(x, 0.0f, z);
            KnownVisibility known = KnownVisibility::Unknown;
            classify_shadow_photons(map, p, Vec3(0, 1, 0), k, max_radius, 1, scratch, &known);
            const bool shadowed = std::abs(x) <= 1.0f && std::abs(z) <= 1.0f;
            const bool wrong = (known == KnownVisibility::Lit && shadowed) ||
                               (known == KnownVisibility::Shadowed && !shadowed);
            const float edge = distance_to_shadow_edge(x, z, 1.0f);
            map.nearest(p, k, max_radius, neighbours);
            float r_k = 0.0f;
            for (const PhotonNeighbour& nb : neighbours)
                r_k = std::max(r_k, std::sqrt(nb.distance2));
            if (wrong) {
                EXPECT_LE(edge, r_k) << x << " " << z;
            }
            if (edge > 0.15f) {
                wrong_far += wrong;
                if (shadowed) {
                    ++umbra_far;
                    umbra_decided += known == KnownVisibility::Shadowed;
                } else {
                    ++lit_far;
                    lit_decided += known == KnownVisibility::Lit;
                }
            } else {
                decided_near += known != KnownVisibility::Unknown;
                wrong_near += wrong;
            }
        }
    }
    EXPECT_EQ(wrong_far, 0);
    // Far from the edge a point is Unknown only when fewer than 4 of its 16 neighbours are in its
    // disc (never, on a plane) or max_radius cuts the search (density here >= 380 photons/m²,
    // so r_16 <= 0.12 m < 0.25 m): all of them must be decided. 1% slack for the grid's cells
    // at the floor's rim, where the disc is cut by the floor's edge.
    EXPECT_GE(lit_decided, 0.99 * lit_far) << lit_decided << " of " << lit_far;
    EXPECT_GE(umbra_decided, 0.99 * umbra_far) << umbra_decided << " of " << umbra_far;
    std::printf("lit decided %d/%d, umbra decided %d/%d; near the edge decided %d, wrong %d\n",
                lit_decided, lit_far, umbra_decided, umbra_far, decided_near, wrong_near);
}

TEST(ShadowPhotons, PhotonsOnTheOtherSideOfAThinSurfaceDoNotCount) {
    // The occluder is one quad: its top holds direct photons at the very points of its underside.
    // Seen from below (normal -y) none arrived on that side, so no decision is made (the light is
    // behind the surface anyway); seen from above, Lit. Counting both sides would call the
    // underside Lit.
    const auto scene = gi_runtime_from_text(occluder_scene(0.5f, R"("gi": "none")"));
    const PhotonMap map = shadow_map(*scene, 200000);
    PhotonQueryScratch scratch;
    for (float x : {-0.3f, 0.0f, 0.2f}) {
        KnownVisibility below = KnownVisibility::Lit, above = KnownVisibility::Unknown;
        classify_shadow_photons(map, Vec3(x, 1.0f, 0.1f), Vec3(0, -1, 0), 16, 0.25f, 1, scratch,
                                &below);
        classify_shadow_photons(map, Vec3(x, 1.0f, 0.1f), Vec3(0, 1, 0), 16, 0.25f, 1, scratch,
                                &above);
        EXPECT_EQ(below, KnownVisibility::Unknown) << x;
        EXPECT_EQ(above, KnownVisibility::Lit) << x;
    }
    // Off by default: no shadow map unless render.photons.shadow_count is set.
    EXPECT_EQ(PhotonSettings{}.shadow_count, 0u);
}

RenderOptions quiet() {
    RenderOptions o;
    o.threads = 0;
    o.progress = false;
    return o;
}

TEST(ShadowPhotons, ImageEqualsTheShadowRayImageAndMostRaysAreAvoided) {
    // Photon mapping reduced to direct light (no global or caustic photons, no gathering) with and
    // without the shadow map. A point light's sample uses no random number and the pixel
    // generators are keyed by pixel, so the two images are equal wherever the shadow map's
    // decision is right; with a small occluder (w = 0.25, shadow 1 m × 1 m on 16 m² of floor)
    // the shadow edge is 4 m long, and decisions are Unknown only within ~r_16 of it.
    const std::string base = R"("gi": "photons", "photons": {"global_count": 0,
        "caustic_count": 0, "final_gather_samples": 0)";
    const auto rays = gi_runtime_from_text(occluder_scene(0.25f, base + "}"));
    const auto photons =
        gi_runtime_from_text(occluder_scene(0.25f, base + R"(, "shadow_count": 200000})"));
    const RenderResult a = render_image(*rays, quiet());
    const RenderResult b = render_image(*photons, quiet());
    EXPECT_EQ(a.counters.shadow_rays_avoided, 0u);
    const uint64_t total = a.counters.surface_shadow_rays;
    ASSERT_GT(total, 3000u);
    EXPECT_EQ(b.counters.surface_shadow_rays + b.counters.shadow_rays_avoided, total);
    const double avoided = static_cast<double>(b.counters.shadow_rays_avoided) / total;
    const Image ia = a.film.to_image(), ib = b.film.to_image();
    const int pixels = ia.width * ia.height;
    int differing = 0;
    for (int i = 0; i < pixels; ++i) {
        bool same = true;
        for (const char* c : {"R", "G", "B"})
            same = same && ia.find(c)->data[i] == ib.find(c)->data[i];
        differing += !same;
    }
    const double differing_fraction = static_cast<double>(differing) / pixels;
    std::printf("shadow rays avoided %.4f; pixels differing %d of %d\n", avoided, differing,
                pixels);
    // Unknown points: the band within r_16 <= 0.12 m of the 4 m edge, at most 0.96 m² of the
    // 16 m² floor (6%), plus the floor's rim; 0.85 leaves room for both.
    EXPECT_GT(avoided, 0.85);
    // A differing pixel needs a wrong decision, within r_16 of the edge: the band holds ~6% of
    // the pixels and almost all decisions there are Unknown (mixed); at most 1% may differ.
    EXPECT_LE(differing_fraction, 0.01);
}

}  // namespace
}  // namespace kasumi
