#pragma once
/// The pieces of the `kasumi` extension module, each adding its submodule.
#include <pybind11/pybind11.h>

#include <cstddef>
#include <string>

namespace kasumi::python {

/// Arrays at least this long are processed with the GIL released: below it the release costs
/// more than the loop.
inline constexpr std::ptrdiff_t kReleaseGilFrom = 4096;

void bind_phase(pybind11::module_& phase);
void bind_mie(pybind11::module_& mie);
/// kasumi.RenderResult, then kasumi.Scene (whose render returns one), on the package itself.
void bind_render_result(pybind11::module_& m);
void bind_scene(pybind11::module_& m);
/// kasumi.read_exr.
void bind_exr(pybind11::module_& m);

/// Raises FileNotFoundError (OSError, errno ENOENT) for a path that does not exist: the library
/// reports it as an input error, Python code expects the OSError.
void raise_if_missing(const std::string& path);

}  // namespace kasumi::python
