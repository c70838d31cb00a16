#!/usr/bin/env bash
# Regenerates tests/data/fog_street_96x54.exr, the reference of render_image_test, on purpose
# (no test writes into the source tree). The reference is made by a different estimator than
# the test's render: ratio tracking (unbiased) for the fog instead of the default jittered
# march, at 2048 samples per pixel, seed 2 (the test renders 16 samples, seed 1). Review the
# test's printed ratios before committing a new reference.
# usage: tests/render/regenerate_image_reference.sh [KASUMI_BINARY]   (default build/ci/apps/kasumi)
set -euo pipefail
src="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
kasumi="${1:-$src/build/ci/apps/kasumi}"
preview="$(mktemp -d)/fog_street_96x54.png"
"$kasumi" render "$src/data/scenes/fog_street.json" --res 96x54 --spp 2048 --seed 2 \
  --set /render/volume/estimator='"ratio"' \
  -o "$src/tests/data/fog_street_96x54.exr" --preview "$preview"
rm -f "$preview"
echo "wrote $src/tests/data/fog_street_96x54.exr; now run render_image_test"
