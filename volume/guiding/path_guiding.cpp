#include "volume/guiding/path_guiding.h"

namespace kasumi {

void GuidingPathRecorder::record_vertex(const Vec3& position, const Vec3& wi, float pdf_sr,
                                        const Rgb& throughput) {
    if (m_count >= kMaxVertices)
        return;
    m_vertices[static_cast<size_t>(m_count++)] =
        Vertex{position, wi, pdf_sr, throughput, Rgb(0.0f)};
}

void GuidingPathRecorder::record_radiance(const Rgb& contribution) {
    for (int i = 0; i < m_count; ++i) {
        Vertex& v = m_vertices[static_cast<size_t>(i)];
        for (int c = 0; c < 3; ++c) {
            if (v.throughput[c] > 0.0f)
                v.incident[c] += contribution[c] / v.throughput[c];
        }
    }
}

void GuidingPathRecorder::flush() {
    for (int i = 0; i < m_count; ++i) {
        const Vertex& v = m_vertices[static_cast<size_t>(i)];
        const float weight = v.pdf > 0.0f ? luminance(v.incident) / v.pdf : 0.0f;
        m_records->push_back({v.position, v.wi, std::isfinite(weight) ? weight : 0.0f});
    }
    m_count = 0;
}

}  // namespace kasumi
