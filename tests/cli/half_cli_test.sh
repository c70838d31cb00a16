#!/usr/bin/env bash
# Half-float EXR output: `render --pixel-type half|float` and the scene key film.pixel_type
# write R, G, B, A as HALF (AOVs stay FLOAT); values beyond the half range (65504) are
# saturated to 65504, counted in the file (kasumi/half/saturated), in -v and in a warning; bad
# values are a usage error (option, exit 2) or an invalid scene naming the key (exit 3).
# usage: half_cli_test.sh KASUMI_BINARY SOURCE_DIR
set -u
kasumi="$1"
src="$2"
source "$(dirname "$0")/cli_lib.sh"

# exr_types FILE: "name:type,..." sorted (EXR chlist pixel types uint, half, float), then ";"
# and the kasumi/half/saturated attribute ("-" if absent).
exr_types() { python3 "$(dirname "$0")/exr_header.py" "$1" channel-types attr:kasumi/half/saturated; }

# 4x3 pixels, no surface: every camera ray sees the background, 1e6 cd/m2 (the sun's disc is
# ~1.6e9): 12 pixels x R, G, B beyond the half range; A is 0 (no hit).
cat >"$work/bright.json" <<JSON
{
  "camera": {"position": [0, 1, 5], "look_at": [0, 1, 0]},
  "film": {"width": 4, "height": 3, "spp": 1},
  "background": [1e6, 1e6, 1e6],
  "lights": [{"type": "directional", "direction": [0, -1, 0], "illuminance_lux": 1000}]
}
JSON
expect_exit 0 "warning: .*h\.exr: 36 values of R, G, B, A exceed the half-float range \(largest 1e\+06\)" \
  -- render "$work/bright.json" -o "$work/h.exr" --no-preview --aovs depth --pixel-type half -v
grep -qE "half saturated +36 " "$work/stderr" || fail "-v lacks the saturated count: $(cat "$work/stderr")"
grep -qE "exr pixel type +half" "$work/stderr" || fail "-v lacks the pixel type"
got=$(exr_types "$work/h.exr")
[ "$got" = "A:half,B:half,G:half,R:half,depth.Z:float;36" ] || fail "--pixel-type half: $got"

# Default: float, no half attribute, no warning.
expect_exit 0 "" -- render "$work/bright.json" -o "$work/f.exr" --no-preview --aovs none
grep -q "warning" "$work/stderr" && fail "float output warned: $(cat "$work/stderr")"
got=$(exr_types "$work/f.exr")
[ "$got" = "A:float,B:float,G:float,R:float;-" ] || fail "default pixel type: $got"

# The scene key, and the option overriding it.
expect_exit 0 "" -- render "$work/bright.json" -o "$work/k.exr" --no-preview --aovs none -q \
  --set /film/pixel_type=half --set /background=[0.5,0.5,0.5]
got=$(exr_types "$work/k.exr")
[ "$got" = "A:half,B:half,G:half,R:half;0" ] || fail "film.pixel_type half: $got"
expect_exit 0 "" -- render "$work/bright.json" -o "$work/o.exr" --no-preview --aovs none -q \
  --set /film/pixel_type=half --pixel-type float
got=$(exr_types "$work/o.exr")
[ "$got" = "A:float,B:float,G:float,R:float;-" ] || fail "--pixel-type float over the scene: $got"

# Bad values: usage error for the option, invalid scene naming the key; no output written.
expect_exit 2 "pixel-type" -- render "$work/bright.json" -o "$work/bad.exr" --pixel-type double
expect_exit 3 "/film/pixel_type" -- render "$work/bright.json" -o "$work/bad.exr" \
  --set /film/pixel_type=16
[ -e "$work/bad.exr" ] && fail "a rejected render wrote an EXR"

finish "half cli"
