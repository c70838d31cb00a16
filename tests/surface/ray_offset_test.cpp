#include "surface/surface_scene.h"

#include "core/rng.h"
#include "core/sampling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace kasumi {
namespace {

constexpr int kPoints = 10000;

Shape make(std::variant<SphereShape, QuadShape, BoxShape, MeshShape> geometry) {
    Shape s;
    s.geometry = std::move(geometry);
    return s;
}

/// A square ground quad of half-size `half`, centred at `center`, tilted by `tilt_deg` about
/// the x axis; front side up.
QuadShape ground(const Vec3& center, float half, float tilt_deg) {
    const float c = std::cos(radians(tilt_deg)), s = std::sin(radians(tilt_deg));
    const Vec3 x(half, 0, 0);
    const Vec3 z(0, -s * half, c * half);
    return QuadShape{{center - x - z, center - x + z, center + x + z, center + x - z}};
}

struct AcneCase {
    std::string name;
    Shape shape;
    Vec3 focus;   ///< points are sampled around here...
    float reach;  ///< ...within this distance (metres)
};

/// Counts shadow rays that hit their own surface. Surface points come from camera rays (so
/// they carry the float error real hits carry); each gets a random direction toward a light
/// on its front side, from grazing (cos 1e-3) to normal incidence.
struct AcneCount {
    int point_offset = 0;  ///< self-hits with offset_ray_origin(p, n, wi)
    int hit_offset = 0;    ///< self-hits with offset_ray_origin(hit, wi)
    int points = 0;
};

AcneCount count_acne(const AcneCase& c, uint64_t seed) {
    const SurfaceScene scene({c.shape});
    Pcg32 rng(seed, 5);
    AcneCount count;
    while (count.points < kPoints) {
        Ray camera;
        const Vec3 target =
            c.focus +
            c.reach * (2.0f * Vec3(rng.next_float(), rng.next_float(), rng.next_float()) - 1.0f);
        camera.origin = target + 3.0f * c.reach * sample_uniform_sphere(rng.next_vec2());
        camera.direction = glm::normalize(target - camera.origin);
        const auto hit = scene.intersect(camera);
        if (!hit)
            continue;
        const Vec3& n = hit->geometric_normal;
        const float cos_theta = std::max(1e-3f, rng.next_float());
        const Vec3 wi = direction_about(n, cos_theta, kTwoPi * rng.next_float());
        ++count.points;
        Ray shadow;
        shadow.direction = wi;
        shadow.origin = offset_ray_origin(hit->position, n, wi);
        count.point_offset += scene.occluded(shadow);
        shadow.origin = offset_ray_origin(*hit, wi);
        count.hit_offset += scene.occluded(shadow);
    }
    return count;
}

const float kFar = 1e4f;

std::vector<AcneCase> acne_cases() {
    return {
        {"unit sphere", make(SphereShape{Vec3(0), 1.0f}), Vec3(0), 1.0f},
        {"unit sphere at 1e4", make(SphereShape{Vec3(kFar), 1.0f}), Vec3(kFar), 1.0f},
        {"sphere r=1e4", make(SphereShape{Vec3(0), kFar}), Vec3(0), kFar},
        {"small sphere r=1e-2 at 10", make(SphereShape{Vec3(10), 1e-2f}), Vec3(10), 1e-2f},
        // The origin on the surface of an Earth-sized sphere, seen up close.
        {"planet", make(SphereShape{Vec3(0, -6.371e6f, 0), 6.371e6f}), Vec3(0), 100.0f},
        {"ground 2e4 m", make(ground(Vec3(0), kFar, 0)), Vec3(0), 100.0f},
        {"ground 2e4 m at 1e4", make(ground(Vec3(kFar), kFar, 0)), Vec3(kFar), 100.0f},
        {"tilted ground 20 m", make(ground(Vec3(0), 10.0f, 20)), Vec3(0), 10.0f},
        {"tilted ground 2e4 m far part", make(ground(Vec3(0), kFar, 20)), Vec3(5e3f), 5e3f},
        {"tilted ground 20 m at 1e4", make(ground(Vec3(kFar), 10.0f, 20)), Vec3(kFar), 10.0f},
        {"box at 1e4", make(BoxShape{Vec3(kFar), Vec3(kFar + 1.0f)}), Vec3(kFar + 0.5f), 1.0f},
    };
}

/// Self-intersection (acne) must never happen: zero of 10k shadow rays may hit their own
/// surface, for spheres from 1 cm to planet size and ground quads up to 1e4 m from the origin.
TEST(RayOffset, NoSelfIntersection) {
    uint64_t seed = 1;
    for (const AcneCase& c : acne_cases()) {
        const AcneCount count = count_acne(c, seed++);
        EXPECT_EQ(count.point_offset, 0) << c.name;
        EXPECT_EQ(count.hit_offset, 0) << c.name;
    }
}

/// The primitive-aware offset also covers a 2e4 m tilted ground hit near the origin, where the
/// point alone understates the error (Embree works relative to vertices 1e4 m away).
TEST(RayOffset, HitOffsetCoversLargePrimitiveNearOrigin) {
    const AcneCase c{"tilted ground 2e4 m near origin", make(ground(Vec3(0), kFar, 20)), Vec3(0),
                     10.0f};
    EXPECT_EQ(count_acne(c, 99).hit_offset, 0);
}

TEST(RayOffset, OffsetSideFollowsDirectionAndScale) {
    const Vec3 n(0, 1, 0);
    const Vec3 p(3, 0, -2);
    const Vec3 up = offset_ray_origin(p, n, Vec3(0.1f, 0.5f, 0));
    const Vec3 down = offset_ray_origin(p, n, Vec3(0.1f, -0.5f, 0));
    const float expected = kRayOffsetRelative * (kRayOffsetFloor + 3.0f);
    EXPECT_FLOAT_EQ(up.y, expected);
    EXPECT_FLOAT_EQ(down.y, -expected);
    EXPECT_EQ(up.x, p.x);
    EXPECT_EQ(up.z, p.z);
}

/// Contact shadows. A box of height h stands on a ground quad; a directional light at
/// elevation θ shines over it from -x, so the box's shadow covers the ground from its face at
/// x = x0 to x0 + L, L = h / tan θ, exactly. A shadow ray from a ground point at distance d
/// from the face, its origin raised by ε along the ground normal, crosses the face's plane at
/// height ε + d tan θ: the shadow reaches the contact edge (d → 0) for any ε < h, and its far
/// edge moves by at most ε / tan θ. For each sampled ground point (from a camera hit, so with
/// real float error) the test asserts the exact answer outside the band
/// |d - L| <= (ε + 4 ulp(scale)) / tan θ, and that this band is below `max_band` of L.
void expect_sharp_contact_shadow(const Vec3& origin, float h, float elevation_deg, float max_band) {
    const float tan_theta = std::tan(radians(elevation_deg));
    const float length = h / tan_theta;
    const float x0 = origin.x;
    const SurfaceScene scene(
        {make(ground(origin, 10.0f * length, 0)),
         make(BoxShape{origin + Vec3(-h, 0, -5.0f * length), origin + Vec3(0, h, 5.0f * length)})});
    const Vec3 wi(-std::cos(radians(elevation_deg)), std::sin(radians(elevation_deg)), 0.0f);
    const float scale =
        std::max(std::abs(origin.x), std::max(std::abs(origin.y), std::abs(origin.z))) +
        2.0f * length;
    const float epsilon = kRayOffsetRelative * (kRayOffsetFloor + scale);
    const float ulp = 0x1p-23f * scale;
    const float band = (epsilon + 4.0f * ulp) / tan_theta;
    EXPECT_LT(band, max_band * length) << "offset too large for a sharp contact shadow";

    Pcg32 rng(17, 4);
    int contact = 0, shadowed = 0, lit = 0;
    // Distances log-uniform from 8 ulps (closer is the box's edge itself) to 2 L, so the
    // contact edge is sampled over many decades.
    const float d_min = std::max(1e-6f * length, 8.0f * ulp);
    for (int i = 0; i < kPoints; ++i) {
        const float d = d_min * std::pow(2.0f * length / d_min, rng.next_float());
        Ray camera;
        camera.origin = origin + Vec3(d + 0.3f * length, 3.0f * length, 0.1f * length);
        camera.direction = glm::normalize(origin + Vec3(d, 0, 0) - camera.origin);
        const auto hit = scene.intersect(camera);
        ASSERT_TRUE(hit);
        if (hit->shape != 0u)
            continue;  // rounding put the target on the box's bottom edge
        const float d_hit = hit->position.x - x0;
        Ray shadow;
        shadow.direction = wi;
        shadow.origin = offset_ray_origin(hit->position, hit->geometric_normal, wi);
        const bool blocked = scene.occluded(shadow);
        if (d_hit < length - band) {
            EXPECT_TRUE(blocked) << "light leaks at d = " << d_hit << " m, L = " << length;
            ++shadowed;
            contact += d_hit < 10.0f * d_min;
        } else if (d_hit > length + band) {
            EXPECT_FALSE(blocked) << "spurious shadow at d = " << d_hit << " m, L = " << length;
            ++lit;
        }
    }
    EXPECT_GT(contact, 1000);
    EXPECT_GT(shadowed, 3000);
    EXPECT_GT(lit, 300);
}

/// A 1 cm box: the shadow is exact to 0.1% of its 5.7 cm length, from 6e-8 m of its face.
TEST(RayOffset, ContactShadowOfSmallBoxNearOrigin) {
    expect_sharp_contact_shadow(Vec3(0), 0.01f, 10.0f, 1e-3f);
}

/// Grazing light (2°) magnifies the offset by 1 / tan θ = 29: still exact to 0.1%.
TEST(RayOffset, ContactShadowAtGrazingLight) {
    expect_sharp_contact_shadow(Vec3(1.0f, 0.0f, -2.0f), 0.1f, 2.0f, 1e-3f);
}

/// 1e4 m from the origin float spacing is 1 mm: a 1 m box keeps its contact shadow from 8 mm
/// of its face, with the far edge exact to 5% of its length.
TEST(RayOffset, ContactShadowFarFromOrigin) {
    expect_sharp_contact_shadow(Vec3(kFar, 0.0f, kFar), 1.0f, 10.0f, 5e-2f);
}

}  // namespace
}  // namespace kasumi
