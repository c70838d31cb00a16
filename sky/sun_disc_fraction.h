#pragma once
/// The sun disc's visible fraction over the planet's horizon, shared by the sky's table builds.
#include "sky/sky_luts.h"

namespace kasumi {

/// Fraction of the sun's disc above the planet's horizon seen from radius r with the sun's
/// centre at zenith cosine mu_s, and the cosine of the horizon's elevation there (its sine is
/// -sqrt(1 - (rg/r)²)): disc_fraction_above(asin(mu_s) + acos(rg / r), radius). The disc is
/// whole (1) or gone (0) unless mu_s lies within the sines of horizon +- radius (written with
/// sin(a +- b) of the horizon's cosine and sine: no inverse trigonometry for the nodes that are
/// not in the band, nearly all of them); a margin of 1e-9 in the cosine leaves the borderline
/// cases to the exact formula.
double sun_disc_fraction(double r, double mu_s, double rg, const SkyLuts::SunDisc& sun,
                         double& sin_horizon);

/// The parts of sun_disc_fraction() that depend on the radius alone, for many sun cosines at
/// one radius (the multiple-scattering table's nodes): the horizon's cosine and sine and the
/// sines of horizon +- radius.
struct HorizonAt {
    double cos_h = 1.0, sin_horizon = 0.0, upper = 0.0, lower = 0.0;
};
HorizonAt horizon_at(double r, double rg, const SkyLuts::SunDisc& sun);
/// sun_disc_fraction() from the radius's HorizonAt: the same value, bit for bit.
double sun_disc_fraction(const HorizonAt& h, double mu_s, const SkyLuts::SunDisc& sun);

}  // namespace kasumi
