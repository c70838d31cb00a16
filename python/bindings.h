#pragma once
/// The pieces of the `kasumi` extension module, each adding its submodule.
#include <pybind11/pybind11.h>

#include <cstddef>

namespace kasumi::python {

/// Arrays at least this long are processed with the GIL released: below it the release costs
/// more than the loop.
inline constexpr std::ptrdiff_t kReleaseGilFrom = 4096;

void bind_phase(pybind11::module_& phase);
void bind_mie(pybind11::module_& mie);

}  // namespace kasumi::python
