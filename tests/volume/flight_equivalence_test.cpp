// The free-flight and shadow hot path's shortcuts against the plain forms they replace, bit for
// bit (a render must not move one bit): the brick DDA against a reference DDA written the
// straightforward way (floor, indexed axes, brick slot recomputed per step); the walk on a
// RayMediaQuery's index-space ray against the walk that transforms the ray itself; the Poisson
// collision walk against one that takes every collision's logarithm at once; the
// one-medium scattering sample with known coefficients against the general one.
#include "core/rng.h"
#include "volume/grid/density_grid.h"
#include "volume/majorant_walk.h"
#include "volume/medium_set.h"
#include "volume/poisson_collisions.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstring>
#include <memory>
#include <vector>

namespace kasumi {
namespace {

constexpr int kEdge = 48;  ///< voxels per grid edge: 6 bricks per axis

/// Random blocks of random densities; about half the bricks stay empty.
std::shared_ptr<DensityGrid> blocks_grid(uint64_t seed) {
    auto grid =
        std::make_shared<DensityGrid>(IVec3(-5, 3, 0), IVec3(kEdge - 6, kEdge + 2, kEdge - 1));
    Pcg32 rng(seed, 7);
    for (int bz = 0; bz < kEdge / 8; ++bz)
        for (int by = 0; by < kEdge / 8; ++by)
            for (int bx = 0; bx < kEdge / 8; ++bx) {
                if (rng.next_float() < 0.5f)
                    continue;
                for (int z = 0; z < 8; ++z)
                    for (int y = 0; y < 8; ++y)
                        for (int x = 0; x < 8; ++x)
                            grid->set(IVec3(8 * bx + x - 5, 8 * by + y + 3, 8 * bz + z),
                                      2.0f * rng.next_float());
            }
    grid->finalize();
    return grid;
}

bool same_bits(float a, float b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

/// One brick crossing of the reference DDA: [t0, t1] in the brick whose voxel (0, 0, 0) is at
/// `lower` (index space).
struct Crossing {
    float t0, t1;
    Vec3 lower;
};

/// The brick DDA as first written (Amanatides & Woo 1987): every brick crossing with t1 > t0,
/// empty or not, computed with floor, per-axis arrays and the slot recomputed per step.
std::vector<Crossing> reference_crossings(const DensityGrid& grid, const Vec3& o, const Vec3& dir,
                                          float t0, float t1) {
    constexpr int kBrick = DensityGrid::kBrick;
    std::vector<Crossing> out;
    const Vec3 origin = grid.lower();
    const IVec3 bricks = IVec3((grid.upper() - grid.lower()) / static_cast<float>(kBrick));
    const Vec3 p = (o - origin) * (1.0f / kBrick);
    const Vec3 d = dir * (1.0f / kBrick);
    const Vec3 n(bricks);
    float ta = t0, tb = t1;
    IVec3 step(0);
    Vec3 t_next(kInfinity), t_delta(0.0f);
    for (int a = 0; a < 3; ++a) {
        if (!(d[a] > 0.0f || d[a] < 0.0f)) {  // parallel to the slab: inside it or missing
            if (p[a] < 0.0f || !(p[a] < n[a]))
                return out;
            continue;
        }
        const float inv = 1.0f / d[a];
        const float enter = (0.0f - p[a]) * inv, leave = (n[a] - p[a]) * inv;
        ta = std::max(ta, std::min(enter, leave));
        tb = std::min(tb, std::max(leave, enter));
    }
    if (!(tb > ta))
        return out;
    IVec3 cell = glm::clamp(IVec3(glm::floor(p + d * ta)), IVec3(0), bricks - IVec3(1));
    for (int a = 0; a < 3; ++a) {
        if (d[a] > 0.0f || d[a] < 0.0f) {
            const bool up = d[a] > 0.0f;
            step[a] = up ? 1 : -1;
            t_next[a] = (static_cast<float>(cell[a] + (up ? 1 : 0)) - p[a]) / d[a];
            t_delta[a] = (up ? 1.0f : -1.0f) / d[a];
        }
    }
    for (float t = ta; t < tb;) {
        const int axis =
            t_next.x <= t_next.y ? (t_next.x <= t_next.z ? 0 : 2) : (t_next.y <= t_next.z ? 1 : 2);
        const float t_exit = std::min(t_next[axis], tb);
        if (t_exit > t)
            out.push_back({t, t_exit, origin + Vec3(cell * kBrick)});
        t = std::max(t, t_exit);
        cell[axis] += step[axis];
        if (cell[axis] < 0 || cell[axis] >= bricks[axis])
            break;
        t_next[axis] += t_delta[axis];
    }
    return out;
}

TEST(FlightEquivalence, BrickWalkMatchesTheReferenceDdaBitForBit) {
    const auto grid = blocks_grid(3);
    ASSERT_GT(grid->allocated_bricks(), 20u);
    ASSERT_LT(grid->allocated_bricks(), grid->total_bricks());
    Pcg32 rng(9, 2);
    size_t spans = 0;
    for (int r = 0; r < 3000; ++r) {
        const auto in_box = [&] {
            return grid->lower() - Vec3(6.0f) +
                   Vec3(rng.next_float(), rng.next_float(), rng.next_float()) *
                       (grid->upper() - grid->lower() + Vec3(12.0f));
        };
        const Vec3 o = in_box();
        Vec3 d = in_box() - o;
        // Axis-parallel rays (zero components) and rays starting inside the grid included.
        if (r % 7 == 0)
            d.x = 0.0f;
        if (r % 11 == 0)
            d.y = 0.0f;
        const float t0 = r % 3 == 0 ? 0.3f * rng.next_float() : 0.0f;
        const float t1 = r % 5 == 0 ? 0.5f + 0.5f * rng.next_float() : 1.0f;
        const std::vector<Crossing> reference = reference_crossings(*grid, o, d, t0, t1);
        size_t next = 0;  // the walk's spans are a subsequence of the reference crossings
        grid->walk(o, d, t0, t1, [&](const BrickSpan& s, const BrickRef& b) {
            while (next < reference.size() && !same_bits(reference[next].t0, s.t0))
                ++next;
            EXPECT_LT(next, reference.size()) << "ray " << r;
            if (next < reference.size()) {
                EXPECT_TRUE(same_bits(reference[next].t1, s.t1)) << "ray " << r;
                EXPECT_EQ(reference[next].lower, b.lower) << "ray " << r;
                ++next;
            }
            ++spans;
            return true;
        });
    }
    EXPECT_GT(spans, 3000u);
}

/// One grid medium placed in the world by a rotation, a scale and a translation.
MediumSet placed_grid(const std::shared_ptr<DensityGrid>& grid) {
    VdbMedium v;
    v.grid = grid;
    const Mat4 index_to_world =
        glm::translate(Mat4(1.0f), Vec3(3.0f, -2.0f, 10.0f)) *
        glm::rotate(Mat4(1.0f), 0.7f, glm::normalize(Vec3(1.0f, 2.0f, 0.5f))) *
        glm::scale(Mat4(1.0f), Vec3(0.25f));
    v.world_to_index = glm::inverse(index_to_world);
    v.sigma_a_per_density = Rgb(0.3f, 0.2f, 0.1f);
    v.sigma_s_per_density = Rgb(1.0f, 1.5f, 2.0f);
    for (int c = 0; c < 8; ++c) {
        const Vec3 corner((c & 1) ? grid->upper().x : grid->lower().x,
                          (c & 2) ? grid->upper().y : grid->lower().y,
                          (c & 4) ? grid->upper().z : grid->lower().z);
        v.bounds_world.extend(Vec3(index_to_world * Vec4(corner, 1.0f)));
    }
    return MediumSet({Medium{"blocks", v}});
}

struct Visited {
    MajorantSegment s;
    Vec3 lower;
};

TEST(FlightEquivalence, WalkOnTheQueryRayMatchesTheWalkOnTheRay) {
    const MediumSet media = placed_grid(blocks_grid(5));
    ASSERT_NE(media.single_grid(), nullptr);
    const Bounds3 box = media.fast(0).bounds_world;
    Pcg32 rng(4, 4);
    size_t segments = 0;
    for (int r = 0; r < 2000; ++r) {
        const Vec3 a =
            box.min + Vec3(rng.next_float(), rng.next_float(), rng.next_float()) * box.extent();
        const Vec3 b =
            box.min + Vec3(rng.next_float(), rng.next_float(), rng.next_float()) * box.extent();
        const Ray ray{a - (b - a), glm::normalize(b - a), 0.1f * rng.next_float(),
                      3.0f * glm::length(b - a)};
        const auto record = [](std::vector<Visited>& out) {
            return [&out](const MajorantSegment& s, const BrickRef* brick) {
                out.push_back({s, brick != nullptr ? brick->lower : Vec3(-1.0f)});
                return true;
            };
        };
        std::vector<Visited> by_ray, by_query;
        walk_majorants(media, ray, record(by_ray));
        const RayMediaQuery query(media, ray);
        walk_majorants(media, query, record(by_query));
        ASSERT_EQ(by_ray.size(), by_query.size()) << "ray " << r;
        for (size_t i = 0; i < by_ray.size(); ++i) {
            const MajorantSegment &x = by_ray[i].s, &y = by_query[i].s;
            EXPECT_TRUE(same_bits(x.t0, y.t0) && same_bits(x.t1, y.t1)) << "ray " << r;
            for (int c = 0; c < 3; ++c) {
                EXPECT_TRUE(same_bits(x.sigma_max[c], y.sigma_max[c])) << "ray " << r;
                EXPECT_TRUE(same_bits(x.sigma_min[c], y.sigma_min[c])) << "ray " << r;
            }
            EXPECT_EQ(by_ray[i].lower, by_query[i].lower);
        }
        segments += by_ray.size();
    }
    EXPECT_GT(segments, 2000u);
}

/// Collisions::walk as first written: each collision's unit exponential drawn and its
/// logarithm taken at once.
class EagerCollisions {
  public:
    explicit EagerCollisions(Pcg32& rng) : m_rng(rng) {}
    template <class At>
    bool walk(float t0, float t1, float mu, At&& at) {
        if (m_left < 0.0f)
            m_left = unit_exponential(m_rng);
        for (float t = t0;;) {
            const float depth = std::max(t1 - t, 0.0f) * mu;
            if (!(m_left < depth)) {
                m_left -= depth;
                return true;
            }
            t = std::max(t + m_left / mu, std::nextafter(t, kInfinity));
            m_left = unit_exponential(m_rng);
            if (!at(t))
                return false;
        }
    }

  private:
    Pcg32& m_rng;
    float m_left = -1.0f;
};

/// Collisions as walk_tentative_collisions drives it: passes() in line first, walk() only for
/// a segment that holds a collision.
class CheckedCollisions {
  public:
    explicit CheckedCollisions(Pcg32& rng) : m_collisions(rng) {}
    template <class At>
    bool walk(float t0, float t1, float mu, At&& at) {
        return m_collisions.passes(t0, t1, mu) || m_collisions.walk(t0, t1, mu, at);
    }

  private:
    Collisions m_collisions;
};

/// The collision distances of a walk over random segments (some starting at t = 0) whose
/// visitor draws its own numbers and stops at random, and the generator's state after it.
template <class Walker>
std::pair<std::vector<float>, uint32_t> collisions_of(uint64_t seed) {
    Pcg32 rng(seed, 5);
    Walker walker(rng);
    std::vector<float> ts;
    float t = seed % 2 == 0 ? 0.0f : 0.5f;
    for (int segment = 0; segment < 12; ++segment) {
        const float length = 3.0f * rng.next_float(), mu = 0.1f + 4.0f * rng.next_float();
        const bool go_on = walker.walk(t, t + length, mu, [&](float tc) {
            ts.push_back(tc);
            return rng.next_float() < 0.9f;  // the visitor's own number, then maybe a stop
        });
        if (!go_on)
            break;
        t += length;
    }
    return {ts, rng.next_u32()};
}

TEST(FlightEquivalence, LazyLogarithmsAndTheInlineEmptySegmentTestGiveTheEagerWalk) {
    size_t collisions = 0;
    for (uint64_t seed = 0; seed < 500; ++seed) {
        const auto lazy = collisions_of<Collisions>(seed);
        const auto eager = collisions_of<EagerCollisions>(seed);
        const auto checked = collisions_of<CheckedCollisions>(seed);
        EXPECT_EQ(checked.first, lazy.first) << "seed " << seed;
        EXPECT_EQ(checked.second, lazy.second) << "seed " << seed;
        ASSERT_EQ(lazy.first.size(), eager.first.size()) << "seed " << seed;
        for (size_t i = 0; i < lazy.first.size(); ++i)
            EXPECT_TRUE(same_bits(lazy.first[i], eager.first[i])) << "seed " << seed;
        EXPECT_EQ(lazy.second, eager.second) << "seed " << seed;  // the same numbers drawn
        collisions += lazy.first.size();
    }
    EXPECT_GT(collisions, 2000u);
}

TEST(FlightEquivalence, NextFloatUpFromZeroIsTheSmallestSubnormal) {
    for (float zero : {0.0f, -0.0f})
        EXPECT_TRUE(same_bits(next_float_up(zero), std::nextafter(zero, kInfinity)));
}

TEST(FlightEquivalence, OneMediumScatteringWithKnownCoefficientsMatchesTheGeneralSample) {
    HomogeneousMedium h;
    h.sigma_a = Rgb(0.1f, 0.2f, 0.3f);
    h.sigma_s = Rgb(0.7f, 0.5f, 0.9f);
    h.phase = HenyeyGreenstein{0.6f};
    const MediumSet media({Medium{"haze", h}});
    Pcg32 rng(8, 8);
    for (int i = 0; i < 2000; ++i) {
        const Vec3 p(rng.next_float(), rng.next_float(), rng.next_float());
        const Vec3 wo = glm::normalize(Vec3(rng.next_float(), rng.next_float(), 0.1f) - 0.5f);
        const float u_pick = rng.next_float();
        const Vec2 u = rng.next_vec2();
        const PointCoefficients known = media.coefficients(p, 1u);
        const MixtureSample a = media.sample_scattering(p, 1u, wo, u_pick, u, &known);
        const MixtureSample b = media.sample_scattering(p, 1u, wo, u_pick, u, nullptr);
        EXPECT_TRUE(same_bits(a.pdf, b.pdf));
        for (int c = 0; c < 3; ++c) {
            EXPECT_TRUE(same_bits(a.wi[c], b.wi[c]));
            EXPECT_TRUE(same_bits(a.scattering[c], b.scattering[c]));
        }
    }
}

}  // namespace
}  // namespace kasumi
