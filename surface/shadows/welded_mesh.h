#pragma once
/// A box, quad or mesh as an indexed triangle list with vertices welded by exact position, so
/// that triangles sharing an edge share its two indices (boxes: 8 corners, 12 triangles). The
/// triangles keep the order and winding of the shape's triangles in the Embree scene
/// (surface/surface_scene.h): triangle i here is primitive i of a hit on the shape.
#include "core/math.h"
#include "surface/shape.h"

#include <array>
#include <optional>
#include <vector>

namespace kasumi {

/// World space, metres.
struct WeldedMesh {
    std::vector<Vec3> positions;
    std::vector<std::array<uint32_t, 3>> triangles;
};

/// The shape's triangles; nothing for a sphere (no polygons).
std::optional<WeldedMesh> welded_mesh(const Shape& shape);

/// Closed and consistently wound: every directed edge appears once and its reverse once.
bool is_closed(const WeldedMesh& mesh);

}  // namespace kasumi
