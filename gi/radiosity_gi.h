#pragma once
/// Radiosity (render.gi = "radiosity"): the Phong quads, boxes and meshes are cut into patches
/// (gi/patch_tree.h), lit directly by every light (shadow rays from stratified points on
/// each patch: point, spot, goniometric, directional, line, polygon and sphere lights are the
/// primary sources, so the first bounce is in the solution) and by emissive materials, coupled by
/// form factors cast through Embree with visibility (gi/form_factor.h: point-to-polygon,
/// Lambert's closed form times the visible fraction), and solved per RGB by shooting or
/// Gauss-Seidel (gi/radiosity_solver.h). Then, max_subdivision times, every patch whose
/// Gouraud corner values differ from its own radiance by more than refine_threshold (relative) is
/// split in four and the system solved again: the patches follow shadow boundaries and other
/// fast changes. The solution is view independent: render.radiosity.cache saves it and later runs
/// (every frame of a sequence) load it when the scene's geometry, materials, lights and settings
/// are unchanged.
///
/// At render time a Phong hit on a patch's front side gets the radiosity interpolated across the
/// patch corners (Gouraud), plus the Phong specular highlights of the lights (shadow rays), plus
/// the ambient term; mirrors and glass reflect and refract it by Whitted rays (render/whitted.h).
/// Left out of the exchange, and so stated in the plan: light through mirrors and glass (they
/// only block), specular-to-diffuse transport, Phong spheres (direct light only), the back
/// sides of quads and open meshes (direct light only), and media (applied along eye rays only).
#include "gi/patch_tree.h"
#include "render/gi_method.h"
#include "render/whitted.h"

#include <optional>

namespace kasumi {

struct RadiosityStats {
    size_t patches = 0;          ///< leaves of the final solution
    size_t coarse_patches = 0;   ///< before adaptive refinement
    int refinement_levels = 0;   ///< adaptive levels that split at least one patch
    int iterations = 0;          ///< shots or sweeps of the final solve
    double residual = 0.0;       ///< relative residual of the final solution
    double solve_seconds = 0.0;  ///< form factors, direct light and solves, all levels
    bool from_cache = false;
    std::string cache_note;  ///< what happened with render.radiosity.cache
};

class RadiosityGi final : public GiMethod, public PhongShading {
  public:
    explicit RadiosityGi(const SceneRuntime& scene);

    /// Whitted's shade_hit with this solution at Phong surfaces (mirrors and glass reflect and
    /// refract it).
    Rgb surface_radiance(const SceneRuntime& scene, const Ray& ray, const SurfaceHit& hit,
                         Pcg32& rng, RenderCounters& counters) const override;
    /// The interpolated radiosity plus the lights' Phong highlights; shade_surface where the hit
    /// is not on the front of a patch.
    Rgb phong_radiance(const SceneRuntime& scene, const Ray& ray, const SurfaceHit& hit, Pcg32& rng,
                       RenderCounters& counters) const override;
    std::string summary() const override;

    const RadiosityStats& stats() const { return m_stats; }
    const PatchTree& tree() const { return *m_tree; }
    /// The interpolated reflected radiance (emission excluded) at a hit seen from `wo`; empty
    /// where the hit is not on the front of a patch.
    std::optional<Rgb> reflected_radiance(const SurfaceHit& hit, const Vec3& wo) const;

  private:
    void solve(const SceneRuntime& scene);
    bool load_cache(const std::string& path, uint64_t fingerprint);
    void save_cache(const std::string& path, uint64_t fingerprint) const;

    std::unique_ptr<PatchTree> m_tree;
    std::vector<int32_t> m_face_base;  ///< per shape: its first face in the tree, or -1
    std::vector<bool> m_shape_is_mesh;
    std::vector<uint32_t> m_splits;  ///< adaptive splits in order (replayed from the cache)
    RadiosityStats m_stats;
};

}  // namespace kasumi
