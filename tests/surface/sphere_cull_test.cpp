// Spheres in the Embree scene (user geometry) skip the double-precision ray test for rays whose
// line passes clear of them in a float test with a margin (surface_scene.cpp,
// line_may_meet_sphere). It must never drop a ray the exact test would hit: rays aimed at the
// silhouette from inside and outside by relative offsets down to 1e-7, from origins near and
// far, on spheres near the origin and far from it (where the float centre is rounded), long
// and unnormalised directions included; each answer must equal intersect_sphere's in double.
#include "lights/ray_sphere.h"
#include "surface/surface_scene.h"
#include "tests/surface/test_shapes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace kasumi {
namespace {

struct Case {
    Vec3 center;
    float radius;
    float distance;  ///< of the ray origins from the centre
};

TEST(SphereCull, NoGrazingRayIsDroppedThatTheExactTestHits) {
    const Case cases[] = {{Vec3(0.3f, 1.6f, 0.0f), 0.6f, 8.0f},
                          {Vec3(0.3f, 1.6f, 0.0f), 0.6f, 1.0e3f},
                          {Vec3(1.0e4f, -3.0e3f, 2.0e2f), 0.7f, 5.0f},
                          {Vec3(-2.5e5f, 1.0e3f, 4.0e4f), 30.0f, 2.0e3f},
                          {Vec3(0.0f), 6.4e6f, 6.4e6f + 100.0f}};
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    const auto random_direction = [&] {
        Vec3 v;
        do {
            v = Vec3(unit(rng), unit(rng), unit(rng));
        } while (glm::dot(v, v) > 1.0f || glm::dot(v, v) < 1e-4f);
        return glm::normalize(v);
    };
    size_t hits = 0, misses = 0, grazing = 0;
    for (const Case& c : cases) {
        SCOPED_TRACE(c.radius);
        const SurfaceScene scene({sphere(c.center, c.radius)});
        for (int k = 0; k < 4000; ++k) {
            const Vec3 origin = c.center + c.distance * random_direction();
            // A silhouette point: perpendicular to the view of the centre, at r (1 + s), s a
            // signed relative offset between 1e-7 and 1e-2 (log-uniform), then a random scale
            // of the direction (Embree and the exact test both take any length).
            const Vec3 to_center = c.center - origin;
            Vec3 side = glm::cross(to_center, random_direction());
            side /= glm::length(side);
            const float s =
                (k % 2 ? 1.0f : -1.0f) * std::pow(10.0f, -7.0f + 5.0f * (unit(rng) + 1.0f) / 2.0f);
            const Vec3 target = c.center + c.radius * (1.0f + s) * side;
            Vec3 direction = glm::normalize(target - origin);
            Ray ray{origin, direction, 0.0f, kInfinity};
            const auto hit = scene.intersect(ray);
            const auto exact = intersect_sphere(DVec3(c.center), c.radius, DVec3(origin),
                                                DVec3(direction), 0.0, 1e30);
            // intersect() shortens the interval to Embree's closed form by one float step at
            // t = 0: the origins are far outside, so the hit/miss answer is the exact one.
            ASSERT_EQ(hit.has_value(), exact.has_value())
                << "origin " << origin.x << " " << origin.y << " " << origin.z << " offset " << s;
            (hit ? hits : misses)++;
            grazing += std::fabs(s) < 1e-5f ? 1u : 0u;
        }
    }
    EXPECT_GT(hits, 2000u);
    EXPECT_GT(misses, 2000u);
    EXPECT_GT(grazing, 2000u);
}

}  // namespace
}  // namespace kasumi
