#include "gi/patch_tree.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

namespace kasumi {

namespace {

float cross2(Vec2 a, Vec2 b) {
    return a.x * b.y - a.y * b.x;
}

/// How far inside the convex polygon p is (the smallest signed edge distance; negative outside).
float inside_score(const PatchNode& node, Vec2 p) {
    float score = kInfinity;
    for (int k = 0; k < node.corner_count; ++k) {
        const Vec2 a = node.uv[k], b = node.uv[(k + 1) % node.corner_count];
        const Vec2 e = b - a;
        const float len = glm::length(e);
        if (len > 0.0f)
            score = std::min(score, cross2(e, p - a) / len);
    }
    return score;
}

}  // namespace

Vec2 local_coordinates(const PatchNode& node, Vec2 uv) {
    if (node.corner_count == 4) {
        const Vec2 lo = node.uv[0], hi = node.uv[2];
        return glm::clamp((uv - lo) / (hi - lo), Vec2(0.0f), Vec2(1.0f));
    }
    const Vec2 a = node.uv[0], e1 = node.uv[1] - a, e2 = node.uv[2] - a, d = uv - a;
    const float det = cross2(e1, e2);
    Vec2 b(cross2(d, e2) / det, cross2(e1, d) / det);
    b = glm::max(b, Vec2(0.0f));
    const float sum = b.x + b.y;
    return sum > 1.0f ? b / sum : b;
}

PatchTree::PatchTree(std::vector<ShapeFace> faces, float patch_size_m) : m_faces(std::move(faces)) {
    for (uint32_t f = 0; f < m_faces.size(); ++f) {
        PatchNode root;
        root.face = f;
        root.corner_count = m_faces[f].vertex_count;
        root.uv = root.corner_count == 4
                      ? std::array<Vec2, 4>{Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)}
                      : std::array<Vec2, 4>{Vec2(0, 0), Vec2(1, 0), Vec2(0, 1), Vec2(0, 0)};
        m_nodes.push_back(root);
    }
    for (uint32_t f = 0; f < m_faces.size(); ++f)
        split_to_size(f, patch_size_m);
    for (PatchNode& node : m_nodes)
        node.refinement = 0;
}

void PatchTree::split_to_size(uint32_t node, float patch_size_m) {
    const FormFactorPatch g = geometry(node);
    double longest = 0.0;
    for (int k = 0; k < g.count; ++k)
        longest = std::max(longest, glm::length(g.vertices[(k + 1) % g.count] - g.vertices[k]));
    if (longest <= patch_size_m || m_nodes[node].depth >= 12)
        return;
    split(node);
    const auto first = static_cast<uint32_t>(m_nodes[node].first_child);
    for (uint32_t c = first; c < first + 4; ++c)
        split_to_size(c, patch_size_m);
}

std::vector<uint32_t> PatchTree::leaves() const {
    std::vector<uint32_t> out;
    for (uint32_t i = 0; i < m_nodes.size(); ++i) {
        if (m_nodes[i].first_child < 0)
            out.push_back(i);
    }
    return out;
}

void PatchTree::split(uint32_t index) {
    const PatchNode parent = m_nodes[index];
    std::array<std::array<Vec2, 4>, 4> children{};
    const auto& c = parent.uv;
    if (parent.corner_count == 4) {
        const Vec2 lo = c[0], hi = c[2], mid = 0.5f * (lo + hi);
        const Vec2 cells[4][2] = {{lo, mid},
                                  {Vec2(mid.x, lo.y), Vec2(hi.x, mid.y)},
                                  {mid, hi},
                                  {Vec2(lo.x, mid.y), Vec2(mid.x, hi.y)}};
        for (int k = 0; k < 4; ++k) {
            const Vec2 a = cells[k][0], b = cells[k][1];
            children[k] = {a, Vec2(b.x, a.y), b, Vec2(a.x, b.y)};
        }
    } else {
        const Vec2 ab = 0.5f * (c[0] + c[1]), bc = 0.5f * (c[1] + c[2]), ca = 0.5f * (c[2] + c[0]);
        // The medial triangle (ab, bc, ca) keeps the parent's orientation.
        children = {
            std::array<Vec2, 4>{c[0], ab, ca, Vec2(0)}, std::array<Vec2, 4>{ab, c[1], bc, Vec2(0)},
            std::array<Vec2, 4>{ca, bc, c[2], Vec2(0)}, std::array<Vec2, 4>{ab, bc, ca, Vec2(0)}};
    }
    const auto first = static_cast<int32_t>(m_nodes.size());
    for (int k = 0; k < 4; ++k) {
        PatchNode child;
        child.face = parent.face;
        child.depth = parent.depth + 1;
        child.refinement = parent.refinement + 1;
        child.corner_count = parent.corner_count;
        child.uv = children[k];
        child.radiance = parent.radiance;
        child.corner.fill(parent.radiance);
        m_nodes.push_back(child);
    }
    m_nodes[index].first_child = first;
}

uint32_t PatchTree::find_leaf(uint32_t face, Vec2 uv) const {
    uint32_t node = face;
    while (m_nodes[node].first_child >= 0) {
        const auto first = static_cast<uint32_t>(m_nodes[node].first_child);
        uint32_t best = first;
        float best_score = -kInfinity;
        for (uint32_t c = first; c < first + 4; ++c) {
            const float score = inside_score(m_nodes[c], uv);
            if (score > best_score) {
                best_score = score;
                best = c;
            }
        }
        node = best;
    }
    return node;
}

FormFactorPatch PatchTree::geometry(uint32_t index) const {
    const PatchNode& node = m_nodes[index];
    Vec3 corners[4];
    for (int k = 0; k < node.corner_count; ++k)
        corners[k] = face_point(m_faces[node.face], node.uv[k]);
    return make_form_factor_patch(corners, node.corner_count);
}

void PatchTree::compute_corners() {
    // Corners sit on dyadic parameters (k / 2^depth): quantising at 2^-24 merges them exactly.
    using Key = std::tuple<uint32_t, int64_t, int64_t>;
    const auto key = [](uint32_t face, Vec2 uv) {
        return Key{face, std::llround(static_cast<double>(uv.x) * 16777216.0),
                   std::llround(static_cast<double>(uv.y) * 16777216.0)};
    };
    std::map<Key, std::pair<Rgb, double>> sums;
    const std::vector<uint32_t> leaf_nodes = leaves();
    for (const uint32_t i : leaf_nodes) {
        const PatchNode& node = m_nodes[i];
        const double area = geometry(i).area;
        for (int k = 0; k < node.corner_count; ++k) {
            auto& s = sums[key(node.face, node.uv[k])];
            s.first += node.radiance * static_cast<float>(area);
            s.second += area;
        }
    }
    for (const uint32_t i : leaf_nodes) {
        PatchNode& node = m_nodes[i];
        for (int k = 0; k < node.corner_count; ++k) {
            const auto& s = sums[key(node.face, node.uv[k])];
            node.corner[k] =
                s.second > 0.0 ? s.first / static_cast<float>(s.second) : node.radiance;
        }
    }
}

Rgb PatchTree::interpolate(uint32_t index, Vec2 uv) const {
    const PatchNode& node = m_nodes[index];
    const Vec2 l = local_coordinates(node, uv);
    if (node.corner_count == 4) {
        return (1.0f - l.x) * (1.0f - l.y) * node.corner[0] + l.x * (1.0f - l.y) * node.corner[1] +
               l.x * l.y * node.corner[2] + (1.0f - l.x) * l.y * node.corner[3];
    }
    return (1.0f - l.x - l.y) * node.corner[0] + l.x * node.corner[1] + l.y * node.corner[2];
}

}  // namespace kasumi
