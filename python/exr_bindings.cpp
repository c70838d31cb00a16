/// kasumi.read_exr: an EXR's channels and kasumi/* metadata as the library reads them (the
/// CLI's renders compared with the module's arrays, bit for bit).
#include "bindings.h"

#include "core/exr_io.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cerrno>
#include <filesystem>

namespace py = pybind11;

namespace kasumi::python {

void raise_if_missing(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::exists(path, ec))
        return;
    errno = ENOENT;
    PyErr_SetFromErrnoWithFilename(PyExc_OSError, path.c_str());  // becomes FileNotFoundError
    throw py::error_already_set();
}

void bind_exr(py::module_& m) {
    m.def(
        "read_exr",
        [](const std::string& path) {
            raise_if_missing(path);
            Image image;
            {
                py::gil_scoped_release release;
                image = read_exr(path);
            }
            py::dict channels;
            for (const ImageChannel& channel : image.channels) {
                py::array_t<float> plane({image.height, image.width});
                std::copy(channel.data.begin(), channel.data.end(), plane.mutable_data());
                channels[py::str(channel.name)] = plane;
            }
            py::dict metadata;
            for (const auto& [key, value] : image.metadata)
                metadata[py::str(key)] = value;
            return py::make_tuple(channels, metadata);
        },
        py::arg("path"),
        "Reads an EXR: ({channel name: float32 array (height, width)}, {metadata key: text}); "
        "kasumi/* attributes lose the prefix (\"spp\", \"stats/camera_rays\"). Half channels "
        "are converted exactly.");
}

}  // namespace kasumi::python
