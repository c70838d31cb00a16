/// The `kasumi._kasumi` extension: kasumi.Scene, kasumi.phase and kasumi.mie over the same
/// library as the CLI, and the error types. kasumi/__init__.py re-exports it.
#include "bindings.h"

#include "core/error.h"

namespace py = pybind11;

PYBIND11_MODULE(_kasumi, m) {
    m.doc() =
        "kasumi: scenes, renders and probes; phase functions, Lorenz-Mie theory and their "
        "validation";
    // Input errors carry the CLI's located message ("phase: /g = 1.2: must be in (-1, 1)").
    static py::exception<kasumi::Error> scene_error(m, "SceneError", PyExc_ValueError);
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p)
                std::rethrow_exception(p);
        } catch (const kasumi::Error& e) {
            switch (e.kind()) {
                case kasumi::ErrorKind::Input:
                    scene_error(e.what());
                    return;
                case kasumi::ErrorKind::Output:
                    PyErr_SetString(PyExc_OSError, e.what());
                    return;
                case kasumi::ErrorKind::Usage:
                    PyErr_SetString(PyExc_ValueError, e.what());
                    return;
                default:
                    PyErr_SetString(PyExc_RuntimeError, e.what());
                    return;
            }
        }
    });
    py::module_ phase = m.def_submodule("phase", "Phase functions (mu = cos θ, +1 forward; 1/sr)");
    kasumi::python::bind_phase(phase);
    py::module_ mie = m.def_submodule("mie", "Lorenz-Mie theory of spheres (Bohren & Huffman)");
    kasumi::python::bind_mie(mie);
    kasumi::python::bind_render_result(m);
    kasumi::python::bind_scene(m);
    kasumi::python::bind_exr(m);
}
