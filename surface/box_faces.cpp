#include "surface/box_faces.h"

namespace kasumi {

std::array<std::array<Vec3, 4>, 6> box_faces(const BoxShape& b) {
    std::array<std::array<Vec3, 4>, 6> faces;
    for (int axis = 0; axis < 3; ++axis) {
        // (axis, u, v) is a cyclic permutation of (x, y, z), so cross(e_u, e_v) = e_axis:
        // corners ordered (0,0), (1,0), (1,1), (0,1) in (u, v) wind counter-clockwise toward
        // +axis; the face at min is wound the other way round so both face outward.
        const int u = (axis + 1) % 3;
        const int v = (axis + 2) % 3;
        for (int side = 0; side < 2; ++side) {
            const float w = side ? b.max[axis] : b.min[axis];
            Vec3 c[4];
            const float uv[4][2] = {{b.min[u], b.min[v]},
                                    {b.max[u], b.min[v]},
                                    {b.max[u], b.max[v]},
                                    {b.min[u], b.max[v]}};
            for (int k = 0; k < 4; ++k) {
                c[k][axis] = w;
                c[k][u] = uv[k][0];
                c[k][v] = uv[k][1];
            }
            faces[2 * axis + side] = side ? std::array<Vec3, 4>{c[0], c[1], c[2], c[3]}
                                          : std::array<Vec3, 4>{c[0], c[3], c[2], c[1]};
        }
    }
    return faces;
}

}  // namespace kasumi
