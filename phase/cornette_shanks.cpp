#include "phase/cornette_shanks.h"

#include "phase/draine.h"

namespace kasumi {

float eval(const CornetteShanks& p, float mu) {
    return eval(Draine{p.g, 1.0f}, mu);
}

double eval_precise(const CornetteShanks& p, double mu) {
    return eval_precise(Draine{p.g, 1.0f}, mu);
}

float pdf(const CornetteShanks& p, float mu) {
    return eval(p, mu);
}

PhaseSample sample(const CornetteShanks& p, const Vec3& wo, Vec2 u) {
    return sample(Draine{p.g, 1.0f}, wo, u);
}

float mean_cosine(const CornetteShanks& p) {
    return mean_cosine(Draine{p.g, 1.0f});
}

}  // namespace kasumi
