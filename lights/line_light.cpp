#include "lights/line_light.h"

namespace kasumi {

namespace {

/// p relative to the line: unit tangent t, foot parameter s0 (p's projection is from + s0 t),
/// length, and d = p − foot with h = |d|.
struct LineFrame {
    DVec3 t;
    double length = 0.0;
    double s0 = 0.0;
    DVec3 d;
    double h = 0.0;
};

LineFrame line_frame(const LineLight& light, const Vec3& p) {
    LineFrame f;
    const DVec3 a(light.from), b(light.to), q(p);
    f.length = glm::length(b - a);
    f.t = (b - a) / f.length;
    f.s0 = glm::dot(q - a, f.t);
    f.d = q - (a + f.s0 * f.t);
    f.h = glm::length(f.d);
    return f;
}

/// Antiderivative in s of n·(x − p)/r⁴ with x − p = s t − d, r² = s² + h²:
///   (n·t) ∫ s/(s²+h²)² ds − (n·d) ∫ 1/(s²+h²)² ds
///   = −(n·t) / (2(s²+h²)) − (n·d) [s / (2h²(s²+h²)) + atan(s/h) / (2h³)].
double antiderivative(double s, double h, double nt, double nd) {
    const double r2 = s * s + h * h;
    return -nt / (2.0 * r2) - nd * (s / (2.0 * h * h * r2) + std::atan(s / h) / (2.0 * h * h * h));
}

IncidentLight with_point(const Vec3& p, const DVec3& x, const Rgb& irradiance) {
    IncidentLight in;
    const DVec3 to = x - DVec3(p);
    const double r = glm::length(to);
    in.light_position = Vec3(x);
    if (!(r > 0.0))
        return in;
    in.distance = static_cast<float>(r);
    in.wi = Vec3(to / r);
    in.irradiance = irradiance;
    return in;
}

}  // namespace

Rgb unshadowed_irradiance(const LineLight& light, const Vec3& p, const Vec3& n) {
    const LineFrame f = line_frame(light, p);
    if (!(f.length > 0.0) || !(f.h > 1e-7))
        return Rgb(0.0f);
    const DVec3 nd(n);
    const double nt = glm::dot(nd, f.t), ndd = glm::dot(nd, f.d);
    // s is measured from the foot of p: the segment is [−s0, L − s0]. n·(x − p) = s nt − ndd is
    // linear in s, so the part above the tangent plane is one interval.
    double s_lo = -f.s0, s_hi = f.length - f.s0;
    if (nt > 0.0) {
        s_lo = std::max(s_lo, ndd / nt);
    } else if (nt < 0.0) {
        s_hi = std::min(s_hi, ndd / nt);
    } else if (!(-ndd > 0.0)) {
        return Rgb(0.0f);
    }
    if (!(s_hi > s_lo))
        return Rgb(0.0f);
    const double e =
        f.h * (antiderivative(s_hi, f.h, nt, ndd) - antiderivative(s_lo, f.h, nt, ndd));
    return light.intensity_per_m * static_cast<float>(std::max(e, 0.0));
}

IncidentLight sample_incident(const LineLight& light, const Vec3& p, Vec2 u) {
    const LineFrame f = line_frame(light, p);
    if (!(f.length > 0.0))
        return IncidentLight{};
    const DVec3 a(light.from);
    if (f.h > 1e-6 * f.length) {
        // s = h tan φ with φ uniform: ds = r²/h dφ, so the pdf in s is h / (r² Δφ) and
        // I_l sin α / r² / pdf = I_l (h/r) Δφ / h = I_l Δφ / r.
        const double phi0 = std::atan(-f.s0 / f.h), phi1 = std::atan((f.length - f.s0) / f.h);
        const double phi = phi0 + static_cast<double>(u.x) * (phi1 - phi0);
        const double s = f.h * std::tan(phi);
        const double r = std::sqrt(s * s + f.h * f.h);
        const DVec3 x = a + (f.s0 + s) * f.t;
        return with_point(p, x, light.intensity_per_m * static_cast<float>((phi1 - phi0) / r));
    }
    // On the axis (sin α = 0 everywhere) the light delivers nothing; keep a valid direction.
    const DVec3 x = a + static_cast<double>(u.x) * f.length * f.t;
    return with_point(p, x, Rgb(0.0f));
}

float line_flux_lm(const LineLight& light) {
    return kPi * kPi * luminance(light.intensity_per_m) * glm::length(light.to - light.from);
}

}  // namespace kasumi
