#pragma once
/// Preview exposure that follows the light over a sequence (`render.preview.exposure_stops:
/// "auto"`, docs/sequences.md#auto-exposure). Each frame is metered on a small render of its
/// own (the meter render: kMeterWidth pixels wide, kMeterSpp samples, random numbers of frame 0
/// so equal documents meter equal), by core/exposure_meter.h; the exposure of frame n smooths
/// the log luminance of frames n, n-1, ..., n-W+1 (frames >= 0) with weights exp(-j / tau).
/// The window is finite and the meter render does not depend on --res or --spp, so a frame's
/// exposure depends only on the scene and its number: the same whatever the chunking of a
/// Slurm array, whichever frames a task renders, or whether it runs alone (--frame N).
#include "scene/scene_loader.h"
#include "sequence/meter_store.h"
#include "sequence/sequence_cache.h"

#include <cstdint>
#include <functional>
#include <map>
#include <string>

namespace kasumi {

/// The time constant of the smoothing, in frames (0.25 s at 24 fps): a step in the light is
/// followed to 1 - e^-1 = 63% after 6 frames.
inline constexpr double kAutoExposureTimeConstantFrames = 6.0;
/// The frames a frame's exposure looks at, itself included: 4 time constants (the weights cut
/// off hold e^-4 = 1.8% of the infinite filter's); a step is followed fully after 23 frames.
inline constexpr int kAutoExposureWindowFrames = 24;
/// The meter render's width in pixels (height from the film's aspect, at least 1).
inline constexpr int kMeterWidth = 64;
/// The meter render's samples per pixel.
inline constexpr int kMeterSpp = 4;

/// The smoothed log2 luminance of `frame`: sum_j w_j m(frame - j) / sum_j w_j over j in
/// [0, kAutoExposureWindowFrames) with frame - j >= 0, w_j = exp(-j / tau); `log2_meter`
/// gives a frame's log2 average luminance. Equal meterings give exactly that metering.
double smoothed_log2_luminance(int64_t frame, const std::function<double(int64_t)>& log2_meter);

/// Meters and smooths the frames of one scene; remembers every metering it made.
class AutoExposure {
  public:
    /// `source` must outlive this. `reuse`: keep the BVH and sky tables between meter renders;
    /// `threads`: of the meter renders (0: the scene's render.threads); `store_dir`: where
    /// meterings are kept between processes (sequence/meter_store.h; empty: nowhere).
    AutoExposure(const SceneSource& source, const std::string& scene_path, bool reuse, int threads,
                 const std::string& store_dir = {});

    /// The preview exposure of `frame` in stops: metered_exposure_stops of its smoothed log2
    /// luminance. Throws the input errors of the frames' documents.
    float exposure_stops(int64_t frame);

    /// log2 average luminance (cd/m2) of `frame`'s meter render.
    double log2_luminance(int64_t frame);

    size_t meter_renders() const { return m_renders; }    ///< meter renders made so far
    double meter_seconds() const { return m_seconds; }    ///< their wall time (build + render)
    size_t stored_meterings() const { return m_stored; }  ///< meterings read from the store
    /// Why the store could not be written (the first failure), or empty.
    const std::string& store_problem() const { return m_store_problem; }

  private:
    const SceneSource& m_source;
    std::string m_scene_path;
    bool m_reuse;
    int m_threads;
    SequenceCache m_cache;
    MeterStore m_store;
    std::map<int64_t, double> m_by_frame;
    std::map<std::string, double> m_by_document;  ///< by the frame document's JSON text
    size_t m_renders = 0;
    double m_seconds = 0.0;
    size_t m_stored = 0;
    std::string m_store_problem;
};

}  // namespace kasumi
