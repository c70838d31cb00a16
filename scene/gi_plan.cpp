#include "scene/gi_plan.h"

#include <sstream>

namespace kasumi {

namespace {

struct SurfaceCensus {
    size_t diffuse_polygonal = 0;  ///< Phong quads, boxes and meshes
    size_t diffuse_spheres = 0;
    size_t specular = 0;  ///< mirrors and dielectrics
    size_t emissive = 0;
};

SurfaceCensus census(const SceneDesc& scene) {
    SurfaceCensus c;
    for (const Shape& shape : scene.shapes) {
        const Material& m = scene.materials[shape.material];
        if (max_component(emission(m)) > 0.0f)
            ++c.emissive;
        if (is_specular(m))
            ++c.specular;
        else if (std::holds_alternative<SphereShape>(shape.geometry))
            ++c.diffuse_spheres;
        else
            ++c.diffuse_polygonal;
    }
    return c;
}

std::string media_role(const SceneDesc& scene) {
    if (scene.media.empty())
        return "no media";
    const bool multiple = scene.render.volume.integrator == VolumeIntegrator::Multiple;
    return std::to_string(scene.media.size()) + " media through the volume stage (" +
           (multiple ? "multiple" : "single") + " scattering)";
}

}  // namespace

PlanStage gi_plan_stage(const SceneDesc& scene) {
    const SurfaceCensus c = census(scene);
    const RenderSettings& r = scene.render;
    std::ostringstream reason;
    switch (r.gi) {
        case GiMode::None:
            reason << "render.gi is \"none\": light does not bounce between diffuse surfaces";
            if (c.emissive > 0)
                reason << "; " << c.emissive << " emissive shapes are seen but light nothing";
            return {"global-illumination", false, reason.str()};
        case GiMode::Radiosity: {
            const RadiositySettings& s = r.radiosity;
            reason << "radiosity on " << c.diffuse_polygonal
                   << " Phong quads/boxes/meshes (patches <= " << s.patch_size_m << " m, "
                   << s.max_subdivision << " adaptive levels, "
                   << (s.solver == RadiositySolver::Shooting ? "progressive shooting"
                                                             : "Gauss-Seidel")
                   << ", tolerance " << s.tolerance << "), " << scene.lights.size()
                   << " lights and " << c.emissive
                   << " emissive shapes as sources; Gouraud-interpolated, Phong highlights and "
                      "Whitted rays ("
                   << c.specular << " mirrors/dielectrics) on top";
            reason << "; patches are one-sided: the front (the winding side) exchanges light, "
                      "the backs of quads and open meshes get direct light only";
            if (c.diffuse_spheres > 0)
                reason << "; " << c.diffuse_spheres
                       << " Phong spheres: not patches, direct light only (they still block)";
            reason << "; " << media_role(scene)
                   << (scene.media.empty() ? "" : " along eye rays, not in the exchange");
            if (!s.cache.empty())
                reason << "; cache " << s.cache;
            return {"global-illumination", true, reason.str()};
        }
        case GiMode::Path:
            reason << "reference path tracer (max depth " << r.path.max_depth
                   << ", Russian roulette from bounce " << r.path.rr_depth << ") over all "
                   << scene.shapes.size() << " shapes (" << c.specular << " mirrors/dielectrics, "
                   << c.emissive << " emissive, next-event estimation with MIS); "
                   << media_role(scene);
            return {"global-illumination", true, reason.str()};
        case GiMode::Photons: {
            const PhotonSettings& p = r.photons;
            reason << "photon maps: " << p.global_count << " global, " << p.caustic_count
                   << " caustic, " << (scene.media.empty() ? 0 : p.volume_count)
                   << " volume photons emitted; k " << p.k << ", " << p.final_gather_samples
                   << " final-gather rays; shadow photons ";
            if (p.shadow_count > 0)
                reason << p.shadow_count << " (k " << p.shadow_k << ")";
            else
                reason << "off";
            return {"global-illumination", true, reason.str()};
        }
    }
    return {"global-illumination", false, ""};
}

void add_gi_summary(Plan& plan, const std::string& summary) {
    for (PlanStage& stage : plan.stages) {
        if (stage.name == "global-illumination")
            stage.reason += "; " + summary;
    }
}

}  // namespace kasumi
