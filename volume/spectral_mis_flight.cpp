#include "volume/spectral_mis_flight.h"

#include "volume/majorant_walk.h"
#include "volume/poisson_collisions.h"

namespace kasumi {

FreeFlight sample_free_flight_spectral_mis(const MediumSet& media, const Ray& ray,
                                           const Rgb& throughput, Pcg32& rng,
                                           VolumeCounters& counters) {
    if (media.emits())
        return sample_free_flight(media, ray, throughput, rng, counters);
    ++counters.free_flights;
    // The hero's selection probabilities q_c, in proportion to |throughput|.
    Rgb q = glm::abs(throughput);
    const float q_sum = q.r + q.g + q.b;
    q = q_sum > 0.0f ? q / q_sum : Rgb(1.0f / 3.0f);
    const float u = rng.next_float();
    const int hero = u < q.r ? 0 : u < q.r + q.g ? 1 : 2;
    const RayMediaQuery query(media, ray);
    FreeFlight flight;
    // Products of sigma_n / mu over the null collisions passed, per channel: technique c's
    // probability of the null choices so far, and channel c's null-collision factors of f
    // (the same numbers; dividing each by mu keeps them <= 1).
    Rgb nulls(1.0f);
    const bool escaped = walk_tentative_collisions(
        media, query, rng, counters,
        [&](float t, const MajorantSegment& s, const PointCoefficients& k, float mu) {
            const Rgb sigma_n = glm::max(Rgb(mu) - k.sigma_t, Rgb(0.0f));
            const float x = rng.next_float() * mu;
            if (x < k.sigma_s[hero]) {
                // Scattering: f_lambda / F_lambda = nulls_lambda / mu; technique c's pdf
                // holds nulls_c sigma_s,c / mu; the common 1 / mu cancels.
                const float mixture = glm::dot(q, nulls * k.sigma_s);
                flight.scattered = mixture > 0.0f;
                flight.weight = flight.scattered ? nulls / mixture : Rgb(0.0f);
                flight.t = t;
                flight.position = ray.at(t);
                flight.media_mask = s.media_mask;
                flight.k = k;
                return false;
            }
            if (x < k.sigma_t[hero]) {
                flight.weight = Rgb(0.0f);  // absorbed: no path goes on
                return false;
            }
            nulls *= sigma_n / mu;
            return true;
        });
    if (escaped) {
        const float mixture = glm::dot(q, nulls);
        flight.weight = mixture > 0.0f ? nulls / mixture : Rgb(0.0f);
    }
    return flight;
}

}  // namespace kasumi
