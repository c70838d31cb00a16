#pragma once
/// The learnt incident radiance inside the media: a kd-tree over the box of the training
/// records, split at the midpoint of the longest axis while a node holds more than
/// `leaf_records` records (the spatial binary tree of Müller, Gross & Novák 2017, sec. 5.1,
/// rebuilt per training pass), whose leaves hold a DirectionalHistogram of the incident
/// radiance (Herholz, Zhao, Georgiev, Keller & Lensch 2019, "Volume path guiding based on
/// zero-variance random walk theory": sample scattering directions in proportion to L_i).
/// Built from records alone, in their order: the same records give the same field.
#include "core/bounds.h"
#include "volume/guiding/directional_histogram.h"

#include <vector>

namespace kasumi {

/// One scattering vertex of a training path: where it was, the direction it continued in, and
/// the luminance of the radiance the rest of the path brought back along it, divided by the
/// pdf of that direction (cd/m² sr): a one-sample estimate of L_i(position, wi) / pdf(wi), so
/// summing records per bin estimates the integral of L_i over the bin.
struct GuidingRecord {
    Vec3 position{0.0f};  ///< world, metres
    Vec3 wi{0.0f};        ///< unit, toward where the light came from
    float weight = 0.0f;
};

class GuidingField {
  public:
    GuidingField() = default;
    /// Builds the tree over the records' bounding box; `uniform` is each histogram's uniform
    /// share (DirectionalHistogram::normalise). A leaf whose records carry no light guides
    /// nothing (find returns null there).
    GuidingField(const std::vector<GuidingRecord>& records, int leaf_records, float uniform);

    /// The histogram of the leaf holding world point p, or null (outside the box, or a leaf
    /// without light).
    const DirectionalHistogram* find(const Vec3& p) const;
    bool empty() const { return m_nodes.empty(); }
    size_t leaf_count() const { return m_histograms.size(); }

  private:
    struct Node {
        int axis = -1;       ///< -1: a leaf
        float split = 0.0f;  ///< world coordinate of the split plane on `axis`
        int child = -1;      ///< first child (the second is child + 1)
        int histogram = -1;  ///< a leaf's histogram, -1 if it guides nothing
    };
    /// Makes m_nodes[node] the root of a subtree over records [begin, end) inside `box`.
    void build(std::vector<GuidingRecord>& records, size_t begin, size_t end, const Bounds3& box,
               int depth, size_t node, int leaf_records, float uniform);

    Bounds3 m_box;
    std::vector<Node> m_nodes;
    std::vector<DirectionalHistogram> m_histograms;
};

}  // namespace kasumi
