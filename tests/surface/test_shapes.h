#pragma once
// Shared by the surface tests: shapes built from their geometry alone (default material).
#include "surface/shape.h"

namespace kasumi {

inline Shape sphere(Vec3 c, float r) {
    Shape s;
    s.geometry = SphereShape{c, r};
    return s;
}
inline Shape box(Vec3 lo, Vec3 hi) {
    Shape s;
    s.geometry = BoxShape{lo, hi};
    return s;
}
inline Shape quad(Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
    Shape s;
    s.geometry = QuadShape{{a, b, c, d}};
    return s;
}

}  // namespace kasumi
