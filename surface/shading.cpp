#include "surface/shading.h"

#include <algorithm>
#include <cmath>

namespace kasumi {

std::vector<Vec3> angle_weighted_normals(const std::vector<Vec3>& positions,
                                         const std::vector<std::array<uint32_t, 3>>& triangles) {
    std::vector<DVec3> sum(positions.size(), DVec3(0.0));
    for (const auto& tri : triangles) {
        const DVec3 p[3] = {DVec3(positions[tri[0]]), DVec3(positions[tri[1]]),
                            DVec3(positions[tri[2]])};
        const DVec3 cross = glm::cross(p[1] - p[0], p[2] - p[0]);
        const double length = glm::length(cross);
        if (!(length > 0.0))
            continue;
        const DVec3 n = cross / length;
        for (int k = 0; k < 3; ++k) {
            const DVec3 a = p[(k + 1) % 3] - p[k];
            const DVec3 b = p[(k + 2) % 3] - p[k];
            // atan2(|a x b|, a . b) keeps its accuracy for angles near 0 and π, where acos of
            // the normalised dot product does not.
            const double angle = std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
            sum[tri[k]] += angle * n;
        }
    }
    std::vector<Vec3> normals(positions.size());
    for (size_t i = 0; i < sum.size(); ++i) {
        const double length = glm::length(sum[i]);
        normals[i] = length > 1e-12 ? Vec3(sum[i] / length) : Vec3(0.0f, 0.0f, 1.0f);
    }
    return normals;
}

}  // namespace kasumi
