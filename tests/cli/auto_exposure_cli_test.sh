#!/usr/bin/env bash
# `render.preview.exposure_stops: "auto"` (docs/sequences.md#auto-exposure): constant light gets
# a constant exposure; after a step to 10x darker light the smoothed exposure settles exactly
# log2(10) = 3.32 stops higher once the 24-frame window has passed the step; a frame's exposure
# is the same rendered alone (a Slurm task) as in a whole run, and from meterings stored on disk
# by an earlier process; the EXR's pixels do not change
# (absolute), only its kasumi/preview/* metadata; bad values exit 3 naming the JSON pointer.
# usage: auto_exposure_cli_test.sh KASUMI_BINARY SOURCE_DIR
set -u
kasumi="$1"
src="$2"
source "$(dirname "$0")/cli_lib.sh"
header="$src/tests/cli/exr_header.py"

# A lit quad filling the frame (no black background to dilute the log average) under a
# directional light of 1000 lux up to frame 29 and 100 lux from frame 30.
cat >"$work/step.json" <<'JSON'
{"camera": {"position": [0, 2, 0.5], "look_at": [0, 0, 0]},
 "film": {"width": 16, "height": 9, "spp": 1},
 "materials": {"grey": {"type": "phong", "kd": 0.5, "ks": 0.0}},
 "shapes": [{"type": "quad", "material": "grey",
             "vertices": [[-9, 0, 9], [9, 0, 9], [9, 0, -9], [-9, 0, -9]]}],
 "lights": [{"type": "directional", "direction": [0.3, -1, 0.2], "illuminance_lux": 1000}],
 "render": {"preview": {"exposure_stops": "auto"}},
 "animate": {"/lights/0/illuminance_lux": [[29, 1000], [30, 100]]}}
JSON
stops() { python3 "$header" "$work/$1" attr:kasumi/preview/exposure_stops; }
# all_stops DIR FIRST LAST: the exposures of f.FIRST.exr to f.LAST.exr, one a line (one Python).
all_stops() {
  python3 - "$header" "$work/$1" "$2" "$3" <<'PY'
import importlib.util, sys
spec = importlib.util.spec_from_file_location("exr_header", sys.argv[1])
exr = importlib.util.module_from_spec(spec)
spec.loader.exec_module(exr)
for f in range(int(sys.argv[3]), int(sys.argv[4]) + 1):
    attrs = exr.read_attributes(f"{sys.argv[2]}/f.{f:04d}.exr")
    print(exr.attribute(attrs, "kasumi/preview/exposure_stops"))
PY
}

expect_exit 0 "auto exposure: [0-9]+ meter renders" -- sequence "$work/step.json" \
  --frames 0-59 -o "$work/s/f.####.exr" --preview-dir "$work/p" --no-contact-sheet --threads 1
# Constant light, constant exposure: every frame before the step, to the bit.
[ "$(all_stops s 0 29 | sort -u | wc -l)" -eq 1 ] ||
  fail "frames 0-29 (constant light) have different exposures"
[ "$(python3 "$header" "$work/s/f.0000.exr" attr:kasumi/preview/exposure)" = auto ] ||
  fail "the EXR does not say its preview exposure was metered"
# The step: 10x darker light needs log2(10) = 3.3219 more stops once frame 30 + 23 is reached,
# and the exposure moves monotonically in between (smoothed, no overshoot).
ramp=($(all_stops s 29 59))  # frames 29 (before the step) to 59
python3 - "${ramp[0]}" "${ramp[24]}" "${ramp[30]}" "${ramp[@]:0:25}" <<'PY' || fail "step"
import math, sys
before, settled, later = map(float, sys.argv[1:4])
ramp = list(map(float, sys.argv[4:]))
gain = settled - before
if abs(gain - math.log2(10)) > 1e-5:
    sys.exit(f"exposure after the 10x step rose {gain} stops, expected {math.log2(10)}")
if settled != later:
    sys.exit(f"exposure moved after settling: {settled} then {later}")
if any(b < a for a, b in zip(ramp, ramp[1:])) or not ramp[1] < settled:
    sys.exit(f"not a smooth monotone ramp: {ramp}")
PY
# A frame rendered alone (a Slurm task of one frame) gets the exposure of the whole run.
expect_exit 0 "" -- sequence "$work/step.json" --frames 0-59 --frame 40 -o "$work/one/f.####.exr" -q \
  --threads 1
[ "$(stops one/f.0040.exr)" = "$(stops s/f.0040.exr)" ] ||
  fail "frame 40 alone: $(stops one/f.0040.exr), in the run: $(stops s/f.0040.exr)"
# -q: nothing on stderr, not even the meter renders' progress (they metered here: a new directory).
[ ! -s "$work/stderr" ] || fail "sequence -q printed: $(head -c 300 "$work/stderr")"
# The store of meterings beside the frames (sequence/meter_store.h): one file per distinct
# document (1000 lux and 100 lux), read by a later process instead of metering again, with
# exactly the exposure of the run; unreadable files are misses, metered again and replaced.
[ "$(ls "$work/s/.kasumi-meter" | wc -l)" -eq 2 ] ||
  fail "expected 2 stored meterings, got: $(ls "$work/s/.kasumi-meter")"
expect_exit 0 "auto exposure: 0 meter renders .* 2 meterings read from the store" -- sequence \
  "$work/step.json" --frames 0-59 --frame 40 -o "$work/s/g.####.exr" --threads 1
[ "$(stops s/g.0040.exr)" = "$(stops s/f.0040.exr)" ] ||
  fail "frame 40 from stored meterings: $(stops s/g.0040.exr), metered: $(stops s/f.0040.exr)"
for f in "$work"/s/.kasumi-meter/*.json; do printf '{"log2_lumin' >"$f"; done
expect_exit 0 "auto exposure: 2 meter renders .* 0 meterings read from the store" -- sequence \
  "$work/step.json" --frames 0-59 --frame 41 -o "$work/s/h.####.exr" --threads 1
[ "$(stops s/h.0041.exr)" = "$(stops s/f.0041.exr)" ] || fail "frame 41 after a corrupt store"
for f in "$work"/s/.kasumi-meter/*.json; do
  python3 -c "import json, sys; json.load(open(sys.argv[1]))" "$f" || fail "$f was not replaced"
done
# The EXR stays absolute: the same pixels with a fixed exposure.
expect_exit 0 "" -- sequence "$work/step.json" --frames 40 -o "$work/fixed/f.####.exr" -q --threads 1 \
  --set /render/preview/exposure_stops=-3
python3 "$src/tests/cluster/exr_pixels.py" compare "$work/fixed" "$work/one" >/dev/null ||
  fail "auto exposure changed the EXR's pixels"
# `kasumi render` meters its own frame: a preview of mid grey on average, not black or white.
expect_exit 0 "" -- render "$work/step.json" --frame 45 -o "$work/r.exr" --preview "$work/r.png" -q \
  --threads 1
r_stops="$(python3 "$header" "$work/r.exr" attr:kasumi/preview/exposure_stops)"
python3 -c "import sys; sys.exit(not -20 < $r_stops < 12)" || fail "render: exposure $r_stops"

# Bad values: exit 3, the file and the pointer named; nothing written.
expect_exit 3 "step.json: /render/preview/exposure_stops = \"autox\": expected a number of stops in \[-64, 64\] or \"auto\"" \
  -- sequence "$work/step.json" --frames 0-1 -o "$work/bad/f.####.exr" \
  --set '/render/preview/exposure_stops="autox"'
expect_exit 3 "/render/preview/exposure_stops = 1e\+?39" -- sequence "$work/step.json" \
  --frames 0-1 -o "$work/bad/f.####.exr" --set /render/preview/exposure_stops=1e39
expect_exit 3 "/render/preview/exposure_stops = 200" -- render "$work/step.json" \
  -o "$work/bad/r.exr" --set /render/preview/exposure_stops=200
[ -e "$work/bad" ] && fail "a bad exposure wrote output"

finish auto_exposure_cli
