#pragma once
/// Render options for tests: `threads` workers, no progress line.
#include "render/renderer.h"

namespace kasumi {

inline RenderOptions quiet(int threads) {
    RenderOptions o;
    o.threads = threads;
    o.progress = false;
    return o;
}

}  // namespace kasumi
