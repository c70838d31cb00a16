#include "lights/cap_region.h"

#include <array>
#include <cmath>
#include <limits>

namespace kasumi {

namespace {

constexpr double kTwoPiD = 2.0 * kPiD;

/// A set of azimuths in [0, 2π]: a union of at most kMaxArcs disjoint closed intervals. The
/// interval arrays are left uninitialised past m_count (one is built per circle and per shading
/// point; zeroing them, and a fresh set per intersection, cost more than the arithmetic).
class ArcSet {
  public:
    static constexpr size_t kMaxArcs = 16;
    ArcSet() { add(0.0, kTwoPiD); }
    bool empty() const { return m_count == 0; }
    bool overflow() const { return m_overflow; }
    size_t size() const { return m_count; }
    double lo(size_t k) const { return m_lo[k]; }
    double hi(size_t k) const { return m_hi[k]; }
    void clear() { m_count = 0; }

    /// Keeps only the azimuths within `half` of `center` (half in (0, π)).
    void intersect_arc(double center, double half) {
        double lo = std::fmod(center - half, kTwoPiD);
        if (lo < 0.0)
            lo += kTwoPiD;
        const double hi = lo + 2.0 * half;
        // One input interval can give two outputs, which could overwrite an input not yet
        // read: the inputs are copied first.
        double in_lo[kMaxArcs], in_hi[kMaxArcs];
        const size_t count = m_count;
        for (size_t k = 0; k < count; ++k) {
            in_lo[k] = m_lo[k];
            in_hi[k] = m_hi[k];
        }
        m_count = 0;
        for (size_t k = 0; k < count; ++k) {
            add_clipped(in_lo[k], in_hi[k], lo, std::min(hi, kTwoPiD));
            if (hi > kTwoPiD)
                add_clipped(in_lo[k], in_hi[k], 0.0, hi - kTwoPiD);
        }
    }

  private:
    void add(double lo, double hi) {
        if (m_count == kMaxArcs) {
            m_overflow = true;
            return;
        }
        m_lo[m_count] = lo;
        m_hi[m_count] = hi;
        ++m_count;
    }
    void add_clipped(double a_lo, double a_hi, double b_lo, double b_hi) {
        const double lo = std::max(a_lo, b_lo), hi = std::min(a_hi, b_hi);
        if (hi > lo)
            add(lo, hi);
    }

    double m_lo[kMaxArcs], m_hi[kMaxArcs];
    size_t m_count = 0;
    bool m_overflow = false;
};

/// A right-handed orthonormal frame (e1, e2, a) around unit a: Duff et al. 2017, "Building an
/// Orthonormal Basis, Revisited", JCGT 6(1).
void frame_around(const DVec3& a, DVec3& e1, DVec3& e2) {
    const double sign = std::copysign(1.0, a.z);
    const double s = -1.0 / (sign + a.z);
    const double t = a.x * a.y * s;
    e1 = DVec3(1.0 + sign * a.x * a.x * s, sign * t, -sign * a.x);
    e2 = DVec3(t, sign + a.y * a.y * s, -a.y);
}

}  // namespace

double cap_intersection_projected_solid_angle(const SphericalCap* caps, size_t count,
                                              const DVec3& n) {
    double total = 0.0;
    for (size_t i = 0; i < count; ++i) {
        const SphericalCap& ci = caps[i];
        DVec3 e1, e2;
        frame_around(ci.axis, e1, e2);
        ArcSet arcs;
        for (size_t j = 0; j < count && !arcs.empty(); ++j) {
            if (j == i)
                continue;
            const SphericalCap& cj = caps[j];
            // ω(φ) = cos h_i a_i + sin h_i (cos φ e1 + sin φ e2) is inside cap j when
            // A cos(φ − φ_j) ≥ cos h_j − cos h_i (a_i · a_j) = rhs.
            const double b1 = glm::dot(e1, cj.axis), b2 = glm::dot(e2, cj.axis);
            const double amplitude = ci.sin_h * std::sqrt(b1 * b1 + b2 * b2);
            const double rhs = cj.cos_h - ci.cos_h * glm::dot(ci.axis, cj.axis);
            constexpr double kEps = 1e-12;
            if (amplitude <= kEps) {
                // Coaxial circles: circle i is wholly inside cap j, wholly outside, or the
                // same circle (then only the first of the two is kept, so it counts once).
                if (rhs > kEps || (std::abs(rhs) <= kEps && j < i))
                    arcs.clear();
                continue;
            }
            const double c = rhs / amplitude;
            if (c <= -1.0)
                continue;  // the whole circle is inside cap j
            if (c >= 1.0) {
                arcs.clear();  // outside (or touching at one point: no length)
                continue;
            }
            arcs.intersect_arc(std::atan2(b2, b1), std::acos(c));
        }
        if (arcs.overflow())
            return std::numeric_limits<double>::quiet_NaN();
        if (arcs.empty())
            continue;
        const double n1 = glm::dot(n, e1), n2 = glm::dot(n, e2), na = glm::dot(n, ci.axis);
        double sum = 0.0;
        for (size_t k = 0; k < arcs.size(); ++k) {
            const double p0 = arcs.lo(k), p1 = arcs.hi(k);
            sum += ci.sin_h * na * (p1 - p0) - ci.cos_h * (n1 * (std::sin(p1) - std::sin(p0)) -
                                                           n2 * (std::cos(p1) - std::cos(p0)));
        }
        total += 0.5 * ci.sin_h * sum;
    }
    return total;
}

}  // namespace kasumi
