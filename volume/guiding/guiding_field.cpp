#include "volume/guiding/guiding_field.h"

#include "phase/phase_sample.h"

#include <algorithm>
#include <cmath>

namespace kasumi {

namespace {

/// Deeper than this the box of a 10 km cloud is a 1 cm cell: enough for any record count.
constexpr int kMaxDepth = 20;

}  // namespace

GuidingField::GuidingField(const std::vector<GuidingRecord>& records, int leaf_records,
                           float uniform) {
    if (records.empty())
        return;
    for (const GuidingRecord& r : records)
        m_box.extend(r.position);
    std::vector<GuidingRecord> sorted = records;
    m_nodes.reserve(2 * records.size() / static_cast<size_t>(std::max(1, leaf_records)) + 1);
    m_nodes.emplace_back();
    build(sorted, 0, sorted.size(), m_box, 0, 0, leaf_records, uniform);
}

void GuidingField::build(std::vector<GuidingRecord>& records, size_t begin, size_t end,
                         const Bounds3& box, int depth, size_t node, int leaf_records,
                         float uniform) {
    const Vec3 extent = box.max - box.min;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0
                     : extent.y >= extent.z                       ? 1
                                                                  : 2;
    if (end - begin <= static_cast<size_t>(leaf_records) || depth >= kMaxDepth ||
        !(extent[axis] > 0.0f)) {
        DirectionalHistogram histogram;
        BinTable radiance{};
        for (size_t i = begin; i < end; ++i) {
            histogram.add(records[i].wi, records[i].weight);
            if (records[i].weight > 0.0f && std::isfinite(records[i].weight))
                radiance[static_cast<size_t>(DirectionalHistogram::bin_of(records[i].wi))] +=
                    records[i].weight;
        }
        const float per_record =
            1.0f / (static_cast<float>(end - begin) * DirectionalHistogram::kBinSolidAngle);
        for (float& r : radiance)
            r *= per_record;
        m_nodes[node].leaf = static_cast<int>(m_radiance.size());
        m_radiance.push_back(radiance);
        if (histogram.normalise(uniform)) {
            m_nodes[node].histogram = static_cast<int>(m_histograms.size());
            m_histograms.push_back(histogram);
        }
        return;
    }
    const float split = 0.5f * (box.min[axis] + box.max[axis]);
    // stable_partition keeps the records' order on each side: the build is deterministic.
    const auto middle =
        std::stable_partition(records.begin() + static_cast<std::ptrdiff_t>(begin),
                              records.begin() + static_cast<std::ptrdiff_t>(end),
                              [&](const GuidingRecord& r) { return r.position[axis] < split; });
    const size_t mid = static_cast<size_t>(middle - records.begin());
    Bounds3 low = box, high = box;
    low.max[axis] = split;
    high.min[axis] = split;
    const size_t child = m_nodes.size();
    m_nodes[node].axis = axis;
    m_nodes[node].split = split;
    m_nodes[node].child = static_cast<int>(child);
    m_nodes.emplace_back();  // the children side by side, before either subtree
    m_nodes.emplace_back();
    build(records, begin, mid, low, depth + 1, child, leaf_records, uniform);
    build(records, mid, end, high, depth + 1, child + 1, leaf_records, uniform);
}

int GuidingField::leaf_of(const Vec3& p) const {
    if (m_nodes.empty() || p.x < m_box.min.x || p.y < m_box.min.y || p.z < m_box.min.z ||
        p.x > m_box.max.x || p.y > m_box.max.y || p.z > m_box.max.z)
        return -1;
    int node = 0;
    while (m_nodes[static_cast<size_t>(node)].axis >= 0) {
        const Node& n = m_nodes[static_cast<size_t>(node)];
        node = n.child + (p[n.axis] < n.split ? 0 : 1);
    }
    return node;
}

const DirectionalHistogram* GuidingField::find(const Vec3& p) const {
    const int node = leaf_of(p);
    if (node < 0)
        return nullptr;
    const int h = m_nodes[static_cast<size_t>(node)].histogram;
    return h >= 0 ? &m_histograms[static_cast<size_t>(h)] : nullptr;
}

void GuidingField::convolve(const PhaseFunction& phase) {
    constexpr int kBins = DirectionalHistogram::kBins;
    // The phase function between every pair of bin centres, each row normalised to sum 1.
    std::vector<float> weights(static_cast<size_t>(kBins * kBins));
    for (int b = 0; b < kBins; ++b) {
        const Vec3 wo = DirectionalHistogram::in_bin(b, Vec2(0.5f));
        float sum = 0.0f;
        for (int j = 0; j < kBins; ++j) {
            const float p =
                eval(phase, scattering_cosine(wo, DirectionalHistogram::in_bin(j, Vec2(0.5f))));
            weights[static_cast<size_t>(b * kBins + j)] = p;
            sum += p;
        }
        for (int j = 0; j < kBins; ++j)
            weights[static_cast<size_t>(b * kBins + j)] /= sum;
    }
    m_scattered.assign(m_radiance.size(), BinTable{});
    for (size_t leaf = 0; leaf < m_radiance.size(); ++leaf) {
        for (int b = 0; b < kBins; ++b) {
            float sum = 0.0f;
            for (int j = 0; j < kBins; ++j)
                sum += weights[static_cast<size_t>(b * kBins + j)] *
                       m_radiance[leaf][static_cast<size_t>(j)];
            m_scattered[leaf][static_cast<size_t>(b)] = sum;
        }
    }
}

float GuidingField::scattered_radiance(const Vec3& p, const Vec3& wo) const {
    const int node = leaf_of(p);
    if (node < 0 || m_scattered.empty())
        return -1.0f;
    const int leaf = m_nodes[static_cast<size_t>(node)].leaf;
    return m_scattered[static_cast<size_t>(leaf)]
                      [static_cast<size_t>(DirectionalHistogram::bin_of(wo))];
}

}  // namespace kasumi
