#pragma once
/// `render.quality`: a level ("draft", "default", "final", "reference") that fills the sampling
/// settings a scene leaves unset from a table measured by `kasumi study` (docs/study.md), and
/// the choice between single and multiple scattering from the media's albedo and optical
/// thickness with a bound on the light that single scattering leaves out.
#include "core/json_node.h"
#include "scene/scene_document.h"
#include "volume/in_scattering.h"

#include <optional>
#include <string>
#include <vector>

namespace kasumi {

struct Medium;

enum class QualityLevel { Draft, Default, Final, Reference };

std::optional<QualityLevel> quality_from_name(const std::string& name);
const char* quality_name(QualityLevel level);

/// One row of the quality table. Each value was picked from a measured study; the expected
/// errors are the relative MSE (docs/study.md) those settings measured on the study scenes.
struct QualityPreset {
    QualityLevel level;
    int spp;                     ///< film.spp
    double fog_step_m;           ///< render.volume.step_m, with homogeneous media
    const char* grid_estimator;  ///< render.volume.estimator, with VDB media
    int light_samples;           ///< lights/N/samples of line, polygon and sphere lights
    /// Single scattering is chosen when its bound on the light left out is at most this.
    double single_scattering_tolerance;
    double fog_rel_mse;     ///< fog study (fog_street.json)
    double cloud_rel_mse;   ///< cloud study (cloud.json)
    double shadow_rel_mse;  ///< soft-shadow study (soft_shadows.json)
    /// render.volume.step_m with height fog (and no homogeneous medium: that one's step wins)
    double height_fog_step_m;
    const char* height_fog_estimator;  ///< render.volume.estimator, with height fog (no grid)
    double height_fog_rel_mse;         ///< height-fog studies (fog_height.json)
    /// render.volume.estimator with VDB media when the level chooses single scattering
    /// (replaces grid_estimator there; choose_integrator)
    const char* grid_single_estimator;
    /// Multiple scattering in VDB media (choose_integrator): render.volume.shadow_roulette
    /// (0: off) and render.volume.camera_transmittance, from the cloud studies of the three
    /// clouds (quality.cpp).
    float grid_shadow_roulette;
    CameraTransmittance grid_camera_transmittance;
    /// film.noise_threshold with VDB media, set only where the level's film.spp is used (0:
    /// off); adaptive sampling's neighbourhood rule (render/adaptive_sampling.h), from the
    /// same cloud studies (quality.cpp).
    double grid_noise_threshold;
};

const QualityPreset& quality_preset(QualityLevel level);

/// What the quality level did to a scene, for the plan.
struct QualityChoice {
    std::optional<QualityLevel> level;  ///< unset: render.quality absent
    std::vector<std::string> applied;   ///< "/film/spp = 64" set by the level
    std::vector<std::string> kept;      ///< "/film/spp" given by the scene (it wins)
    std::string expected_error;         ///< the studies' figure for these settings
    std::string integrator;             ///< how single vs multiple scattering was decided
};

/// Reads /render/quality (if present) and writes the level's values into every key the
/// document leaves unset: film.spp, render.volume.step_m (homogeneous media, else height fog),
/// render.volume.estimator (VDB media, else height fog), samples of extended lights. Keys
/// already present win.
/// Throws ErrorKind::Input naming the file and /render/quality for an unknown level.
QualityChoice apply_quality(SceneDocument& doc);

/// Bound on the light single scattering leaves out, from the largest single-scattering albedo
/// omega (any channel) and an optical thickness tau of the media. A photon that has scattered
/// once collides again inside the media with probability at most p = 1 - exp(-tau), and each
/// collision scatters a fraction omega; the order-k scattered energy is therefore at most
/// (omega p)^(k - 1) times the single-scattered energy, and summing k >= 2 bounds the
/// multiply-scattered light relative to the single-scattered light by
///     B = omega p / (1 - omega p)
/// (the single-scattering albedo series; with p = 1 it is omega / (1 - omega)).
struct ScatteringBound {
    double albedo = 0.0;         ///< largest sigma_s / sigma_t over media and channels
    double optical_depth = 0.0;  ///< tau: sum over media of sigma_t,max x mean chord
    double bound = 0.0;          ///< B above; infinite when omega p = 1
    bool scatters = false;
};

/// tau uses each medium's mean chord 4 V / S (Cauchy's formula for a convex body, here its
/// box) times its largest extinction (a grid: its maximum density): an estimate for light that
/// crosses the medium at a random position and direction; rays along the longest diagonal see
/// more.
ScatteringBound scattering_bound(const std::vector<Medium>& media);

/// With a quality level and no /render/volume/integrator in `doc`: single scattering when
/// scattering_bound(media).bound is within the level's tolerance, else multiple. Records the
/// reason in choice.integrator. Without a level, or with the integrator given, leaves it.
/// When it chooses single scattering for VDB media and the level (not the scene) set the
/// estimator, the estimator becomes the level's grid_single_estimator (recorded in
/// choice.applied). With multiple scattering (chosen, or given by the scene) in VDB media, it
/// sets render.volume.shadow_roulette and camera_transmittance to the level's values where the
/// scene leaves them unset (recorded in choice.applied or choice.kept).
void choose_integrator(const SceneDocument& doc, const std::vector<Medium>& media,
                       VolumeSettings& volume, QualityChoice& choice);

/// Text for the plan: "omega = 0.93, tau = 1.3: single scattering leaves out <= 150% ...".
std::string scattering_bound_text(const ScatteringBound& b);

}  // namespace kasumi
