/// kasumi.RenderResult: one rendered frame, its images as NumPy arrays viewing the film without
/// copies, its counters and stage times, and its files written by the CLI's writer.
#include "bindings.h"
#include "python/rendered_frame.h"

#include "render/frame_output.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <optional>

namespace py = pybind11;

namespace kasumi::python {

namespace {

/// A (height, width, channels) float32 array viewing `view`'s planes; its base keeps `frame`
/// (and so the film) alive.
py::array view_array(const std::shared_ptr<RenderedFrame>& frame, const PlaneView& view) {
    const Film& film = frame->result.film;
    const auto width = static_cast<py::ssize_t>(film.width());
    py::capsule owner(new std::shared_ptr<RenderedFrame>(frame),
                      [](void* p) { delete static_cast<std::shared_ptr<RenderedFrame>*>(p); });
    return py::array(
        py::dtype::of<float>(),
        {static_cast<py::ssize_t>(film.height()), width, static_cast<py::ssize_t>(view.channels)},
        {width * static_cast<py::ssize_t>(sizeof(float)), static_cast<py::ssize_t>(sizeof(float)),
         view.channel_stride_bytes},
        view.data, owner);
}

py::object aov_array(const std::shared_ptr<RenderedFrame>& frame, const std::string& name) {
    for (const PlaneView& view : plane_views(*frame)) {
        if (view.name == name)
            return view_array(frame, view);
    }
    return py::none();
}

py::dict stats_dict(const RenderedFrame& frame) {
    const RenderCounters& c = frame.result.counters;
    py::dict d;
    d["camera_rays"] = c.camera_rays;
    d["surface_hits"] = c.surface_hits;
    d["surface_shadow_rays"] = c.surface_shadow_rays;
    d["shadow_rays_avoided"] = c.shadow_rays_avoided;
    d["volume_rays"] = c.volume_rays;
    d["volume_steps"] = c.volume_steps;
    d["volume_shadow_rays"] = c.volume_shadow_rays;
    d["nonfinite_samples"] = c.nonfinite_samples;
    d["density_lookups"] = c.density_lookups;
    d["transmittance_rays"] = c.transmittance_rays;
    d["free_flights"] = c.free_flights;
    d["scattering_events"] = c.scattering_events;
    d["bounded_marches"] = c.bounded_marches;
    d["threads"] = frame.result.threads;
    const RenderRates r = render_rates(c, frame.result.seconds, frame.result.threads);
    d["density_lookups_per_s_per_core"] = r.density_lookups_per_s_per_core;
    d["camera_rays_per_s"] = r.camera_rays_per_s;
    d["all_rays_per_s"] = r.all_rays_per_s;
    return d;
}

py::dict times_dict(const StageTimes& times) {
    py::dict d;
    const std::pair<const char*, double> stages[] = {
        {"load", times.load_s}, {"build", times.build_s}, {"render", times.render_s}};
    for (const auto& [name, seconds] : stages) {
        if (seconds >= 0.0)
            d[name] = seconds;
    }
    for (const auto& [name, seconds] : times.parts)
        d[py::str(name)] = seconds;
    return d;
}

void write_exr(const std::shared_ptr<RenderedFrame>& frame, const std::string& path,
               const std::string& aovs, const std::string& compression,
               const std::optional<std::string>& preview) {
    OutputPaths paths;
    parse_output_format(aovs, compression, paths.aovs, paths.compression);
    paths.exr = path;
    paths.preview = preview.value_or("");
    py::gil_scoped_release release;
    write_render_outputs(*frame->runtime, frame->result, paths, frame->frame, frame->times);
}

}  // namespace

void bind_render_result(py::module_& m) {
    py::class_<RenderedFrame, std::shared_ptr<RenderedFrame>> result(
        m, "RenderResult",
        "One rendered frame. Its images are float32 arrays (height, width, channels) viewing the "
        "film without copies (writable; they keep the pixels alive after the result and the "
        "scene are gone): scene-linear Rec.709, luminance in cd/m².");
    const std::pair<const char*, const char*> aovs[] = {
        {"beauty", "R, G, B: L_volume + T * L_surface (cd/m²), shape (H, W, 3)"},
        {"alpha", "A: fraction of samples that hit a surface, plus the media's opacity, (H, W, 1)"},
        {"albedo", "diffuse reflectance of the first surface (0 where none), (H, W, 3)"},
        {"depth", "camera-space depth of the first surface in metres (0 where none), (H, W, 1)"},
        {"surface", "L_surface (or background) before the media (cd/m²), (H, W, 3)"},
        {"volume", "L_volume: in-scattered radiance of the media (cd/m²), (H, W, 3)"},
        {"transmittance", "T of the media along the camera ray up to the surface, (H, W, 3)"},
    };
    for (const auto& [name, doc] : aovs) {
        const std::string aov = name;
        result.def_property_readonly(
            name, [aov](const std::shared_ptr<RenderedFrame>& f) { return aov_array(f, aov); },
            doc);
    }
    result
        .def_property_readonly(
            "aovs",
            [](const std::shared_ptr<RenderedFrame>& f) {
                std::vector<std::string> names;
                for (const PlaneView& view : plane_views(*f))
                    names.push_back(view.name);
                return names;
            },
            "names of the images this result holds, in the EXR's channel order")
        .def_property_readonly(
            "stats", [](const RenderedFrame& f) { return stats_dict(f); },
            "render counters (the EXR's kasumi/stats/* keys) and rates")
        .def_property_readonly(
            "times", [](const RenderedFrame& f) { return times_dict(f.times); },
            "wall seconds per stage: load, build, render, and their parts (\"build/bvh\", ...)")
        .def_property_readonly(
            "seconds", [](const RenderedFrame& f) { return f.result.seconds; },
            "wall seconds of the render (tiles) alone")
        .def_property_readonly(
            "interrupted", [](const RenderedFrame& f) { return f.result.interrupted; },
            "true when the render was stopped: rows not rendered are black")
        .def_property_readonly("frame", [](const RenderedFrame& f) { return f.frame; })
        .def_property_readonly(
            "width", [](const RenderedFrame& f) { return f.result.film.width(); }, "pixels")
        .def_property_readonly(
            "height", [](const RenderedFrame& f) { return f.result.film.height(); }, "pixels")
        .def("write_exr", &write_exr, py::arg("path"), py::arg("aovs") = "all",
             py::arg("compression") = "zip", py::arg("preview") = py::none(),
             "Writes the EXR as `kasumi render -o PATH` does (same channels and kasumi/* "
             "metadata; the arrays as they are now) and, given `preview`, its PNG. OSError if a "
             "file cannot be written.")
        .def(
            "write_png",
            [](const std::shared_ptr<RenderedFrame>& f, const std::string& path) {
                py::gil_scoped_release release;
                write_render_preview(*f->runtime, f->result, path);
            },
            py::arg("path"),
            "Writes the preview PNG as `kasumi render --preview PATH` does (the scene's "
            "render.preview view and exposure through OpenColorIO).");
}

}  // namespace kasumi::python
