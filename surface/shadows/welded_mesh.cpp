#include "surface/shadows/welded_mesh.h"

#include "surface/box_faces.h"

#include <map>
#include <tuple>

namespace kasumi {

namespace {

class Welder {
  public:
    explicit Welder(WeldedMesh& mesh) : m_mesh(mesh) {}
    uint32_t index(const Vec3& p) {
        const auto key = std::make_tuple(p.x, p.y, p.z);
        const auto it = m_index.find(key);
        if (it != m_index.end())
            return it->second;
        const auto i = static_cast<uint32_t>(m_mesh.positions.size());
        m_mesh.positions.push_back(p);
        m_index.emplace(key, i);
        return i;
    }
    void triangle(const Vec3& a, const Vec3& b, const Vec3& c) {
        m_mesh.triangles.push_back({index(a), index(b), index(c)});
    }
    /// The Embree scene's split of a quad: (a, b, c) and (a, c, d).
    void quad(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
        triangle(a, b, c);
        triangle(a, c, d);
    }

  private:
    WeldedMesh& m_mesh;
    std::map<std::tuple<float, float, float>, uint32_t> m_index;
};

}  // namespace

std::optional<WeldedMesh> welded_mesh(const Shape& shape) {
    WeldedMesh mesh;
    Welder weld(mesh);
    if (const auto* box = std::get_if<BoxShape>(&shape.geometry)) {
        for (const std::array<Vec3, 4>& c : box_faces(*box))
            weld.quad(c[0], c[1], c[2], c[3]);
    } else if (const auto* quad = std::get_if<QuadShape>(&shape.geometry)) {
        weld.quad(quad->vertices[0], quad->vertices[1], quad->vertices[2], quad->vertices[3]);
    } else if (const auto* m = std::get_if<MeshShape>(&shape.geometry)) {
        for (const auto& t : m->mesh.triangles)
            weld.triangle(m->mesh.positions[t[0]], m->mesh.positions[t[1]],
                          m->mesh.positions[t[2]]);
    } else {
        return std::nullopt;
    }
    return mesh;
}

bool is_closed(const WeldedMesh& mesh) {
    using Edge = std::pair<uint32_t, uint32_t>;
    std::map<Edge, int> edges;
    for (const auto& t : mesh.triangles)
        for (int k = 0; k < 3; ++k)
            ++edges[{t[k], t[(k + 1) % 3]}];
    for (const auto& [edge, n] : edges) {
        const auto reverse = edges.find({edge.second, edge.first});
        if (n != 1 || reverse == edges.end() || reverse->second != 1)
            return false;
    }
    return true;
}

}  // namespace kasumi
