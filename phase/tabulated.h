#pragma once
/// A measured or precomputed phase function read from a table of (θ, value); see PhaseTable
/// for the interpolation (linear in mu) and the exact sampling. The table is shared, so copies
/// of the model are cheap.
#include "phase/phase_table.h"

#include <memory>
#include <string>

namespace kasumi {

struct Tabulated {
    std::shared_ptr<const PhaseTable> table;
    std::string source;  ///< file the table came from (for messages)
};

float eval(const Tabulated& p, float mu);
/// The table's p(mu) in double precision; eval() is this value rounded to float.
double eval_precise(const Tabulated& p, double mu);
float pdf(const Tabulated& p, float mu);
PhaseSample sample(const Tabulated& p, const Vec3& wo, Vec2 u);
float mean_cosine(const Tabulated& p);

}  // namespace kasumi
