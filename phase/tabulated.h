#pragma once
/// A measured or precomputed phase function read from a table of (θ, value); see PhaseTable
/// for the interpolation (linear in mu) and the exact sampling. The table is shared, so copies
/// of the model are cheap; eval, pdf, sample and mean_cosine are TablePhase's.
#include "phase/phase_table.h"

#include <string>

namespace kasumi {

struct Tabulated : TablePhase {
    std::string source;  ///< file the table came from (for messages)
};

}  // namespace kasumi
