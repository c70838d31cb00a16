#pragma once
/// Shading interpolation across triangles: flat, Gouraud and Phong (Gouraud 1971; Phong 1975),
/// and vertex normals for meshes that come without them.
#include "core/math.h"

#include <array>
#include <cstdint>
#include <vector>

namespace kasumi {

/// How a shape's shading varies across each triangle.
enum class Shading {
    Flat,     ///< the triangle's geometric normal: constant per triangle
    Gouraud,  ///< lighting evaluated at the three vertices (their normals), then interpolated
    Phong,    ///< vertex normals interpolated and renormalised, lighting per hit
};

/// Barycentric interpolation with Embree's coordinates: (1 - u - v) a0 + u a1 + v a2, so
/// (u, v) = (0, 0), (1, 0), (0, 1) give the vertices exactly.
template <typename T>
T interpolate(const std::array<T, 3>& a, float u, float v) {
    return (1.0f - u - v) * a[0] + u * a[1] + v * a[2];
}

/// Unit vertex normals by angle-weighted averaging of the incident triangles' normals
/// (Thürmer & Wüthrich 1998): each triangle counts with its interior angle at the vertex, so
/// the result does not depend on how a surface is split into triangles. Triangles' normals
/// follow their winding, normalize(cross(p1 - p0, p2 - p0)). A vertex whose triangles' normals
/// cancel (or that no triangle uses) gets (0, 0, 1).
std::vector<Vec3> angle_weighted_normals(const std::vector<Vec3>& positions,
                                         const std::vector<std::array<uint32_t, 3>>& triangles);

}  // namespace kasumi
