#include "phase/isotropic.h"

#include "core/sampling.h"

namespace kasumi {

float eval(const Isotropic&, float) {
    return kInv4Pi;
}
double eval_precise(const Isotropic&, double) {
    return 1.0 / (4.0 * kPiD);
}
float pdf(const Isotropic&, float) {
    return kInv4Pi;
}
PhaseSample sample(const Isotropic&, const Vec3&, Vec2 u) {
    return PhaseSample{sample_uniform_sphere(u), kInv4Pi, kInv4Pi};
}
float mean_cosine(const Isotropic&) {
    return 0.0f;
}

}  // namespace kasumi
