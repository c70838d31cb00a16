#include "gi/photon/photon_tracer.h"

#include "core/sampling.h"
#include "surface/fresnel.h"
#include "surface/phong_brdf.h"
#include "volume/transmittance.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <chrono>

namespace kasumi {

namespace {

/// Photons per parallel task: large enough to amortise the task, small enough to balance.
constexpr uint64_t kPhotonsPerTask = 2048;

/// Russian roulette by the largest channel of the scattered power relative to the power the
/// photon had before (Jensen 2001, §5.2.1): survivors are scaled back, so stored photons keep
/// roughly their emitted power. Returns false when the photon is absorbed.
bool roulette(Rgb& power, const Rgb& scaled, Pcg32& rng) {
    const float before = max_component(power);
    const float after = max_component(scaled);
    if (!(after > 0.0f) || !(before > 0.0f))
        return false;
    const float survive = std::min(1.0f, after / before);
    if (!(rng.next_float() < survive))
        return false;
    power = scaled / survive;
    return true;
}

struct PathState {
    Ray ray;
    Rgb power{0.0f};
    bool direct = true;         ///< no event yet
    bool specular_only = true;  ///< every event so far a mirror or dielectric
};

/// Phong at a photon hit: diffuse (cosine-weighted) or specular (the normalised Phong lobe
/// about the mirror direction, pdf (n + 1)/(2π) cos^n α) chosen with probabilities from the
/// reflectances times the power (Jensen 2001, §5.2.1); false when absorbed.
bool scatter_phong(const PhongMaterial& m, const Vec3& ns, const Vec3& ng, PathState& s,
                   Pcg32& rng) {
    const Vec3 wi = -s.ray.direction;
    const float cos_i = std::max(0.0f, glm::dot(ns, wi));
    const Rgb w_spec = specular_reflectance(m, cos_i);
    const float max_power = max_component(s.power);
    float p_d = max_component(m.kd * s.power) / max_power;
    float p_s = max_component(w_spec * s.power) / max_power;
    if (p_d + p_s > 1.0f) {
        const float scale = 1.0f / (p_d + p_s);
        p_d *= scale;
        p_s *= scale;
    }
    const float u = rng.next_float();
    Vec3 d;
    if (u < p_d) {
        d = Frame(ns).to_world(sample_cosine_hemisphere(rng.next_vec2()));
        s.power *= m.kd / p_d;
    } else if (u < p_d + p_s) {
        d = sample_specular_lobe(reflect(wi, ns), m.n, rng.next_vec2());
        const float cos_o = glm::dot(ns, d);
        if (!(cos_o > 0.0f))
            return false;
        // f cos / pdf = W (n + 2)/(n + 1) cos θ (the cos^n α of f and pdf cancel).
        s.power *= w_spec * ((m.n + 2.0f) / (m.n + 1.0f) * cos_o / p_s);
    } else {
        return false;
    }
    if (!(glm::dot(ng, d) > 0.0f))
        return false;  // below the true surface (shading normal differs): absorbed
    s.ray.direction = d;
    return true;
}

/// The shadow pass for one photon: its line from the light through every surface (the same
/// surfaces that block shadow rays), a direct-illumination photon at the first hit and a shadow
/// photon at each hit behind it, kept at Phong surfaces (the only ones shade_surface lights).
void trace_shadow_line(const SurfaceScene& surfaces, const std::vector<Material>& materials,
                       const EmittedPhoton& emitted, int max_hits, std::vector<Photon>& out) {
    Ray ray = emitted.ray;
    const Vec3 wi = -ray.direction;
    for (int n = 0; n < max_hits; ++n) {
        const std::optional<SurfaceHit> hit = surfaces.intersect(ray);
        if (!hit)
            return;
        if (std::holds_alternative<PhongMaterial>(materials[hit->material]))
            out.push_back(
                {hit->position, wi, Rgb(0.0f), static_cast<uint16_t>(emitted.source), n > 0});
        ray = Ray{offset_ray_origin(*hit, ray.direction), ray.direction, 0.0f, kInfinity};
    }
}

}  // namespace

BoundingSphere scene_bounding_sphere(const SceneRuntime& scene) {
    Bounds3 bounds;
    if (scene.surfaces() != nullptr)
        bounds.extend(scene.surfaces()->bounds());
    for (const Medium& m : scene.desc().media) {
        if (const auto* h = std::get_if<HomogeneousMedium>(&m.model)) {
            if (h->bounds)
                bounds.extend(*h->bounds);
        } else if (const auto* v = std::get_if<VdbMedium>(&m.model)) {
            bounds.extend(v->bounds_world);
        } else if (const auto* f = std::get_if<HeightFogMedium>(&m.model)) {
            if (f->bounds)
                bounds.extend(*f->bounds);
        }
    }
    BoundingSphere sphere;
    if (bounds.empty())
        return sphere;
    sphere.center = 0.5f * (bounds.min + bounds.max);
    sphere.radius = 0.5f * glm::length(bounds.extent());
    return sphere;
}

void collect_emissive_surfaces(const SceneRuntime& scene, std::vector<EmissiveTriangle>& triangles,
                               std::vector<EmissiveSphere>& spheres) {
    triangles.clear();
    spheres.clear();
    const SceneDesc& desc = scene.desc();
    for (const Shape& shape : desc.shapes) {
        const Rgb radiance = emission(desc.materials[shape.material]);
        if (is_black(radiance))
            continue;
        auto quad = [&](const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
            triangles.push_back({a, b, c, radiance});
            triangles.push_back({a, c, d, radiance});
        };
        if (const auto* sphere = std::get_if<SphereShape>(&shape.geometry)) {
            spheres.push_back({sphere->center, sphere->radius, radiance});
        } else if (const auto* q = std::get_if<QuadShape>(&shape.geometry)) {
            quad(q->vertices[0], q->vertices[1], q->vertices[2], q->vertices[3]);
        } else if (const auto* box = std::get_if<BoxShape>(&shape.geometry)) {
            // Six faces wound counter-clockwise seen from outside (outward front normals).
            const Vec3 lo = box->min, hi = box->max;
            quad({lo.x, lo.y, lo.z}, {lo.x, lo.y, hi.z}, {lo.x, hi.y, hi.z}, {lo.x, hi.y, lo.z});
            quad({hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, hi.y, hi.z}, {hi.x, lo.y, hi.z});
            quad({lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, lo.y, hi.z}, {lo.x, lo.y, hi.z});
            quad({lo.x, hi.y, lo.z}, {lo.x, hi.y, hi.z}, {hi.x, hi.y, hi.z}, {hi.x, hi.y, lo.z});
            quad({lo.x, lo.y, lo.z}, {lo.x, hi.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, lo.y, lo.z});
            quad({lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z});
        } else if (const auto* mesh = std::get_if<MeshShape>(&shape.geometry)) {
            for (const auto& t : mesh->mesh.triangles)
                triangles.push_back({mesh->mesh.positions[t[0]], mesh->mesh.positions[t[1]],
                                     mesh->mesh.positions[t[2]], radiance});
        }
    }
}

std::vector<Photon> trace_photons(const SceneRuntime& scene, const PhotonEmitter& emitter,
                                  PhotonPass pass, int max_bounces, uint64_t seed, int threads) {
    const uint64_t count = emitter.count();
    const uint64_t tasks = (count + kPhotonsPerTask - 1) / kPhotonsPerTask;
    std::vector<std::vector<Photon>> stored(tasks);
    const SurfaceScene* surfaces = scene.surfaces();
    const bool media = scene.plan().volume && scene.media().scatters();
    const MediumSet& medium_set = scene.media();
    const auto& materials = scene.desc().materials;
    const uint64_t pass_key = mix64(seed ^ mix64(0x70686f746f6eULL + static_cast<uint64_t>(pass)));

    auto trace_task = [&](uint64_t task) {
        std::vector<Photon>& out = stored[task];
        VolumeCounters vc;
        const uint64_t end = std::min(count, (task + 1) * kPhotonsPerTask);
        for (uint64_t i = task * kPhotonsPerTask; i < end; ++i) {
            Pcg32 rng(pass_key, i);
            const EmittedPhoton emitted = emitter.emit(i, rng);
            if (pass == PhotonPass::Shadow) {
                if (surfaces != nullptr && emitted.source <= 0xffffu && !is_black(emitted.power))
                    trace_shadow_line(*surfaces, materials, emitted, max_bounces, out);
                continue;
            }
            PathState s{emitted.ray, emitted.power, true, true};
            for (int event = 0; event < max_bounces && !is_black(s.power); ++event) {
                std::optional<SurfaceHit> hit;
                if (surfaces != nullptr)
                    hit = surfaces->intersect(s.ray);
                if (media) {
                    const Ray segment{s.ray.origin, s.ray.direction, 0.0f,
                                      hit ? hit->t : kInfinity};
                    const FreeFlight flight = sample_free_flight(
                        medium_set, segment, s.power / max_component(s.power), rng, vc);
                    if (flight.scattered) {
                        if (pass == PhotonPass::Caustic)
                            break;
                        // The flux this collision scatters: the estimate of ∫ T σ_s (·) dt.
                        const PointCoefficients k =
                            medium_set.coefficients(flight.position, flight.media_mask);
                        const Rgb scattered = s.power * flight.weight * k.sigma_s;
                        if (pass == PhotonPass::Volume && !s.direct && !is_black(scattered))
                            out.push_back({flight.position, -s.ray.direction, scattered});
                        // Phase sampling about the travel direction: wo = -d gives wi with
                        // dot(d, wi) = μ distributed as the phase function.
                        const float u_pick = rng.next_float();
                        const MixtureSample next =
                            medium_set.sample_scattering(flight.position, flight.media_mask,
                                                         -s.ray.direction, u_pick, rng.next_vec2());
                        if (!(next.pdf > 0.0f))
                            break;
                        if (!roulette(s.power, s.power * flight.weight * next.scattering / next.pdf,
                                      rng))
                            break;
                        s.ray = Ray{flight.position, next.wi, 0.0f, kInfinity};
                        s.direct = false;
                        s.specular_only = false;
                        continue;
                    }
                    s.power *= flight.weight;  // the transmittance estimate of the crossing
                    if (is_black(s.power))
                        break;
                }
                if (!hit)
                    break;
                const Vec3 wi = -s.ray.direction;
                // Normals on the side the photon arrives from (quads and meshes are two-sided).
                Vec3 ng = hit->geometric_normal, ns = hit->shading_normal;
                const bool front = glm::dot(ng, wi) >= 0.0f;
                if (!front) {
                    ng = -ng;
                    ns = -ns;
                }
                if (glm::dot(ns, wi) <= 0.0f)
                    ns = ng;
                const Material& material = materials[hit->material];
                if (const auto* phong = std::get_if<PhongMaterial>(&material)) {
                    const bool reflects = !is_black(phong->kd) || !is_black(phong->ks);
                    if (pass == PhotonPass::Caustic) {
                        if (reflects && s.specular_only && !s.direct)
                            out.push_back({hit->position, wi, s.power});
                        break;
                    }
                    if (pass == PhotonPass::Global && reflects)
                        out.push_back({hit->position, wi, s.power});
                    if (!scatter_phong(*phong, ns, ng, s, rng))
                        break;
                    s.specular_only = false;
                } else if (const auto* mirror = std::get_if<MirrorMaterial>(&material)) {
                    if (!roulette(s.power, s.power * mirror->kr, rng))
                        break;
                    s.ray.direction = glm::normalize(reflect(wi, ns));
                } else if (const auto* glass = std::get_if<DielectricMaterial>(&material)) {
                    // The shape's normal points outside (relative index 1 there).
                    const float cos_o = glm::dot(hit->shading_normal, wi);
                    const bool outside = cos_o >= 0.0f;
                    const Vec3 n = outside ? hit->shading_normal : -hit->shading_normal;
                    const float eta = outside ? glass->ior : 1.0f / glass->ior;
                    const float reflectance = fresnel_dielectric(cos_o, glass->ior);
                    const std::optional<Vec3> wt =
                        reflectance < 1.0f ? refract(wi, n, eta) : std::nullopt;
                    // Reflect with probability F, else refract (power unchanged in
                    // expectation: F and 1 - F cancel), times the tint on refraction.
                    if (!wt || rng.next_float() < reflectance) {
                        s.ray.direction = glm::normalize(reflect(wi, n));
                    } else {
                        if (!roulette(s.power, s.power * glass->tint, rng))
                            break;
                        s.ray.direction = *wt;
                    }
                }
                s.direct = false;
                s.ray =
                    Ray{offset_ray_origin(*hit, s.ray.direction), s.ray.direction, 0.0f, kInfinity};
            }
        }
    };

    tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
    arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range<uint64_t>(0, tasks, 1),
                          [&](const tbb::blocked_range<uint64_t>& r) {
                              for (uint64_t t = r.begin(); t < r.end(); ++t)
                                  trace_task(t);
                          });
    });
    size_t total = 0;
    for (const auto& v : stored)
        total += v.size();
    std::vector<Photon> photons;
    photons.reserve(total);
    for (auto& v : stored)
        photons.insert(photons.end(), v.begin(), v.end());
    return photons;
}

PhotonMaps build_photon_maps(const SceneRuntime& scene, const PhotonSettings& settings,
                             uint64_t seed, int threads) {
    std::vector<EmissiveTriangle> triangles;
    std::vector<EmissiveSphere> spheres;
    collect_emissive_surfaces(scene, triangles, spheres);
    PhotonEmitter emitter(scene.desc().lights, scene_bounding_sphere(scene), triangles, spheres);
    PhotonMaps maps;
    using Clock = std::chrono::steady_clock;
    PhotonEmitter light_emitter(scene.desc().lights, scene_bounding_sphere(scene));
    auto run = [&](PhotonPass pass, uint64_t count, PhotonMap& map, uint64_t& emitted) {
        PhotonEmitter& source = pass == PhotonPass::Shadow ? light_emitter : emitter;
        source.allot(count);
        emitted = count;
        const auto t0 = Clock::now();
        std::vector<Photon> photons =
            trace_photons(scene, source, pass, settings.max_bounces, seed, threads);
        const auto t1 = Clock::now();
        map = PhotonMap(std::move(photons));
        const auto t2 = Clock::now();
        maps.trace_seconds += std::chrono::duration<double>(t1 - t0).count();
        maps.build_seconds += std::chrono::duration<double>(t2 - t1).count();
    };
    run(PhotonPass::Global, settings.global_count, maps.global, maps.global_emitted);
    run(PhotonPass::Caustic, settings.caustic_count, maps.caustic, maps.caustic_emitted);
    const bool media = scene.plan().volume && scene.media().scatters();
    run(PhotonPass::Volume, media ? settings.volume_count : 0, maps.volume, maps.volume_emitted);
    run(PhotonPass::Shadow, scene.desc().lights.empty() ? 0 : settings.shadow_count, maps.shadow,
        maps.shadow_emitted);
    return maps;
}

}  // namespace kasumi
