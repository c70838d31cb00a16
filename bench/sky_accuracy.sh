#!/usr/bin/env bash
# Fast sky, accuracy and speed in one table (issue #22, part 3): per sun elevation the PSNR of
# luminance over the dome against the reference (its own noise taken out by two independent
# halves), the diagnostic PSNRs (single scattering alone, marched instead of the sky-view table)
# and the median time of a 1280 x 720 frame of data/scenes/sunset.json with that sun. The
# references are cached in /tmp/kasumi_sky_accuracy (--cache none to recompute).
# Prints the machine's load average before and after: on a shared machine compare CPU times.
#   bench/sky_accuracy.sh [BUILD_DIR] [sky_accuracy options: --suns 2,10,30,60,-2,-4
#                         --rings N --azimuths N --paths N --orders N --reps N --no-frame]
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$here/build/release}"
shift || true
bench="$build/bench/sky_accuracy"
if [[ ! -x "$bench" ]]; then
    echo "build the target first: cmake --build $build --target sky_accuracy" >&2
    exit 2
fi
echo "machine: $(nproc) cores; load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
cd "$here"
"$bench" "$@"
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
