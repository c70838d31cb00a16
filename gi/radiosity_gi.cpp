#include "gi/radiosity_gi.h"

#include "core/atomic_file.h"
#include "gi/path_tracer.h"
#include "gi/radiosity_solver.h"
#include "render/integrator.h"
#include "render/scene_runtime.h"
#include "surface/phong_brdf.h"

#include <tbb/parallel_for.h>

#include <chrono>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

namespace kasumi {

namespace {

/// Patches in the final solution at most: the form-factor matrix is N² floats (4000: 64 MB).
constexpr size_t kMaxPatches = 4000;

/// FNV-1a, 64 bit, over raw bytes: the cache fingerprint.
class Fingerprint {
  public:
    void add(const void* data, size_t size) {
        const auto* bytes = static_cast<const unsigned char*>(data);
        for (size_t i = 0; i < size; ++i) {
            m_hash ^= bytes[i];
            m_hash *= 1099511628211ULL;
        }
    }
    template <typename T>
    void add(const T& value) {
        add(&value, sizeof(T));
    }
    uint64_t value() const { return m_hash; }

  private:
    uint64_t m_hash = 14695981039346656037ULL;
};

int strata_for(int samples) {
    return std::max(1, static_cast<int>(std::lround(std::sqrt(static_cast<double>(samples)))));
}

/// Mean illuminance (lux) on a patch from all lights, over n × n jittered points, one
/// sample_incident per light per point, shadow rays through the scene's occlusion query.
Rgb patch_irradiance(const SceneRuntime& scene, const FormFactorPatch& patch, int n, Pcg32& rng) {
    const Vec3 normal(patch.normal);
    Rgb sum(0.0f);
    for (int k = 0; k < n * n; ++k) {
        const Vec2 j = rng.next_vec2();
        const Vec3 x(patch_point(patch, (k % n + j.x) / n, (k / n + j.y) / n));
        for (const Light& light : scene.desc().lights) {
            const IncidentLight in = sample_incident(light, x, rng);
            const float cos_theta = glm::dot(normal, in.wi);
            if (is_black(in.irradiance) || cos_theta <= 0.0f)
                continue;
            if (scene.occlusion() != nullptr && light.shadows != ShadowMode::None) {
                const Vec3 origin = offset_ray_origin(x, normal, in.wi);
                const bool blocked = in.distance >= kInfinity
                                         ? scene.occlusion()->occluded_direction(origin, in.wi)
                                         : scene.occlusion()->occluded(origin, in.light_position);
                if (blocked)
                    continue;
            }
            sum += in.irradiance * cos_theta;
        }
    }
    return sum / static_cast<float>(n * n);
}

/// False when one patch lies entirely behind the other's plane (no exchange).
bool may_see(const FormFactorPatch& a, const FormFactorPatch& b) {
    const auto in_front = [](const FormFactorPatch& from, const FormFactorPatch& to) {
        for (int k = 0; k < to.count; ++k) {
            if (glm::dot(from.normal, to.vertices[k] - from.vertices[0]) > 1e-9)
                return true;
        }
        return false;
    };
    return in_front(a, b) && in_front(b, a);
}

}  // namespace

RadiosityGi::RadiosityGi(const SceneRuntime& scene) {
    const SceneDesc& desc = scene.desc();
    require_energy_conserving(desc);
    std::vector<ShapeFace> faces;
    m_face_base.assign(desc.shapes.size(), -1);
    m_shape_is_mesh.assign(desc.shapes.size(), false);
    for (uint32_t s = 0; s < desc.shapes.size(); ++s) {
        const Shape& shape = desc.shapes[s];
        m_shape_is_mesh[s] = std::holds_alternative<MeshShape>(shape.geometry);
        if (is_specular(desc.materials[shape.material]) ||
            std::holds_alternative<SphereShape>(shape.geometry))
            continue;
        m_face_base[s] = static_cast<int32_t>(faces.size());
        for (ShapeFace& f : shape_faces(shape, s))
            faces.push_back(f);
    }
    m_tree = std::make_unique<PatchTree>(std::move(faces), desc.render.radiosity.patch_size_m);
    m_stats.coarse_patches = m_tree->leaves().size();
    solve(scene);
}

void RadiosityGi::solve(const SceneRuntime& scene) {
    const SceneDesc& desc = scene.desc();
    const RadiositySettings& settings = desc.render.radiosity;
    const auto start = std::chrono::steady_clock::now();
    const int n = strata_for(settings.form_factor_samples);
    const SurfaceScene* surfaces = scene.surfaces();

    // L0 = emission + directly reflected light for the current leaves.
    const auto sources = [&](const std::vector<uint32_t>& leaves, RadiositySystem& system) {
        const size_t count = leaves.size();
        system.area.assign(count, 0.0);
        system.rho.assign(count, Rgb(0.0f));
        system.source.assign(count, Rgb(0.0f));
        tbb::parallel_for(size_t(0), count, [&](size_t i) {
            const PatchNode& node = m_tree->nodes()[leaves[i]];
            const FormFactorPatch g = m_tree->geometry(leaves[i]);
            const Material& m = desc.materials[m_tree->faces()[node.face].material];
            const Rgb rho = std::get<PhongMaterial>(m).kd;
            Pcg32 rng(mix64(leaves[i] ^ mix64(desc.render.seed)), 0x9e3779b97f4a7c15ULL);
            system.area[i] = g.area;
            system.rho[i] = rho;
            system.source[i] = emission(m) + rho * kInvPi * patch_irradiance(scene, g, n, rng);
        });
    };

    // The fingerprint covers what the solution depends on: faces, materials, settings and the
    // coarse sources (which change with any light).
    uint64_t fingerprint = 0;
    if (!settings.cache.empty()) {
        Fingerprint fp;
        fp.add("kasumi-radiosity-1", 18);
        for (const ShapeFace& f : m_tree->faces()) {
            fp.add(f.vertices);
            const Material& m = desc.materials[f.material];
            fp.add(std::get<PhongMaterial>(m).kd);
            fp.add(emission(m));
        }
        fp.add(settings.patch_size_m);
        fp.add(settings.max_subdivision);
        fp.add(settings.refine_threshold);
        fp.add(settings.solver);
        fp.add(settings.tolerance);
        fp.add(settings.max_iterations);
        fp.add(settings.form_factor_samples);
        fp.add(desc.render.seed);
        RadiositySystem coarse;
        sources(m_tree->leaves(), coarse);
        for (const Rgb& s : coarse.source)
            fp.add(s);
        fingerprint = fp.value();
        if (load_cache(settings.cache, fingerprint)) {
            m_stats.solve_seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            return;
        }
    }

    for (int level = 0;; ++level) {
        const std::vector<uint32_t> leaves = m_tree->leaves();
        const size_t count = leaves.size();
        RadiositySystem system;
        sources(leaves, system);
        std::vector<FormFactorPatch> geometry(count);
        for (size_t i = 0; i < count; ++i)
            geometry[i] = m_tree->geometry(leaves[i]);
        system.form_factor.assign(count * count, 0.0f);
        tbb::parallel_for(size_t(0), count, [&](size_t i) {
            for (size_t j = i + 1; j < count; ++j) {
                const PatchNode& ni = m_tree->nodes()[leaves[i]];
                const PatchNode& nj = m_tree->nodes()[leaves[j]];
                if (ni.face == nj.face || !may_see(geometry[i], geometry[j]))
                    continue;
                // Integrate over the smaller patch (the point-to-polygon rule is exact in the
                // other), then reciprocity A_i F_ij = A_j F_ji gives the reverse factor.
                const bool i_small = geometry[i].area <= geometry[j].area;
                const FormFactorPatch& from = i_small ? geometry[i] : geometry[j];
                const FormFactorPatch& to = i_small ? geometry[j] : geometry[i];
                Pcg32 rng(mix64((static_cast<uint64_t>(i) << 32) | j), 0xda3e39cb94b95bdbULL);
                const Vec3 n_from(from.normal);
                const auto visible = [&](const DVec3& x, const DVec3& y) {
                    if (surfaces == nullptr)
                        return true;
                    const Vec3 xf(x), yf(y);
                    const Vec3 d = yf - xf;
                    const float distance = glm::length(d);
                    const Vec3 dir = d / distance;
                    const Vec3 origin = offset_ray_origin(xf, n_from, dir);
                    return !surfaces->occluded(
                        Ray{origin, dir, 0.0f, glm::length(yf - origin) * (1.0f - 1e-4f)});
                };
                const auto jitter = [&] { return static_cast<double>(rng.next_float()); };
                const double f_small = form_factor(from, to, n, visible, jitter);
                const double f_large = f_small * from.area / to.area;
                system.form_factor[i * count + j] = static_cast<float>(i_small ? f_small : f_large);
                system.form_factor[j * count + i] = static_cast<float>(i_small ? f_large : f_small);
            }
        });
        const RadiosityResult result =
            settings.solver == RadiositySolver::Shooting
                ? solve_shooting(system, settings.tolerance, settings.max_iterations)
                : solve_gauss_seidel(system, settings.tolerance, settings.max_iterations);
        for (size_t i = 0; i < count; ++i) {
            PatchNode& node = m_tree->nodes()[leaves[i]];
            node.radiance =
                result.radiance[i] - emission(desc.materials[m_tree->faces()[node.face].material]);
        }
        m_tree->compute_corners();
        m_stats.iterations = result.iterations;
        m_stats.residual = result.residual;
        m_stats.patches = count;
        if (level >= settings.max_subdivision)
            break;
        // Refine where the radiosity changes fast: a patch whose Gouraud corners stray from
        // its own value by more than refine_threshold of max(own, 1% of the mean).
        double mean = 0.0, total_area = 0.0;
        for (size_t i = 0; i < count; ++i) {
            mean += system.area[i] * luminance(result.radiance[i]);
            total_area += system.area[i];
        }
        mean = total_area > 0.0 ? mean / total_area : 0.0;
        std::vector<uint32_t> to_split;
        for (size_t i = 0; i < count; ++i) {
            const PatchNode& node = m_tree->nodes()[leaves[i]];
            if (node.refinement >= settings.max_subdivision)
                continue;
            const float own = luminance(node.radiance);
            float spread = 0.0f;
            for (int k = 0; k < node.corner_count; ++k)
                spread = std::max(spread, std::abs(luminance(node.corner[k]) - own));
            if (spread > settings.refine_threshold * std::max<double>(own, 0.01 * mean))
                to_split.push_back(leaves[i]);
        }
        if (to_split.empty() || count + 3 * to_split.size() > kMaxPatches)
            break;
        for (const uint32_t node : to_split) {
            m_tree->split(node);
            m_splits.push_back(node);
        }
        ++m_stats.refinement_levels;
    }
    m_stats.solve_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!settings.cache.empty())
        save_cache(settings.cache, fingerprint);
}

bool RadiosityGi::load_cache(const std::string& path, uint64_t fingerprint) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        m_stats.cache_note = "cache " + path + " absent: solved and saved";
        return false;
    }
    const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    size_t pos = 0;
    const auto read = [&](void* out, size_t size) {
        if (pos + size > data.size())
            return false;
        std::memcpy(out, data.data() + pos, size);
        pos += size;
        return true;
    };
    char magic[8] = {};
    uint64_t stored = 0, splits = 0, leaves = 0;
    RadiosityStats stats;
    if (!read(magic, 8) || std::memcmp(magic, "KSMRAD01", 8) != 0 || !read(&stored, 8) ||
        stored != fingerprint || !read(&stats.residual, 8) || !read(&stats.iterations, 4) ||
        !read(&stats.refinement_levels, 4) || !read(&splits, 8)) {
        m_stats.cache_note = "cache " + path + " is for another scene or version: solved again";
        return false;
    }
    PatchTree tree = *m_tree;
    std::vector<uint32_t> split_list(splits);
    for (uint32_t& s : split_list) {
        if (!read(&s, 4) || s >= tree.nodes().size() || tree.nodes()[s].first_child >= 0) {
            m_stats.cache_note = "cache " + path + " is damaged: solved again";
            return false;
        }
        tree.split(s);
    }
    const std::vector<uint32_t> leaf_nodes = tree.leaves();
    if (!read(&leaves, 8) || leaves != leaf_nodes.size()) {
        m_stats.cache_note = "cache " + path + " is damaged: solved again";
        return false;
    }
    for (const uint32_t i : leaf_nodes) {
        if (!read(&tree.nodes()[i].radiance, sizeof(Rgb))) {
            m_stats.cache_note = "cache " + path + " is damaged: solved again";
            return false;
        }
    }
    tree.compute_corners();
    *m_tree = std::move(tree);
    m_splits = std::move(split_list);
    m_stats.patches = leaf_nodes.size();
    m_stats.residual = stats.residual;
    m_stats.iterations = stats.iterations;
    m_stats.refinement_levels = stats.refinement_levels;
    m_stats.from_cache = true;
    m_stats.cache_note = "loaded from cache " + path;
    return true;
}

void RadiosityGi::save_cache(const std::string& path, uint64_t fingerprint) const {
    std::string data;
    const auto write = [&](const void* p, size_t size) {
        data.append(static_cast<const char*>(p), size);
    };
    write("KSMRAD01", 8);
    write(&fingerprint, 8);
    write(&m_stats.residual, 8);
    write(&m_stats.iterations, 4);
    write(&m_stats.refinement_levels, 4);
    const uint64_t splits = m_splits.size();
    write(&splits, 8);
    for (const uint32_t s : m_splits)
        write(&s, 4);
    const std::vector<uint32_t> leaf_nodes = m_tree->leaves();
    const uint64_t leaves = leaf_nodes.size();
    write(&leaves, 8);
    for (const uint32_t i : leaf_nodes)
        write(&m_tree->nodes()[i].radiance, sizeof(Rgb));
    write_file_atomic(path, data.data(), data.size());
}

std::string RadiosityGi::summary() const {
    std::ostringstream out;
    out << m_stats.patches << " patches (" << m_stats.coarse_patches << " coarse, "
        << m_stats.refinement_levels << " refinement levels), " << m_stats.iterations
        << (m_tree && m_stats.iterations == 1 ? " iteration" : " iterations") << ", residual "
        << m_stats.residual << ", solve " << m_stats.solve_seconds << " s";
    if (!m_stats.cache_note.empty())
        out << ", " << m_stats.cache_note;
    return out.str();
}

std::optional<Rgb> RadiosityGi::reflected_radiance(const SurfaceHit& hit, const Vec3& wo) const {
    if (hit.shape >= m_face_base.size() || m_face_base[hit.shape] < 0)
        return std::nullopt;
    const uint32_t face = static_cast<uint32_t>(m_face_base[hit.shape]) +
                          (m_shape_is_mesh[hit.shape] ? hit.primitive : hit.primitive / 2);
    const ShapeFace& f = m_tree->faces()[face];
    if (glm::dot(f.normal, wo) <= 0.0f)
        return std::nullopt;  // the back of a one-sided patch
    const Vec2 uv = face_uv(f, hit.primitive, hit.u, hit.v);
    return glm::max(m_tree->interpolate(m_tree->find_leaf(face, uv), uv), Rgb(0.0f));
}

Rgb RadiosityGi::surface_radiance(const SceneRuntime& scene, const Ray& ray, const SurfaceHit& hit,
                                  Pcg32& rng, RenderCounters& counters) const {
    return shade_hit(scene, ray, hit, rng, counters, this);
}

Rgb RadiosityGi::phong_radiance(const SceneRuntime& scene, const Ray& ray, const SurfaceHit& hit,
                                Pcg32& rng, RenderCounters& counters) const {
    const Vec3 wo = -ray.direction;
    const std::optional<Rgb> diffuse = reflected_radiance(hit, wo);
    if (!diffuse)
        return shade_surface(scene, hit, wo, rng, counters);
    const SceneDesc& desc = scene.desc();
    PhongMaterial specular = std::get<PhongMaterial>(desc.materials[hit.material]);
    Rgb radiance = *diffuse;
    if (scene.plan().ambient)
        radiance += specular.ka * desc.ambient;
    if (!(max_component(specular.ks) > 0.0f))
        return radiance;
    // Phong highlights of the lights on top (the diffuse part is in the radiosity).
    specular.kd = Rgb(0.0f);
    Vec3 ns = hit.shading_normal, ng = hit.geometric_normal;
    if (glm::dot(ng, wo) < 0.0f) {
        ns = -ns;
        ng = -ng;
    }
    for (const Light& light : desc.lights) {
        const IncidentLight in = sample_incident(light, hit.position, rng);
        const float cos_theta = glm::dot(ns, in.wi);
        if (is_black(in.irradiance) || cos_theta <= 0.0f || glm::dot(ng, in.wi) <= 0.0f)
            continue;
        const Rgb f = eval(specular, ns, wo, in.wi);
        if (is_black(f))
            continue;
        if (scene.occlusion() != nullptr && light.shadows != ShadowMode::None) {
            ++counters.surface_shadow_rays;
            const Vec3 origin = offset_ray_origin(hit, in.wi);
            const bool blocked = in.distance >= kInfinity
                                     ? scene.occlusion()->occluded_direction(origin, in.wi)
                                     : scene.occlusion()->occluded(origin, in.light_position);
            if (blocked)
                continue;
        }
        radiance += f * in.irradiance * cos_theta;
    }
    return radiance;
}

}  // namespace kasumi
