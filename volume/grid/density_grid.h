#pragma once
/// Our hot-loop copy of a sparse density grid: the non-zero region of a voxel grid stored as
/// dense 8³ bricks, each with a one-voxel apron so a trilinear lookup reads one brick, and with
/// the exact maximum and minimum of the interpolated density per brick (majorant and minorant
/// for the trackers). Empty bricks take no voxel storage and are skipped by the brick DDA.
///
/// Index space follows OpenVDB: voxel (i, j, k) holds its value at the index-space point
/// (i, j, k); between voxel centres the density is trilinear. Voxels never set are 0.
#include "core/math.h"
#include "core/zeroed_allocator.h"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>
#include <utility>
#include <vector>

namespace kasumi {

using IVec3 = glm::ivec3;

/// One stretch [t0, t1] of a ray inside one non-empty brick, with bounds of the density there.
struct BrickSpan {
    float t0 = 0.0f;
    float t1 = 0.0f;
    float density_max = 0.0f;  ///< >= every trilinear density value inside the brick
    float density_min = 0.0f;  ///< <= every trilinear density value inside the brick
};

/// One allocated brick as the trackers see it: its 9³ voxels and the index-space position of
/// its voxel (0, 0, 0), so a lookup inside it needs no brick-table read.
struct BrickRef {
    const float* voxels = nullptr;
    Vec3 lower{0.0f};
};

class DensityGrid {
  public:
    static constexpr int kBrick = 8;            ///< cells per brick edge
    static constexpr int kStored = kBrick + 1;  ///< voxels per stored brick edge (with apron)
    static constexpr int kBrickVoxels = kStored * kStored * kStored;

    DensityGrid() = default;
    /// An empty grid able to hold voxels with indices in [index_min, index_max] (inclusive).
    DensityGrid(IVec3 index_min, IVec3 index_max);

    /// Sets voxel `index` (within the constructor's box) to `value`. Build time only.
    void set(IVec3 index, float value);
    /// Computes the per-brick bounds; call once after the last `set`.
    void finalize();

    /// Trilinear density at an index-space point; 0 outside the stored region. Never throws.
    float density(const Vec3& p_index) const {
        IVec3 l;
        Vec3 f;
        const float* brick = locate(p_index, l, f);
        return brick != nullptr ? trilinear(brick, l, f) : 0.0f;
    }

    /// One coordinate of a lookup point as density() splits it, for a caller that looks up many
    /// points sharing coordinates (the light cache's sweep: every lattice row and column repeats
    /// its coordinates): density_split(axis_split(0, p.x), axis_split(1, p.y), axis_split(2,
    /// p.z)) equals density(p) bit for bit.
    struct AxisSplit {
        size_t slot = 0;      ///< brick coordinate times the brick table's stride on this axis
        int offset = 0;       ///< voxel coordinate within the brick times its stride
        float f = 0.0f;       ///< fraction within the cell
        bool inside = false;  ///< within the stored region on this axis
    };
    AxisSplit axis_split(int axis, float p_index) const {
        AxisSplit s;
        const float q = p_index - m_origin_f[axis];
        s.inside = q >= 0.0f && q < m_cells_f[axis];
        if (!s.inside)
            return s;
        const int c = static_cast<int>(q);  // q >= 0: truncation is the floor
        const size_t stride[3] = {
            1, static_cast<size_t>(m_bricks.x),
            static_cast<size_t>(m_bricks.x) * static_cast<size_t>(m_bricks.y)};
        const int voxel_stride[3] = {1, kStored, kStored * kStored};
        s.slot = static_cast<size_t>(c >> 3) * stride[axis];
        s.offset = (c & (kBrick - 1)) * voxel_stride[axis];
        s.f = q - static_cast<float>(c);
        return s;
    }
    /// density() at the point of three splits. `Flat` (bit a for axis a) names axes whose
    /// fraction the caller knows to be 0: their interpolation is skipped, which gives the same
    /// bits (a + 0 · (b - a) = a for the finite, non-negative, never -0 voxels a grid holds)
    /// with fewer loads (all three flat: one voxel).
    template <unsigned Flat = 0>
    float density_split(const AxisSplit& x, const AxisSplit& y, const AxisSplit& z) const {
        if (!(x.inside && y.inside && z.inside))
            return 0.0f;
        const int32_t brick = m_brick_index[x.slot + y.slot + z.slot];
        if (brick < 0)
            return 0.0f;
        const float* v =
            &m_voxels[static_cast<size_t>(brick) * kBrickVoxels] + x.offset + y.offset + z.offset;
        return trilinear_flat<Flat>(v, x.f, y.f, z.f);
    }

    /// Asks the processor to start loading the voxels a lookup at p_index will read (the brick
    /// table entry is read now): a march calls it a node or two ahead so the lookup finds them
    /// in cache. Reads nothing else and changes nothing; no effect where nothing is stored.
    void prefetch(const Vec3& p_index) const {
        const Vec3 q = p_index - m_origin_f;
        if (!(q.x >= 0.0f && q.y >= 0.0f && q.z >= 0.0f && q.x < m_cells_f.x && q.y < m_cells_f.y &&
              q.z < m_cells_f.z))
            return;
        const IVec3 c(q);
        const int32_t brick = m_brick_index[brick_slot(c >> 3)];
        if (brick < 0)
            return;
        const IVec3 l = c & (kBrick - 1);
        prefetch_cell(&m_voxels[static_cast<size_t>(brick) * kBrickVoxels] +
                      (l.x + kStored * (l.y + kStored * l.z)));
    }

    /// Trilinear density at an index-space point known to lie in brick `b` (the brick a walk
    /// visit names). A point a rounding error outside the brick is clamped onto its faces, so
    /// the value always lies within the brick's bounds. Never throws.
    static float density_in(const BrickRef& b, const Vec3& p_index) {
        const Vec3 q = glm::clamp(p_index - b.lower, Vec3(0.0f), Vec3(static_cast<float>(kBrick)));
        // q >= 0 after the clamp, where truncation to int is the floor.
        const IVec3 l = glm::min(IVec3(q), IVec3(kBrick - 1));
        return trilinear(b.voxels, l, q - Vec3(l));
    }

    /// Stochastic (one-voxel) trilinear filtering (Pharr, Wronski, Salvi & Fajardo 2024,
    /// "Filtering After Shading With Stochastic Texture Filtering"): one of the 8 voxels of the
    /// trilinear cell density_in(b, p_index) reads, voxel c picked with probability equal to its
    /// trilinear weight, so E[density_in_stochastic] = density_in over uniform `bits`. Per axis
    /// a, the upper voxel is taken when 21 bits of `bits` (a uniform in [0, 1) on a 2^-21 grid)
    /// fall below the fraction f_a: each weight is off by less than 2^-21, a bias below
    /// 3 * 2^-21 of the cell's largest voxel difference. The value is a voxel of the cell, so it
    /// lies within the brick's (and the cell's) bounds like the trilinear one; a fraction of 0
    /// (a point on a cell face) never picks the far voxel. Never throws.
    static float density_in_stochastic(const BrickRef& b, const Vec3& p_index, uint64_t bits) {
        const Vec3 q = glm::clamp(p_index - b.lower, Vec3(0.0f), Vec3(static_cast<float>(kBrick)));
        const IVec3 l = glm::min(IVec3(q), IVec3(kBrick - 1));
        return pick_voxel(b.voxels, l, q - Vec3(l), bits);
    }
    /// density() filtered stochastically (density_in_stochastic): unbiased for density() over
    /// uniform `bits`. 0 outside the stored region. Never throws.
    float density_stochastic(const Vec3& p_index, uint64_t bits) const {
        IVec3 l;
        Vec3 f;
        const float* brick = locate(p_index, l, f);
        return brick != nullptr ? pick_voxel(brick, l, f, bits) : 0.0f;
    }

    /// Walks the index-space ray o + t d, t in [t0, t1], in order through the non-empty bricks
    /// (3D DDA over bricks, Amanatides & Woo 1987), calling
    /// visit(const BrickSpan& span, const BrickRef& brick) for each. Stops, returning false, as
    /// soon as visit returns false: nothing past that point is walked (bricks_along lists the
    /// whole ray first). t keeps the caller's units.
    template <class Visit>
    bool walk(const Vec3& o_index, const Vec3& d_index, float t0, float t1, Visit&& visit) const;

    /// Appends, in order, the spans of the index-space ray o + t d, t in [t0, t1], that lie in
    /// non-empty bricks (3D DDA over bricks, Amanatides & Woo 1987). t keeps the caller's units.
    void bricks_along(const Vec3& o_index, const Vec3& d_index, float t0, float t1,
                      std::vector<BrickSpan>& out) const;

    bool empty() const { return m_allocated == 0; }
    /// Largest density anywhere.
    float max_density() const { return m_max_density; }
    size_t allocated_bricks() const { return m_allocated; }
    size_t total_bricks() const { return m_brick_index.size(); }
    /// Index-space box that can hold non-zero density: [lower, upper].
    Vec3 lower() const { return m_origin_f; }
    Vec3 upper() const { return m_origin_f + Vec3(m_bricks * kBrick); }

  private:
    friend class DensityGridBuilder;  // volume/grid/density_grid_build.h: parallel construction

    /// The stored voxels of the brick holding index-space point p_index, with the local index l
    /// of its cell and the fractions f within it; null (l, f untouched) outside the stored
    /// region or in an empty brick.
    const float* locate(const Vec3& p_index, IVec3& l, Vec3& f) const {
        const Vec3 q = p_index - m_origin_f;
        // floor(q) >= 0 iff q >= 0, and floor(q) < n iff q < n for an integer n; in that range
        // the integer conversion (truncation) is the floor, without a rounding-mode dance.
        if (!(q.x >= 0.0f && q.y >= 0.0f && q.z >= 0.0f && q.x < m_cells_f.x && q.y < m_cells_f.y &&
              q.z < m_cells_f.z))
            return nullptr;
        const IVec3 c(q);
        const int32_t brick = m_brick_index[brick_slot(c >> 3)];
        if (brick < 0)
            return nullptr;
        l = c & (kBrick - 1);
        f = q - Vec3(c);
        return &m_voxels[static_cast<size_t>(brick) * kBrickVoxels];
    }
    /// Prefetches the cache lines of the trilinear cell whose voxel (0, 0, 0) is at v: its four
    /// x-rows (two voxels each) at +0, +dy, +dz and +dy+dz.
    static void prefetch_cell(const float* v) {
#if defined(__GNUC__) || defined(__clang__)
        constexpr int dy = kStored, dz = kStored * kStored;
        __builtin_prefetch(v);
        __builtin_prefetch(v + dy + 1);
        __builtin_prefetch(v + dz);
        __builtin_prefetch(v + dz + dy + 1);
#else
        (void)v;
#endif
    }
    // volume/grid/density_grid_build.h: parallel construction

    /// Trilinear interpolation in the cell at local index l of a brick's 9³ voxels, fractions f.
    static float trilinear(const float* brick, IVec3 l, Vec3 f) {
        const float* v = brick + (l.x + kStored * (l.y + kStored * l.z));
        constexpr int dy = kStored, dz = kStored * kStored;
        const float x00 = v[0] + f.x * (v[1] - v[0]);
        const float x10 = v[dy] + f.x * (v[dy + 1] - v[dy]);
        const float x01 = v[dz] + f.x * (v[dz + 1] - v[dz]);
        const float x11 = v[dz + dy] + f.x * (v[dz + dy + 1] - v[dz + dy]);
        const float y0 = x00 + f.y * (x10 - x00);
        const float y1 = x01 + f.y * (x11 - x01);
        return y0 + f.z * (y1 - y0);
    }
    /// The voxel of the cell at local index l that a stochastic trilinear lookup at fractions f
    /// takes with 63 random bits (density_in_stochastic).
    static float pick_voxel(const float* brick, IVec3 l, Vec3 f, uint64_t bits) {
        constexpr uint64_t kMask = (uint64_t{1} << 21) - 1;
        constexpr float kUnit = 1.0f / static_cast<float>(uint64_t{1} << 21);
        const int ux = static_cast<float>(bits & kMask) * kUnit < f.x;
        const int uy = static_cast<float>((bits >> 21) & kMask) * kUnit < f.y;
        const int uz = static_cast<float>((bits >> 42) & kMask) * kUnit < f.z;
        return brick[(l.x + ux) + kStored * ((l.y + uy) + kStored * (l.z + uz))];
    }
    /// trilinear() at the cell whose voxel (0, 0, 0) is at v, without the interpolation along
    /// the axes in `Flat` (their fraction is 0): the same operations on the rest, so the same
    /// bits (see density_split).
    template <unsigned Flat>
    static float trilinear_flat(const float* v, float fx, float fy, float fz) {
        constexpr int dy = kStored, dz = kStored * kStored;
        constexpr bool flat_x = Flat & 1u, flat_y = Flat & 2u, flat_z = Flat & 4u;
        const auto along_x = [&](int o) {
            if constexpr (flat_x)
                return v[o];
            else
                return v[o] + fx * (v[o + 1] - v[o]);
        };
        const float x00 = along_x(0);
        float y0 = x00;
        if constexpr (!flat_y) {
            const float x10 = along_x(dy);
            y0 = x00 + fy * (x10 - x00);
        }
        if constexpr (flat_z) {
            return y0;
        } else {
            const float x01 = along_x(dz);
            float y1 = x01;
            if constexpr (!flat_y) {
                const float x11 = along_x(dz + dy);
                y1 = x01 + fy * (x11 - x01);
            }
            return y0 + fz * (y1 - y0);
        }
    }
    size_t brick_slot(IVec3 b) const {
        return static_cast<size_t>(b.x) +
               static_cast<size_t>(m_bricks.x) *
                   (static_cast<size_t>(b.y) + static_cast<size_t>(m_bricks.y) * b.z);
    }
    float* brick_voxels(IVec3 b);

    IVec3 m_origin{0};  ///< index of the lower corner of brick (0, 0, 0)
    Vec3 m_origin_f{0.0f};
    IVec3 m_bricks{0};  ///< bricks per axis
    Vec3 m_cells_f{0.0f};
    std::vector<int32_t> m_brick_index;  ///< per brick slot: storage index, or -1 (all zero)
    std::vector<float, ZeroedAllocator<float>> m_voxels;  ///< kBrickVoxels per allocated brick
    std::vector<float> m_brick_max;                       ///< per brick slot
    std::vector<float> m_brick_min;                       ///< per brick slot
    size_t m_allocated = 0;
    float m_max_density = 0.0f;
};

template <class Visit>
bool DensityGrid::walk(const Vec3& o_index, const Vec3& d_index, float t0, float t1,
                       Visit&& visit) const {
    if (m_allocated == 0 || !(t1 > t0))
        return true;
    // Brick space: brick b covers [b, b + 1) per axis.
    const Vec3 p = (o_index - m_origin_f) * (1.0f / kBrick);
    const Vec3 d = d_index * (1.0f / kBrick);
    const Vec3 n(m_bricks);
    float ta = t0, tb = t1;
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0.0f) {
            if (!(p[a] >= 0.0f && p[a] < n[a]))
                return true;
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
        return true;
    // Truncation is the floor for q >= 0, and both clamp to 0 below.
    IVec3 cell = glm::clamp(IVec3(p + d * ta), IVec3(0), m_bricks - IVec3(1));
    IVec3 step(0);
    Vec3 t_next(kInfinity), t_delta(0.0f);
    // The brick slot follows the cell: a step along axis a moves it by +-stride[a].
    const ptrdiff_t stride[3] = {1, m_bricks.x, static_cast<ptrdiff_t>(m_bricks.x) * m_bricks.y};
    ptrdiff_t slot_step[3] = {0, 0, 0};
    for (int a = 0; a < 3; ++a) {
        if (d[a] > 0.0f) {
            step[a] = 1;
            slot_step[a] = stride[a];
            t_next[a] = (static_cast<float>(cell[a] + 1) - p[a]) / d[a];
            t_delta[a] = 1.0f / d[a];
        } else if (d[a] < 0.0f) {
            step[a] = -1;
            slot_step[a] = -stride[a];
            t_next[a] = (static_cast<float>(cell[a]) - p[a]) / d[a];
            t_delta[a] = -1.0f / d[a];
        }
    }
    ptrdiff_t slot = static_cast<ptrdiff_t>(brick_slot(cell));
    // One step along an axis: false when it leaves the grid. Called with each axis's own
    // members (no indexing by a run-time axis), so the walk's state stays in registers.
    const auto advance = [&slot](int& c, int s, int cells, ptrdiff_t ds, float& tn, float dt) {
        c += s;
        if (c < 0 || c >= cells)
            return false;
        slot += ds;
        tn += dt;
        return true;
    };
    for (float t = ta; t < tb;) {
        const int axis =
            t_next.x <= t_next.y ? (t_next.x <= t_next.z ? 0 : 2) : (t_next.y <= t_next.z ? 1 : 2);
        const float t_exit = std::min(axis == 0 ? t_next.x : (axis == 1 ? t_next.y : t_next.z), tb);
        const int32_t storage = m_brick_index[static_cast<size_t>(slot)];
        if (storage >= 0 && t_exit > t) {
            const BrickRef brick{&m_voxels[static_cast<size_t>(storage) * kBrickVoxels],
                                 m_origin_f + Vec3(cell * kBrick)};
            if (!visit(BrickSpan{t, t_exit, m_brick_max[static_cast<size_t>(slot)],
                                 m_brick_min[static_cast<size_t>(slot)]},
                       brick))
                return false;
        }
        t = std::max(t, t_exit);
        const bool inside =
            axis == 0   ? advance(cell.x, step.x, m_bricks.x, slot_step[0], t_next.x, t_delta.x)
            : axis == 1 ? advance(cell.y, step.y, m_bricks.y, slot_step[1], t_next.y, t_delta.y)
                        : advance(cell.z, step.z, m_bricks.z, slot_step[2], t_next.z, t_delta.z);
        if (!inside)
            break;
    }
    return true;
}

}  // namespace kasumi
