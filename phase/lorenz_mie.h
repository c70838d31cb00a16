#pragma once
/// Exact Lorenz-Mie scattering by a homogeneous sphere (Bohren & Huffman 1983, "Absorption and
/// Scattering of Light by Small Particles", ch. 4), in double precision. Conventions are Bohren
/// & Huffman's: time dependence exp(-iωt), so an absorbing sphere has m = n + ik with k >= 0;
/// S1 is the amplitude for light polarised perpendicular to the scattering plane and S2 parallel
/// to it (BH eq. 4.74). MIEV0 (Wiscombe 1979/1996) uses m = n - ik and returns the complex
/// conjugates of these amplitudes.
#include <complex>
#include <vector>

namespace kasumi {

using Complex = std::complex<double>;

/// Efficiencies (cross section / πr²) and the asymmetry parameter of one sphere.
struct MieEfficiencies {
    double qext = 0.0;
    double qsca = 0.0;
    double qabs = 0.0;
    double qback = 0.0;  ///< backscattering efficiency, BH eq. 4.82 (4π dC/dΩ at 180° / πr²)
    double g = 0.0;      ///< mean cosine of the scattering angle
};

/// Wiscombe's (1980, Appl. Opt. 19, 1505, eq. 3) number of terms:
/// x + 4 x^{1/3} + 1 for x <= 8, x + 4.05 x^{1/3} + 2 for 8 < x < 4200, x + 4 x^{1/3} + 2 above.
int wiscombe_n_terms(double x);

/// The Mie series of one sphere: size parameter x = 2π r n_medium / λ > 0 and refractive index
/// m relative to the medium, Re m > 0, Im m >= 0.
class LorenzMie {
  public:
    LorenzMie(double x, Complex m);

    double x() const { return m_x; }
    Complex m() const { return m_m; }
    int n_terms() const { return static_cast<int>(m_a.size()); }
    const std::vector<Complex>& a() const { return m_a; }  ///< a_1 .. a_N (index n - 1)
    const std::vector<Complex>& b() const { return m_b; }

    MieEfficiencies efficiencies() const;
    /// Amplitudes S1, S2 at mu = cos θ (θ = 0 forward), BH eq. 4.74.
    void amplitudes(double mu, Complex& s1, Complex& s2) const;
    /// (|S1|² + |S2|²) / 2, the unpolarised scattered intensity S11 (BH eq. 4.77).
    double s11(double mu) const;

  private:
    double m_x;
    Complex m_m;
    std::vector<Complex> m_a, m_b;
};

}  // namespace kasumi
