#pragma once
/// The scene description: plain values read from a scene file and validated, before anything
/// is built. Units: metres, lux, candela, cd/m², 1/m.
#include "core/camera.h"
#include "core/exr_io.h"
#include "lights/light.h"
#include "scene/gi_settings.h"
#include "scene/photon_settings.h"
#include "scene/quality.h"
#include "sky/sky_scene.h"
#include "surface/material.h"
#include "surface/shape.h"
#include "volume/in_scattering.h"
#include "volume/medium.h"

#include <cstdint>
#include <string>
#include <vector>

namespace kasumi {

/// film.denoise: the consistent non-local-means filter of the beauty (render/denoise/nlm_filter.h).
struct DenoiseSettings {
    bool enabled = false;    ///< "off" (false) or "nlm"
    int radius = 3;          ///< search window half-width, pixels, [1, 32]
    int patch = 3;           ///< patch half-width, pixels, [0, 8]
    float k = 0.85f;         ///< colour strength: weights fall past ~k standard errors, (0, 4)
    float k_feature = 0.6f;  ///< transmittance feature strength, (0, 16)
    /// true: per pixel, the raw mean or the filter at 1, 2 or 4 times (k, k_feature), whichever
    /// has the least estimated MSE (SURE, render/denoise/sure_selection.h); false: the filter
    /// at (k, k_feature) everywhere
    bool select = false;
};

struct FilmDesc {
    int width = 640;   ///< pixels, 1..16384
    int height = 360;  ///< pixels, 1..16384
    int spp = 16;      ///< samples per pixel, >= 1 (the most a pixel takes when adaptive)
    /// > 0: adaptive sampling (render/adaptive_sampling.h): a pixel stops once the relative
    /// standard error of its mean luminance is below this; 0: every pixel takes spp samples.
    float noise_threshold = 0.0f;
    /// Luminance (cd/m²) below which a pixel's standard error counts relative to this instead of
    /// its mean: black and near-black pixels converge on an absolute error.
    float noise_floor_cd_m2 = 1e-3f;
    int min_spp = 16;  ///< adaptive: samples every pixel takes before it may stop, >= 2
    /// adaptive: radius (pixels, [0, 16]) of the neighbours whose pilot samples fix a pixel's
    /// count (render/adaptive_sampling.h); 0: the pixel's own samples (biased on heavy tails)
    int noise_window = 2;
    bool jitter = true;  ///< false: every sample through the pixel centre (peer comparisons)
    /// EXR pixel type of R, G, B, A (AOVs stay float); half saturates beyond 65504 (exr_io.h)
    ExrPixelType pixel_type = ExrPixelType::Float;
    DenoiseSettings denoise;  ///< film.denoise (default off)
};

struct PreviewDesc {
    std::string view = "ACES 1.0 - SDR Video";  ///< OCIO view of the sRGB display
    float exposure_stops = 0.0f;  ///< scene-linear gain 2^stops before the view, [-64, 64]
    /// exposure_stops "auto": metered per frame (core/exposure_meter.h), smoothed over a
    /// sequence (sequence/auto_exposure.h); exposure_stops is then unused.
    bool exposure_auto = false;
};

/// Whitted recursion through mirrors and dielectrics (render/whitted.h).
struct WhittedSettings {
    int max_depth = 5;         ///< specular bounces after the camera ray's first hit, [0, 64]
    float min_weight = 1e-3f;  ///< a branch whose path weight falls below this is not traced
};

/// What finds the camera's visible surfaces (render.surface).
enum class SurfaceMethod {
    Ray,       ///< a primary ray per camera sample through Embree (the default)
    Scanline,  ///< a scanline renderer of polygons (surface/scanline/scanline_surface.h)
};

struct RenderSettings {
    uint64_t seed = 0;
    int threads = 0;                             ///< 0: all hardware threads
    int tile_size = 16;                          ///< pixels
    bool shadows = true;                         ///< shadow rays for surfaces and media
    SurfaceMethod surface = SurfaceMethod::Ray;  ///< render.surface: "ray" or "scanline"
    VolumeSettings volume;
    WhittedSettings whitted;
    SkySettings sky;           ///< render.sky, render.spectral, render.wavelengths_nm (docs/sky.md)
    GiMode gi = GiMode::None;  ///< render.gi: global illumination method
    PathSettings path;
    RadiositySettings radiosity;
    PhotonSettings photons;  ///< render.photons (scene/photon_settings.h)
    PreviewDesc preview;
    QualityChoice quality;  ///< render.quality and what it set (scene/quality.h)
};

struct SceneDesc {
    std::string file;      ///< the scene file, as given
    std::string base_dir;  ///< directory relative paths resolve against
    CameraDesc camera;
    FilmDesc film;
    std::vector<std::string> material_names;
    std::vector<Material> materials;
    std::vector<Shape> shapes;
    std::vector<Light> lights;
    std::vector<Medium> media;
    Rgb ambient{0.0f};     ///< ambient radiance (cd/m²) that the Phong ka term reflects
    Rgb background{0.0f};  ///< radiance (cd/m²) of rays that leave the scene
    std::shared_ptr<const SkyScene> sky;  ///< "atmosphere" + "sun"; null without an atmosphere
    RenderSettings render;
};

}  // namespace kasumi
