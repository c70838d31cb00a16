#include "phase/tabulated.h"

namespace kasumi {

double eval_precise(const Tabulated& p, double mu) {
    return p.table->eval(mu);
}

float eval(const Tabulated& p, float mu) {
    return static_cast<float>(eval_precise(p, mu));
}

float pdf(const Tabulated& p, float mu) {
    return eval(p, mu);
}

PhaseSample sample(const Tabulated& p, const Vec3& wo, Vec2 u) {
    return sample_phase_table(*p.table, wo, u);
}

float mean_cosine(const Tabulated& p) {
    return static_cast<float>(p.table->mean_cosine());
}

}  // namespace kasumi
