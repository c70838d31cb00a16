#pragma once
/// render.volume.guiding: volume path guiding (volume/guiding/guided_scattering.h).

namespace kasumi {

struct GuidingSettings {
    bool enabled = false;
    /// Share of scattering directions drawn from the learnt field, in (0, 1); the rest follow
    /// the phase function (the one-sample mixture keeps every direction the phase reaches).
    float mix = 0.5f;
    int training_passes = 4;  ///< passes over the image that train the field, before the render
    int training_spp = 1;     ///< samples per pixel in each training pass
    int leaf_records = 4000;  ///< a kd-tree node holding more records is split
    /// Share of each leaf's histogram spread over the sphere, in [0, 1): no direction is left
    /// with a density below uniform / (4 pi) where the training saw no light.
    float uniform = 0.2f;
};

}  // namespace kasumi
