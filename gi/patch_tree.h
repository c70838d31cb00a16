#pragma once
/// Radiosity patches as a forest of subdivision trees, one per face (gi/patch_faces.h):
/// a quad splits into four at its parameter midpoints, a triangle into four at its edge
/// midpoints. The leaves are the unknowns of the radiosity system; the tree finds the leaf under
/// a hit and gives each leaf the radiance at its corners (Gouraud interpolation, Gouraud 1971:
/// a corner's value is the area-weighted mean of the leaves that share it).
#include "core/color.h"
#include "gi/form_factor.h"
#include "gi/patch_faces.h"

#include <array>
#include <cstdint>
#include <vector>

namespace kasumi {

struct PatchNode {
    uint32_t face = 0;   ///< index into the tree's faces
    int depth = 0;       ///< splits below the face
    int refinement = 0;  ///< adaptive splits beyond the face's uniform (coarse) level
    int corner_count = 4;
    std::array<Vec2, 4> uv{};     ///< corners in face parameters, counter-clockwise
    int32_t first_child = -1;     ///< four consecutive children, or -1 for a leaf
    Rgb radiance{0.0f};           ///< leaf: reflected + emitted radiance, cd/m²
    std::array<Rgb, 4> corner{};  ///< leaf: Gouraud radiance at the corners
};

class PatchTree {
  public:
    /// One root per face, split uniformly until every edge is at most `patch_size_m`.
    PatchTree(std::vector<ShapeFace> faces, float patch_size_m);

    const std::vector<ShapeFace>& faces() const { return m_faces; }
    const std::vector<PatchNode>& nodes() const { return m_nodes; }
    std::vector<PatchNode>& nodes() { return m_nodes; }
    /// Indices of the leaf nodes, in node order.
    std::vector<uint32_t> leaves() const;
    /// Splits leaf `node` into four children (each inherits its radiance).
    void split(uint32_t node);
    /// The leaf of face `face` containing face parameters uv (the nearest if uv is outside).
    uint32_t find_leaf(uint32_t face, Vec2 uv) const;
    /// The node's polygon in world space (3 or 4 corners, the face's winding).
    FormFactorPatch geometry(uint32_t node) const;
    /// Sets every leaf's corner radiance to the area-weighted mean of the leaves of the same
    /// face sharing that corner.
    void compute_corners();
    /// Radiance at uv inside leaf `node`: bilinear (quads) or barycentric (triangles)
    /// interpolation of its corner values.
    Rgb interpolate(uint32_t node, Vec2 uv) const;

  private:
    void split_to_size(uint32_t node, float patch_size_m);

    std::vector<ShapeFace> m_faces;
    std::vector<PatchNode> m_nodes;  ///< roots are nodes 0 .. faces - 1
};

/// Local coordinates of uv in a leaf's parameter polygon: (s, t) in [0, 1]² of the bilinear
/// quad, or the barycentric (b1, b2) of the triangle.
Vec2 local_coordinates(const PatchNode& node, Vec2 uv);

}  // namespace kasumi
