#!/usr/bin/env bash
# --set means the same on every scene-reading command (docs/scene-format.md, "--set"): a missing
# parent object is created like `mkdir -p` and the value reaches the scene, "-" appends to an
# array, a pointer that cannot be followed exits 3 naming it, a malformed one exits 2.
# usage: set_cli_test.sh KASUMI_BINARY SOURCE_DIR
set -u
kasumi="$1"
src="$2"
source "$(dirname "$0")/cli_lib.sh"

# Radiosity on, render.radiosity absent: --set /render/radiosity/patch_size_m must create it.
scene="$work/scene.json"
cat >"$scene" <<'JSON'
{
  "camera": {"position": [0, 1, 2], "look_at": [0, 0, 0]},
  "film": {"width": 4, "height": 3, "spp": 1},
  "materials": {"white": {"type": "phong", "kd": 0.7}},
  "shapes": [{"type": "quad", "material": "white",
              "vertices": [[-1, 0, 1], [1, 0, 1], [1, 0, -1], [-1, 0, -1]]}],
  "lights": [{"type": "point", "position": [0, 2, 0], "intensity_cd": 10}],
  "render": {"gi": "radiosity"}
}
JSON

declare -A args=(
  [render]="render $scene -o $work/out/r.exr --no-preview -q"
  [plan]="plan $scene"
  [check]="check $scene -q"
  [radiance]="probe radiance $scene --origin 0,1,2 --direction 0,-0.5,-1 --spp 1"
  [transmittance]="probe transmittance $scene --from 0,1,0 --to 0,1,-1 --samples 1"
  [illuminance]="probe illuminance $scene --at 0,0,0 --normal 0,1,0 --samples 1"
  [study]="study $scene --vary spp=1,2 --repeats 1 --reference-spp 2 -o $work/out/study -q"
  [sequence]="sequence $scene --frames 0-0 -o $work/out/f.####.exr --no-contact-sheet --no-skip-existing -q"
)
lamp='{"type": "point", "position": [0, 2, 0], "intensity_cd": -5}'
for name in render plan check radiance transmittance illuminance study sequence; do
  read -r -a cmd <<<"${args[$name]}"
  # A missing parent is created and the value used: a valid one is accepted, an invalid one is
  # refused at its pointer by the loader.
  expect_exit 0 "" -- "${cmd[@]}" --set /render/radiosity/patch_size_m=0.5
  expect_exit 3 "scene.json: /render/radiosity/patch_size_m = -1: must be > 0" -- \
    "${cmd[@]}" --set /render/radiosity/patch_size_m=-1
  # "-" appends: the new light is /lights/1.
  expect_exit 3 "scene.json: /lights/1/intensity_cd = -5: " -- "${cmd[@]}" --set "/lights/-=$lamp"
  # Pointers that cannot be followed name themselves.
  expect_exit 3 "scene.json: --set /shapes/5/x: index 5 is past the end of /shapes \(1 elements; - appends\)" -- \
    "${cmd[@]}" --set /shapes/5/x=1
  expect_exit 3 "scene.json: --set /film/width/w: /film/width is not an object or array" -- \
    "${cmd[@]}" --set /film/width/w=1
  expect_exit 2 "--set /film/~2: invalid JSON pointer" -- "${cmd[@]}" --set /film/~2=1
done

# The values are used.
expect_exit 0 "" -- plan "$scene" --json --set /render/radiosity/patch_size_m=0.5
grep -q "patches <= 0.5 m" "$work/stdout" || fail "plan --json does not show the patch size set: $(grep radiosity "$work/stdout")"
expect_exit 0 "" -- render "$scene" -o "$work/out/v.exr" --no-preview -v --set /render/radiosity/patch_size_m=0.5
grep -q "patches <= 0.5 m" "$work/stderr" || fail "render -v does not show the patch size set"
expect_exit 0 "" -- check "$scene" --set '/lights/-={"type": "point", "position": [1, 2, 0], "intensity_cd": 10}'
grep -q "2 lights" "$work/stdout" || fail "check: the appended light is not counted: $(cat "$work/stdout")"
expect_exit 0 "" -- probe illuminance "$scene" --at 0,0,0 --normal 0,1,0 --samples 1 \
  --set '/lights/-={"type": "point", "position": [0, 2, 0], "intensity_cd": 30}'
python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); l=[x["lux"] for x in d["per_light"]]; sys.exit(not (len(l) == 2 and abs(l[1] - 3 * l[0]) < 1e-6 * l[1]))' \
  "$work/stdout" || fail "probe illuminance: the appended light: $(tr -d ' \n' <"$work/stdout")"
fog='{"type": "homogeneous", "sigma_a": 0.5, "sigma_s": 0}'
expect_exit 0 "" -- probe transmittance "$scene" --from 0,1,0 --to 0,1,-2 --samples 1 --set "/media/-=$fog"
python3 -c 'import json,math,sys; t=json.load(open(sys.argv[1]))["transmittance"]; sys.exit(not all(abs(x - math.exp(-1)) < 1e-5 for x in t))' \
  "$work/stdout" || fail "probe transmittance: the medium created by --set /media/-: $(tr -d ' \n' <"$work/stdout")"
expect_exit 0 "" -- study "$scene" --vary spp=1,2 --repeats 1 --probe transmittance --from 0,1,0 --to 0,1,-2 \
  --exact beer-lambert -o "$work/out/bl" -q --set "/media/-=$fog"
grep -q "0.367879" "$work/out/bl/study.md" || fail "study: the medium created by --set is not in the reference: $(grep -i exact "$work/out/bl/study.md")"
expect_exit 0 "" -- sequence "$scene" --frames 0-0 -o "$work/out/lit.####.exr" --no-contact-sheet -q
expect_exit 0 "" -- sequence "$scene" --frames 0-0 -o "$work/out/dark.####.exr" --no-contact-sheet -q \
  --set /lights/0/intensity_cd=0
cmp -s "$work/out/lit.0000.exr" "$work/out/dark.0000.exr" && fail "sequence: --set /lights/0/intensity_cd=0 changed nothing"

finish "set_cli"
