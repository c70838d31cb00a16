/// kasumi.mie: Lorenz-Mie efficiencies and amplitudes of one sphere (Bohren & Huffman 1983,
/// m = n + ik with k >= 0, S1 perpendicular and S2 parallel to the scattering plane), and the
/// size distributions polydisperse models average over.
#include "bindings.h"

#include "core/error.h"
#include "phase/lorenz_mie.h"
#include "phase/size_distribution.h"

#include <pybind11/complex.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <sstream>

namespace py = pybind11;

namespace kasumi::python {

namespace {

/// The scene loader's ranges (phase/phase_json.cpp), as input errors.
LorenzMie sphere(Complex m, double x) {
    std::ostringstream where;
    where << "mie: x = " << x << ", m = (" << m.real() << ", " << m.imag() << "): ";
    if (!(x > 0.0 && x <= 1e5))
        throw_input_error(where.str() + "size parameter must be in (0, 1e5]");
    if (!(m.real() > 0.0) || !std::isfinite(m.real()))
        throw_input_error(where.str() + "real part of the refractive index must be > 0");
    if (!(m.imag() >= 0.0) || !std::isfinite(m.imag()))
        throw_input_error(where.str() +
                          "imaginary part must be >= 0 (absorption is m = n + ik with k >= 0)");
    return LorenzMie(x, m);
}

void check_positive(const char* name, double v) {
    if (!(v > 0.0) || !std::isfinite(v))
        throw py::value_error(std::string(name) + " must be > 0");
}

}  // namespace

void bind_mie(py::module_& m) {
    py::class_<MieEfficiencies>(m, "Efficiencies",
                                "Cross sections over πr² and the mean cosine of one sphere.")
        .def_readonly("qext", &MieEfficiencies::qext, "extinction efficiency")
        .def_readonly("qsca", &MieEfficiencies::qsca, "scattering efficiency")
        .def_readonly("qabs", &MieEfficiencies::qabs, "absorption efficiency")
        .def_readonly("qback", &MieEfficiencies::qback, "backscattering efficiency (BH 4.82)")
        .def_readonly("g", &MieEfficiencies::g, "mean cosine of the scattering angle")
        .def("__iter__",
             [](const MieEfficiencies& e) {
                 return py::iter(py::make_tuple(e.qext, e.qsca, e.qback, e.g));
             })
        .def("__repr__", [](const MieEfficiencies& e) {
            std::ostringstream s;
            s.precision(9);
            s << "Efficiencies(qext=" << e.qext << ", qsca=" << e.qsca << ", qabs=" << e.qabs
              << ", qback=" << e.qback << ", g=" << e.g << ")";
            return s.str();
        });

    m.def(
        "efficiencies", [](Complex index, double x) { return sphere(index, x).efficiencies(); },
        py::arg("m"), py::arg("x"),
        "Efficiencies of a sphere of size parameter x = 2π r n_medium / λ and relative index m "
        "(complex, m = n + ik, k >= 0). Unpacks as qext, qsca, qback, g; qabs by name.");
    m.def(
        "n_terms", [](Complex index, double x) { return sphere(index, x).n_terms(); }, py::arg("m"),
        py::arg("x"), "Terms of the series (Wiscombe 1980).");
    m.def(
        "amplitudes",
        [](Complex index, double x,
           const py::array_t<double, py::array::c_style | py::array::forcecast>& mu) {
            const LorenzMie s = sphere(index, x);
            const std::vector<py::ssize_t> shape(mu.shape(), mu.shape() + mu.ndim());
            py::array_t<Complex> s1(shape), s2(shape);
            const double* in = mu.data();
            Complex* a = s1.mutable_data();
            Complex* b = s2.mutable_data();
            const py::ssize_t n = mu.size();
            for (py::ssize_t i = 0; i < n; ++i)
                if (!(in[i] >= -1.0 && in[i] <= 1.0))
                    throw py::value_error("mu must be in [-1, 1]");
            {
                py::gil_scoped_release release;
                for (py::ssize_t i = 0; i < n; ++i)
                    s.amplitudes(in[i], a[i], b[i]);
            }
            return py::make_tuple(s1, s2);
        },
        py::arg("m"), py::arg("x"), py::arg("mu"),
        "(S1, S2) complex128 arrays at mu = cos θ (θ = 0 forward), BH eq. 4.74; the unpolarised "
        "intensity is S11 = (|S1|² + |S2|²) / 2.");

    py::class_<LogNormalSizes>(m, "LogNormal",
                               "n(r) log-normal in r (µm): median radius and sigma = ln of the "
                               "geometric standard deviation; scene name \"lognormal\".")
        .def(py::init([](double median_radius_um, double sigma) {
                 check_positive("median_radius_um", median_radius_um);
                 check_positive("sigma", sigma);
                 return LogNormalSizes{median_radius_um, sigma};
             }),
             py::arg("median_radius_um"), py::arg("sigma"))
        .def_readonly("median_radius_um", &LogNormalSizes::median_radius_um)
        .def_readonly("sigma", &LogNormalSizes::sigma);
    py::class_<ModifiedGammaSizes>(m, "ModifiedGamma",
                                   "Deirmendjian's modified gamma n(r) ∝ r^alpha exp(-b r^gamma) "
                                   "with mode radius r_c (µm); scene name \"modified-gamma\".")
        .def(py::init([](double mode_radius_um, double alpha, double gamma) {
                 check_positive("mode_radius_um", mode_radius_um);
                 check_positive("alpha", alpha);
                 check_positive("gamma", gamma);
                 return ModifiedGammaSizes{mode_radius_um, alpha, gamma};
             }),
             py::arg("mode_radius_um"), py::arg("alpha"), py::arg("gamma"))
        .def_readonly("mode_radius_um", &ModifiedGammaSizes::mode_radius_um)
        .def_readonly("alpha", &ModifiedGammaSizes::alpha)
        .def_readonly("gamma", &ModifiedGammaSizes::gamma);

    m.def(
        "number_density",
        [](const SizeDistribution& d,
           const py::array_t<double, py::array::c_style | py::array::forcecast>& r) {
            py::array_t<double> out(std::vector<py::ssize_t>(r.shape(), r.shape() + r.ndim()));
            for (py::ssize_t i = 0; i < r.size(); ++i)
                out.mutable_data()[i] = number_density(d, r.data()[i]);
            return out;
        },
        py::arg("distribution"), py::arg("radius_um"),
        "n(r) per µm, normalised to 1 over r in (0, ∞).");
    m.def("dominant_radius_um", &dominant_radius_um, py::arg("distribution"),
          "The radius (µm) where n(r) r³ peaks.");
    m.def(
        "scattering_radius_range",
        [](const SizeDistribution& d) {
            double lo = 0.0, hi = 0.0;
            scattering_radius_range(d, lo, hi);
            return py::make_tuple(lo, hi);
        },
        py::arg("distribution"),
        "(r_min, r_max) in µm holding all but ~1e-12 of the scattering weight.");
}

}  // namespace kasumi::python
