#include "gi/photon/photon_estimate.h"

namespace kasumi {

float filter_weight(PhotonFilter filter, int dims, float d, float r) {
    if (!(r > 0.0f) || d > r)
        return 0.0f;
    const float t = d / r;
    const float r2 = r * r;
    switch (filter) {
        case PhotonFilter::Box:
            return dims == 2 ? 1.0f / (kPi * r2) : 3.0f / (4.0f * kPi * r2 * r);
        case PhotonFilter::Cone: {
            const float w = 1.0f - t / kConeFilterK;
            // ∫_0^1 (1 - t/k) 2π t dt = π (1 - 2/(3k)); ∫_0^1 (1 - t/k) 4π t² dt = 4π (1/3 -
            // 1/(4k)).
            return dims == 2 ? w / ((1.0f - 2.0f / (3.0f * kConeFilterK)) * kPi * r2)
                             : w / (4.0f * kPi * (1.0f / 3.0f - 0.25f / kConeFilterK) * r2 * r);
        }
        case PhotonFilter::Epanechnikov: {
            const float w = 1.0f - t * t;
            // ∫_0^1 (1 - t²) 2π t dt = π/2; ∫_0^1 (1 - t²) 4π t² dt = 8π/15.
            return dims == 2 ? 2.0f * w / (kPi * r2) : 15.0f * w / (8.0f * kPi * r2 * r);
        }
    }
    return 0.0f;
}

float estimate_radius(const std::vector<PhotonNeighbour>& found, int k, float max_radius) {
    if (static_cast<int>(found.size()) >= k && !found.empty())
        return std::sqrt(found.front().distance2);
    return max_radius;
}

}  // namespace kasumi
