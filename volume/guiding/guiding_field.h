#pragma once
/// The learnt incident radiance inside the media: a kd-tree over the box of the training
/// records, split at the midpoint of the longest axis while a node holds more than
/// `leaf_records` records (the spatial binary tree of Müller, Gross & Novák 2017, sec. 5.1,
/// rebuilt per training pass), whose leaves hold a DirectionalHistogram of the incident
/// radiance (Herholz, Zhao, Georgiev, Keller & Lensch 2019, "Volume path guiding based on
/// zero-variance random walk theory": sample scattering directions in proportion to L_i).
/// Built from records alone, in their order: the same records give the same field.
#include "core/bounds.h"
#include "phase/phase_function.h"
#include "volume/guiding/directional_histogram.h"
#include "volume/guiding/pixel_estimates.h"

#include <utility>
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

    /// Fills every leaf's table of scattered radiance for `phase` (scattered_radiance): for
    /// each outgoing bin b, I_b = sum_j L_j p(mu_bj) / sum_j p(mu_bj), L_j the leaf's mean
    /// incident radiance over bin j and mu_bj the scattering cosine between the bins' centres
    /// (the phase function's quadrature over the bins, normalised so a uniform L gives L).
    void convolve(const PhaseFunction& phase);
    /// The learnt in-scattered radiance at world point p toward the path arriving along -wo
    /// (wo unit, pointing back along the arriving path): I(x, wo) = integral of L_i(x, wi)
    /// p(wo, wi) dwi, luminance, cd/m², from the leaf's table (convolve); the incident radiance
    /// is the records' (light gathered after the vertex: the vertex's own next-event estimate is
    /// not in it). Negative when p is outside the field's box or convolve() was not called.
    /// Biased (coarse bins, few records): it only steers (render.volume.splitting "guided").
    float scattered_radiance(const Vec3& p, const Vec3& wo) const;

    /// The per-pixel estimates of the training passes (render.volume.splitting "guided").
    void set_pixel_estimates(PixelEstimates pixels) { m_pixels = std::move(pixels); }
    const PixelEstimates& pixel_estimates() const { return m_pixels; }

  private:
    struct Node {
        int axis = -1;       ///< -1: a leaf
        float split = 0.0f;  ///< world coordinate of the split plane on `axis`
        int child = -1;      ///< first child (the second is child + 1)
        int histogram = -1;  ///< a leaf's histogram, -1 if it guides nothing
        int leaf = -1;       ///< a leaf's index into m_radiance and m_scattered
    };
    using BinTable = std::array<float, DirectionalHistogram::kBins>;
    /// The leaf holding p, or -1 outside the box.
    int leaf_of(const Vec3& p) const;
    /// Makes m_nodes[node] the root of a subtree over records [begin, end) inside `box`.
    void build(std::vector<GuidingRecord>& records, size_t begin, size_t end, const Bounds3& box,
               int depth, size_t node, int leaf_records, float uniform);

    Bounds3 m_box;
    std::vector<Node> m_nodes;
    std::vector<DirectionalHistogram> m_histograms;
    /// Per leaf: the mean incident luminance over each bin, cd/m² (sum of the bin's record
    /// weights / (records in the leaf x bin solid angle): the records' weights are L_i / pdf).
    std::vector<BinTable> m_radiance;
    std::vector<BinTable> m_scattered;  ///< per leaf: I_b of convolve(), empty before it
    PixelEstimates m_pixels;
};

}  // namespace kasumi
