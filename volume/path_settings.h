#pragma once
/// render.volume's choices for the volume path tracer's multiple scattering
/// (volume/scattered_paths.h, volume/volume_path.h). Every choice is unbiased.

namespace kasumi {

/// Where the camera segment's transmittance (T in L = L_volume + T L_surface) comes from
/// (render.volume.camera_transmittance).
enum class CameraTransmittance {
    Walk,         ///< a separate walk by render.volume.estimator (low variance, one more walk)
    FirstFlight,  ///< the path's first free flight's escape weight: no extra walk, noisier T
};

/// Russian roulette and splitting of scattered paths (render.volume.splitting).
enum class PathSplitting {
    Off,  ///< Russian roulette on the throughput from the third scattering event
    Sun,  ///< a weight window on throughput x the cached sun transmittance (volume/weight_window.h)
    /// a weight window on throughput x the radiance learnt by guiding's training passes,
    /// centred on the pixel's training estimate (volume/weight_window.h)
    Guided,
};

}  // namespace kasumi
