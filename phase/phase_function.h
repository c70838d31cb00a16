#pragma once
/// The closed set of phase functions a medium can carry, as a variant of small value types with
/// free eval / pdf / sample functions (no virtual call per sample). Convention: wo toward the
/// viewer, wi toward the light, mu = -dot(wo, wi); values and pdfs are per steradian and every
/// model integrates to 1 over the sphere.
#include "phase/cornette_shanks.h"
#include "phase/double_henyey_greenstein.h"
#include "phase/draine.h"
#include "phase/henyey_greenstein.h"
#include "phase/isotropic.h"
#include "phase/jendersie_deon.h"
#include "phase/mie.h"
#include "phase/rayleigh.h"
#include "phase/tabulated.h"

#include <variant>

namespace kasumi {

/// Heavy models (Tabulated, Mie) hold their tables through shared_ptr<const ...>, so copying a
/// PhaseFunction never copies a table.
using PhaseFunction = std::variant<Isotropic, HenyeyGreenstein, Rayleigh, DoubleHenyeyGreenstein,
                                   CornetteShanks, Draine, JendersieDeon, Tabulated, Mie>;

inline float eval(const PhaseFunction& p, float mu) {
    return std::visit([mu](const auto& model) { return eval(model, mu); }, p);
}
/// p(mu) per steradian with mu in double precision, for quadrature, tables and plots. Near
/// mu = ±1 float spacing (6e-8) is wider than the forward peak of |g| >= 0.999 (width
/// ~(1 - |g|)²), so only this path integrates to 1 there; eval(p, float mu) is its value at the
/// float mu, rounded to float, and stays the renderer's path.
inline double eval_precise(const PhaseFunction& p, double mu) {
    return std::visit([mu](const auto& model) { return eval_precise(model, mu); }, p);
}
/// The sampling density in double precision. Every model samples exactly (pdf == eval, which
/// validate_phase checks on the float path), so this is eval_precise.
inline double pdf_precise(const PhaseFunction& p, double mu) {
    return eval_precise(p, mu);
}
inline float pdf(const PhaseFunction& p, float mu) {
    return std::visit([mu](const auto& model) { return pdf(model, mu); }, p);
}
inline PhaseSample sample(const PhaseFunction& p, const Vec3& wo, Vec2 u) {
    return std::visit([&](const auto& model) { return sample(model, wo, u); }, p);
}
inline float mean_cosine(const PhaseFunction& p) {
    return std::visit([](const auto& model) { return mean_cosine(model); }, p);
}

/// Evaluates the phase function for a pair of directions in the project's convention.
inline float eval(const PhaseFunction& p, const Vec3& wo, const Vec3& wi) {
    return eval(p, scattering_cosine(wo, wi));
}

}  // namespace kasumi
