#pragma once
/// Cached transmittance toward a directional light through a grid medium (`render.volume.
/// light_cache`): the density integral D(x) = integral of density from x toward the light is
/// precomputed once on the grid's own lattice, and a shadow query becomes one trilinear lookup
/// and T = exp(-sigma_t_per_density · D) per channel, instead of a walk to the light.
///
/// The sweep (a slice-by-slice semi-Lagrangian march, as in shadow-volume and deep-shadow
/// caches): slices of the lattice are visited from the one nearest the light; each lattice point
/// p takes D(q) at q = p + one lattice step toward the light (q lies on the previous slice,
/// bilinear there) plus the segment's integral by Simpson's rule (densities at p, the midpoint
/// and q). BIASED, by (1) Simpson's rule on each segment (O(h^4) where the density is smooth,
/// O(h²) at kinks) and (2) the bilinear interpolation repeated slice after slice, which blurs D
/// sideways by about sqrt(n) · h after n slices (shadow edges soften by a fraction of a voxel per
/// slice crossed) and the trilinear lookup between lattice points. Exact for media constant
/// along the light direction. Surfaces are not in the cache (the occlusion query handles them).
#include "core/zeroed_allocator.h"
#include "volume/medium.h"

#include <optional>
#include <vector>

namespace kasumi {

class LightTransmittanceCache {
  public:
    /// `toward_light`: unit world direction from the medium toward the light.
    LightTransmittanceCache(const VdbMedium& medium, const Vec3& toward_light);

    /// Transmittance from world point p toward the light through this medium; nullopt when p is
    /// outside the cached lattice (the caller then walks the ray).
    std::optional<Rgb> transmittance(const Vec3& p) const;

    /// Lattice coordinates of the points o + t d of one world ray, affine in t: u(t) = u0 + t du.
    struct Line {
        Vec3 u0{0.0f};
        Vec3 du{0.0f};
    };
    Line line(const Vec3& origin, const Vec3& direction) const {
        const Vec3 o(m_world_to_index * Vec4(origin, 1.0f));
        const Vec3 d(m_world_to_index * Vec4(direction, 0.0f));
        return {(o - m_lower) / m_cell, d / m_cell};
    }
    /// transmittance(origin + t direction) for the ray of `line` (no 4x4 transform per point;
    /// equal up to rounding).
    std::optional<Rgb> transmittance(const Line& line, float t) const {
        if (m_d.empty())
            return Rgb(1.0f);
        return at_lattice(line.u0 + t * line.du);
    }
    /// The density integral toward the light (density · metres) at the point of `line` at t,
    /// trilinear between lattice points, into `d`; false (d untouched) outside the lattice.
    /// transmittance(line, t) = exp(-sigma_t_per_density() · d): a caller that multiplies it
    /// with another exponential (the marched camera transmittance) adds the exponents instead.
    bool density_integral(const Line& line, float t, float& d) const {
        if (m_d.empty()) {
            d = 0.0f;
            return true;
        }
        return lattice_integral(line.u0 + t * line.du, d);
    }
    /// Extinction per unit density of the cached medium (1/m).
    const Rgb& sigma_t_per_density() const { return m_sigma_t_per_density; }
    /// Density integral toward the light (density · metres) at lattice point (i, j, k).
    float density_integral(int i, int j, int k) const { return m_d[index(i, j, k)]; }
    IVec3 dims() const { return m_dims; }
    /// Lattice spacing in voxels: 1, doubled until the lattice has at most kMaxPoints points
    /// (2 for a 256³ cloud, 4 for 512³): the build then costs well under one image's render.
    float cell() const { return m_cell; }
    static constexpr size_t kMaxPoints = size_t(1) << 19;

  private:
    std::optional<Rgb> at_lattice(const Vec3& u) const;
    bool lattice_integral(const Vec3& u, float& d) const {
        // floor(u) >= 0 iff u >= 0 and floor(u) < n iff u < n (n an integer); in that range
        // the conversion to int (truncation) is the floor.
        if (!(u.x >= 0.0f && u.y >= 0.0f && u.z >= 0.0f && u.x < m_dims.x - 1 &&
              u.y < m_dims.y - 1 && u.z < m_dims.z - 1))
            return false;
        const IVec3 i(u);
        const Vec3 w = u - Vec3(i);
        const size_t dy = static_cast<size_t>(m_dims.x), dz = dy * static_cast<size_t>(m_dims.y);
        const float* v = &m_d[index(i.x, i.y, i.z)];
        const float x00 = v[0] + w.x * (v[1] - v[0]);
        const float x10 = v[dy] + w.x * (v[dy + 1] - v[dy]);
        const float x01 = v[dz] + w.x * (v[dz + 1] - v[dz]);
        const float x11 = v[dz + dy] + w.x * (v[dz + dy + 1] - v[dz + dy]);
        const float y0 = x00 + w.y * (x10 - x00), y1 = x01 + w.y * (x11 - x01);
        d = y0 + w.z * (y1 - y0);
        return true;
    }
    size_t index(int i, int j, int k) const {
        return static_cast<size_t>(i) +
               static_cast<size_t>(m_dims.x) *
                   (static_cast<size_t>(j) + static_cast<size_t>(m_dims.y) * k);
    }

    Mat4 m_world_to_index{1.0f};
    Vec3 m_lower{0.0f};  ///< index-space position of lattice point (0, 0, 0)
    float m_cell = 1.0f;
    IVec3 m_dims{0};
    Rgb m_sigma_t_per_density{0.0f};
    bool m_grey = true;  ///< sigma_t equal in all channels: one exp per query
    std::vector<float, ZeroedAllocator<float>> m_d;  ///< every point written by the build
};

}  // namespace kasumi
