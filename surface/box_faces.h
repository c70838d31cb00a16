#pragma once
/// The six faces of an axis-aligned box as quads, the one winding every box consumer shares
/// (Embree triangles, shadow-volume meshes, radiosity patches).
#include "surface/shape.h"

#include <array>

namespace kasumi {

/// Faces in the order (axis x, y, z) × (min side, max side), each wound counter-clockwise seen
/// from outside, so cross(c1 - c0, c2 - c0) points out of the box. World space, metres.
std::array<std::array<Vec3, 4>, 6> box_faces(const BoxShape& b);

}  // namespace kasumi
