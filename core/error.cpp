#include "core/error.h"

#include <cstdio>
#include <cstdlib>

namespace kasumi {

void check_failed(const char* condition, const char* file, int line) {
    std::fprintf(stderr, "kasumi: internal check failed: %s (%s:%d)\n", condition, file, line);
    std::abort();
}

}  // namespace kasumi
