#!/usr/bin/env bash
# Fast-sky benchmark (issue #6): median time of a 1280x720, 1 spp, fast-mode frame of
# data/scenes/sunset.json (sunset sky, aerial perspective, white wall and ground), the time per
# frame of the 240-frame data/scenes/sunset_sequence.json (EXRs written to a scratch dir), and
# the fast-vs-reference luminance error over the sky dome at the frame's sun elevation.
# Prints the machine's load average before and after: on a shared machine compare CPU times.
#   bench/sky_bench.sh [BUILD_DIR] [sky_bench options: --reps N --frames N --paths N
#                      --aovs all|none|LIST --compression zip|piz|rle|none --write-queue N]
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$here/build/release}"
shift || true
bench="$build/bench/sky_bench"
if [[ ! -x "$bench" ]]; then
    echo "build the target first: cmake --build $build --target sky_bench" >&2
    exit 2
fi
echo "machine: $(nproc) cores; load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
cd "$here"
"$bench" "$@"
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
