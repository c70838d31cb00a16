#include "volume/light_cache.h"

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <vector>

namespace kasumi {

LightTransmittanceCache::LightTransmittanceCache(const VdbMedium& medium, const Vec3& toward_light)
    : m_world_to_index(medium.world_to_index), m_sigma_t_per_density(medium.sigma_t_per_density()) {
    m_grey = m_sigma_t_per_density.r == m_sigma_t_per_density.g &&
             m_sigma_t_per_density.g == m_sigma_t_per_density.b;
    const DensityGrid& grid = *medium.grid;
    if (grid.empty())
        return;
    m_lower = grid.lower();
    // Lattice spacing in voxels: 1, or 2, 4, ... so the lattice stays within kMaxPoints (the
    // build is one pass of three lookups per point; memory 4 bytes per point).
    const Vec3 extent = grid.upper() - grid.lower();
    m_cell = 1.0f;
    while ((extent.x / m_cell + 1.0f) * (extent.y / m_cell + 1.0f) * (extent.z / m_cell + 1.0f) >
           static_cast<float>(kMaxPoints))
        m_cell *= 2.0f;
    m_dims = IVec3(glm::ceil(extent / m_cell)) + IVec3(1);
    // Zeroed pages, no fill; at least 2 MiB reserved, so the allocator maps them as one
    // transparent huge page (one page fault instead of one per 4 KiB as the sweep writes them).
    const size_t points = static_cast<size_t>(m_dims.x) * m_dims.y * m_dims.z;
    m_d.reserve(std::max(points, decltype(m_d)::allocator_type::kHugePage / sizeof(float)));
    m_d.resize(points);

    // One lattice step toward the light along the major axis a of the index-space direction.
    const Vec3 d_index(m_world_to_index * Vec4(toward_light, 0.0f));
    int a = 0;
    for (int c = 1; c < 3; ++c)
        if (std::abs(d_index[c]) > std::abs(d_index[a]))
            a = c;
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    const Vec3 step = d_index * (m_cell / std::abs(d_index[a]));  // index units, |step[a]| = cell
    const float length_m = m_cell / std::abs(d_index[a]);         // metres per step
    const int toward = step[a] > 0.0f ? 1 : -1;                   // slice index change toward light
    const int first = toward > 0 ? m_dims[a] - 1 : 0;             // slice nearest the light

    auto at = [&](IVec3 p) -> float& { return m_d[index(p.x, p.y, p.z)]; };
    // D at q is bilinear on the upstream slice at (p[b] + step[b] / cell, p[c] + step[c] /
    // cell): the lower corner and the weights depend on p[b] alone along b and on p[c] alone
    // along c, so they are computed once per column and per row (the same float operations as
    // per point: the cache is bit-identical to the per-point form). A corner outside the
    // lattice adds nothing (the ray has left the box, which it never re-enters).
    // Each corner's offset in the upstream slice along the axis and its weight; a corner
    // outside the lattice gets weight 0 (and an offset inside): its term 0 · w · D = +0 adds
    // nothing, bit for bit what skipping it did (D >= 0, finite), without a branch.
    struct Axis {
        size_t offset[2];  ///< lattice offsets of i0 and i0 + 1 (clamped into the lattice)
        float w[2];        ///< weights of i0 and i0 + 1; 0 outside the lattice
    };
    const size_t stride[3] = {1, static_cast<size_t>(m_dims.x),
                              static_cast<size_t>(m_dims.x) * static_cast<size_t>(m_dims.y)};
    const auto axis_table = [&](int axis) {
        std::vector<Axis> table(static_cast<size_t>(m_dims[axis]));
        for (int i = 0; i < m_dims[axis]; ++i) {
            const float u = static_cast<float>(i) + step[axis] / m_cell;
            const float fu = std::floor(u);
            const int iu = static_cast<int>(fu);
            const float tu = u - fu;
            Axis& e = table[static_cast<size_t>(i)];
            const float w[2] = {1.0f - tu, tu};
            for (int k = 0; k < 2; ++k) {
                const bool in = iu + k >= 0 && iu + k < m_dims[axis];
                e.w[k] = in ? w[k] : 0.0f;
                e.offset[k] =
                    static_cast<size_t>(std::clamp(iu + k, 0, m_dims[axis] - 1)) * stride[axis];
            }
        }
        return table;
    };
    const std::vector<Axis> along_b = axis_table(b), along_c = axis_table(c);
    // The three densities of a point (at x, the midpoint x + step / 2 and q = x + step) are
    // grid lookups whose coordinates, axis by axis, depend on that axis's lattice index alone
    // (x = lower + cell p per component): they are split once per lattice index and axis
    // (DensityGrid::axis_split) and combined per point, the same bits as grid.density(x) of
    // the whole point. x lies on voxels (integer index coordinates: fraction 0 on every axis)
    // and so do the midpoint and q along a when the step there is a whole number of voxels
    // (cell >= 2): those lookups skip the interpolation along such axes (same bits).
    using Split = DensityGrid::AxisSplit;
    std::vector<Split> split_x[3], split_m[3], split_q[3];
    bool x_on_voxels = true, m_q_flat_along_a = true;
    for (int axis = 0; axis < 3; ++axis) {
        for (int i = 0; i < m_dims[axis]; ++i) {
            // The expressions of the per-point form, component by component.
            const float x = m_lower[axis] + m_cell * static_cast<float>(i);
            split_x[axis].push_back(grid.axis_split(axis, x));
            split_m[axis].push_back(grid.axis_split(axis, x + 0.5f * step[axis]));
            split_q[axis].push_back(grid.axis_split(axis, x + step[axis]));
            x_on_voxels = x_on_voxels && split_x[axis].back().f == 0.0f;
            if (axis == a)
                m_q_flat_along_a = m_q_flat_along_a && split_m[axis].back().f == 0.0f &&
                                   split_q[axis].back().f == 0.0f;
        }
    }
    // The slices' axis a as a template argument (so are b, c and the loop order: the point's
    // coordinates stay in registers), and which lookups lie on voxels.
    const auto sweep = [&](auto axis_a, auto flat_x, auto flat_a) {
        constexpr int A = decltype(axis_a)::value, B = (A + 1) % 3, C = (A + 2) % 3;
        constexpr unsigned kFlatX = decltype(flat_x)::value, kFlatA = decltype(flat_a)::value;
        // Within a slice every point reads only the upstream slice, so the order of the two
        // inner loops is free: the innermost runs along the lower axis (x before y before z),
        // the one along which both this lattice and the grid's bricks (numbered x fastest) are
        // contiguous.
        constexpr int kInner = B < C ? B : C, kOuter = B < C ? C : B;
        const Split* sx[3];
        const Split* sm[3];
        const Split* sq[3];
        for (int axis = 0; axis < 3; ++axis) {
            sx[axis] = split_x[axis].data();
            sm[axis] = split_m[axis].data();
            sq[axis] = split_q[axis].data();
        }
        // The split of axis K among the slice's (along A), the row's and the point's.
        const auto pick = [](auto k, const Split& along_a, const Split& outer,
                             const Split& inner) -> const Split& {
            constexpr int K = decltype(k)::value;
            if constexpr (K == A)
                return along_a;
            else if constexpr (K == kOuter)
                return outer;
            else
                return inner;
        };
        using K0 = std::integral_constant<int, 0>;
        using K1 = std::integral_constant<int, 1>;
        using K2 = std::integral_constant<int, 2>;
        const Axis* const table_b = along_b.data();
        const Axis* const table_c = along_c.data();
        for (int slice = first; slice >= 0 && slice < m_dims[A]; slice -= toward) {
            const int upstream = slice + toward;
            const bool inside = upstream >= 0 && upstream < m_dims[A];
            const float* row = m_d.data() + static_cast<size_t>(inside ? upstream : 0) * stride[A];
            const Split xa = sx[A][slice], ma = sm[A][slice], qa = sq[A][slice];
            IVec3 p(0);
            p[A] = slice;
            for (p[kOuter] = 0; p[kOuter] < m_dims[kOuter]; ++p[kOuter]) {
                const Split xo = sx[kOuter][p[kOuter]], mo = sm[kOuter][p[kOuter]],
                            qo = sq[kOuter][p[kOuter]];
                float* out = &at(p);
                for (int i = 0; i < m_dims[kInner]; ++i) {
                    const Split& xi = sx[kInner][i];
                    const Split& mi = sm[kInner][i];
                    const Split& qi = sq[kInner][i];
                    const float rho_p = grid.density_split<kFlatX>(
                        pick(K0{}, xa, xo, xi), pick(K1{}, xa, xo, xi), pick(K2{}, xa, xo, xi));
                    const float rho_m = grid.density_split<kFlatA>(
                        pick(K0{}, ma, mo, mi), pick(K1{}, ma, mo, mi), pick(K2{}, ma, mo, mi));
                    const float rho_q = grid.density_split<kFlatA>(
                        pick(K0{}, qa, qo, qi), pick(K1{}, qa, qo, qi), pick(K2{}, qa, qo, qi));
                    float upstream_d = 0.0f;
                    if (inside) {
                        const int pb = B == kInner ? i : p[kOuter],
                                  pc = C == kInner ? i : p[kOuter];
                        const Axis& eu = table_b[static_cast<size_t>(pb)];
                        const Axis& ev = table_c[static_cast<size_t>(pc)];
                        for (int dv = 0; dv < 2; ++dv)
                            for (int du = 0; du < 2; ++du)
                                upstream_d +=
                                    eu.w[du] * ev.w[dv] * row[eu.offset[du] + ev.offset[dv]];
                    }
                    out[static_cast<size_t>(i) * stride[kInner]] =
                        upstream_d + length_m * (rho_p + 4.0f * rho_m + rho_q) * (1.0f / 6.0f);
                }
            }
        }
    };
    using Flat0 = std::integral_constant<unsigned, 0u>;
    using Flat7 = std::integral_constant<unsigned, 7u>;
    using X = std::integral_constant<int, 0>;
    using Y = std::integral_constant<int, 1>;
    using Z = std::integral_constant<int, 2>;
    const bool flat = x_on_voxels && m_q_flat_along_a;  // not at cell 1: midpoints off voxels
    if (a == 0)
        flat ? sweep(X{}, Flat7{}, std::integral_constant<unsigned, 1u>{})
             : sweep(X{}, Flat0{}, Flat0{});
    else if (a == 1)
        flat ? sweep(Y{}, Flat7{}, std::integral_constant<unsigned, 2u>{})
             : sweep(Y{}, Flat0{}, Flat0{});
    else
        flat ? sweep(Z{}, Flat7{}, std::integral_constant<unsigned, 4u>{})
             : sweep(Z{}, Flat0{}, Flat0{});
}

std::optional<Rgb> LightTransmittanceCache::transmittance(const Vec3& p_world) const {
    if (m_d.empty())
        return Rgb(1.0f);
    return at_lattice((Vec3(m_world_to_index * Vec4(p_world, 1.0f)) - m_lower) / m_cell);
}

std::optional<Rgb> LightTransmittanceCache::at_lattice(const Vec3& u) const {
    float d = 0.0f;
    if (!lattice_integral(u, d))
        return std::nullopt;
    if (m_grey)
        return Rgb(std::exp(-m_sigma_t_per_density.r * d));
    return exp_neg(m_sigma_t_per_density * d);
}

}  // namespace kasumi
