#!/usr/bin/env bash
# End-to-end checks of the kasumi CLI contract: exit codes, located error messages, no output
# on failure, JSON on stdout, and a small render that writes both files atomically.
# usage: cli_test.sh KASUMI_BINARY SOURCE_DIR
set -u
kasumi="$1"
src="$2"
source "$(dirname "$0")/cli_lib.sh"

cat >"$work/ok.json" <<'JSON'
{
  "camera": {"position": [0, 3, 0.001], "look_at": [0, 0, 0]},
  "film": {"width": 24, "height": 16, "spp": 2},
  "materials": {"white": {"type": "phong", "kd": 1}},
  "shapes": [{"type": "quad", "material": "white", "vertices": [[-9, 0, 9], [9, 0, 9], [9, 0, -9], [-9, 0, -9]]}],
  "lights": [{"type": "directional", "direction": [0, -1, 0], "illuminance_lux": 1000}],
  "media": [{"type": "homogeneous", "bounds": [[-9, 0.5, -9], [9, 9, 9]], "sigma_a": 0, "sigma_s": 0.1,
             "phase": {"model": "hg", "g": 0.3}}]
}
JSON

# Bad input: exit 3, one line naming file and JSON path, no output file.
echo '{"film": {"width": 8,}' >"$work/badjson.json"
expect_exit 3 "badjson.json" -- render "$work/badjson.json" -o "$work/a.exr" -q
expect_exit 3 "missing.json" -- render "$work/missing.json" -o "$work/a.exr" -q
expect_exit 3 "ok.json: /media/0/phase/g = 1.*must be in \(-1, 1\)" -- render "$work/ok.json" --set /media/0/phase/g=1 -o "$work/a.exr" -q
expect_exit 3 "ok.json: /media/0/sigma_s = -0.5.*>= 0" -- check "$work/ok.json" --set /media/0/sigma_s=-0.5
expect_exit 3 "/film/spp.*unknown key|unknown key.*spq" -- check "$work/ok.json" --set /film/spq=3
expect_exit 3 "/lights/0/illuminance_lux" -- plan "$work/ok.json" --set /lights/0/illuminance_lux='"bright"'
[ -e "$work/a.exr" ] && fail "an output file was created for invalid input"
[ "$(wc -l <"$work/stderr")" -eq 1 ] || fail "error message is not one line: $(cat "$work/stderr")"

# IES files (LM-63): every revision loads, and a malformed one is an input error naming the IES
# file and line and the scene's JSON path. An LM-63-1986 file has free-form label lines and no
# format line; from LM-63-1995 on, a label line must be a [KEYWORD] line.
for f in revision_1986 revision_1991 revision_2019 tilt_file mirror_90_270; do
  cp "$src/tests/data/ies/$f.ies" "$work/$f.ies"
done
cp "$src/tests/data/ies/vertical_lamp.tlt" "$work/"
printf 'IESNA:LM-63-2002\n[TEST] 1\nfree text\nTILT=NONE\n1 1000 1 2 1 1 2 0 0 0\n1 1 10\n0 90\n0\n5 5\n' \
  >"$work/bad_label.ies"
printf 'Acme 1986 label\nTILT=INCLUDE\n1 2\n0 90\n1 0.5\n1 1000 1 2 2 1 2 0 0 0\n1 1 10\n0 90\n90 180\n5 5 5 5\n' \
  >"$work/bad_range.ies"
for f in revision_1986 revision_1991 revision_2019 tilt_file mirror_90_270; do
  expect_exit 0 "" -- check "$work/ok.json" --set /lights/0='{"type": "goniometric", "position": [0, 3, 0], "ies": "'$f'.ies"}'
done
expect_exit 3 "ok.json: /lights/0/ies.*bad_label.ies:3: expected a \[KEYWORD\] line" -- \
  render "$work/ok.json" --set /lights/0='{"type": "goniometric", "position": [0, 3, 0], "ies": "bad_label.ies"}' -o "$work/a.exr" -q
expect_exit 3 "ok.json: /lights/0/ies.*bad_range.ies:9: type C horizontal angles" -- \
  check "$work/ok.json" --set /lights/0='{"type": "goniometric", "position": [0, 3, 0], "ies": "bad_range.ies"}'
[ -e "$work/a.exr" ] && fail "an output file was created for a bad IES file"

# Usage errors: exit 2.
expect_exit 2 "" -- render
expect_exit 2 "" -- render "$work/ok.json" --no-such-flag
expect_exit 2 "--res" -- render "$work/ok.json" --res 12by4
expect_exit 2 "--set" -- check "$work/ok.json" --set film/width=3
expect_exit 2 "--origin" -- probe radiance "$work/ok.json" --origin 1,2 --direction 0,-1,0

# check and plan.
expect_exit 0 "" -- check "$work/ok.json"
grep -q "ok" "$work/stdout" || fail "check prints no ok"
# Fog by visibility (docs/volumes.md): the example scene checks; visibility with a sigma is an
# error at the visibility's JSON path.
fogvis="$src/data/scenes/fog_visibility.json"
expect_exit 0 "" -- check "$fogvis"
expect_exit 3 "fog_visibility.json: /media/0/visibility_m.*not both" -- check "$fogvis" --set /media/0/sigma_s=0.1
expect_exit 3 "/media/0/visibility_m = 0.*> 0" -- check "$fogvis" --set /media/0/visibility_m=0
expect_exit 0 "" -- plan "$work/ok.json" --json
grep -q '"volume-in-scattering"' "$work/stdout" || fail "plan --json lacks the in-scattering stage"
expect_exit 0 "" -- plan "$work/ok.json" --set /media/0/sigma_s=0
grep -q "skip  volume-in-scattering" "$work/stdout" || fail "plan does not skip in-scattering for sigma_s = 0"

# probe radiance: JSON with the contract's keys; without fog, E/pi = 318.3 cd/m2 exactly.
expect_exit 0 "" -- probe radiance "$work/ok.json" --origin 0,3,0 --direction 0,-1,0 --spp 4 --set /media/0/sigma_s=0
for key in radiance stderr luminance_cd_m2; do
  grep -q "\"$key\"" "$work/stdout" || fail "probe radiance lacks \"$key\""
done
grep -qE '"luminance_cd_m2": 318\.30' "$work/stdout" || fail "probe radiance is not E/pi: $(cat "$work/stdout")"

# A render writes the EXR and the preview, and leaves no temporary file behind.
expect_exit 0 "" -- render "$work/ok.json" -o "$work/out/r.exr" --preview "$work/out/r.png" -q
[ -s "$work/out/r.exr" ] || fail "no EXR written"
[ -s "$work/out/r.png" ] || fail "no PNG written"
[ "$(ls -A "$work/out" | wc -l)" -eq 2 ] || fail "stray files beside the outputs: $(ls -A "$work/out")"
head -c 4 "$work/out/r.exr" | od -An -tx1 | grep -q "76 2f 31 01" || fail "EXR magic number missing"

# --aovs picks the EXR's channels beside R, G, B, A (names in the header's channel list).
grep -qa "depth.Z" "$work/out/r.exr" || fail "default render lacks the depth.Z AOV"
expect_exit 0 "" -- render "$work/ok.json" -o "$work/aov/r.exr" --no-preview -q --aovs none --compression rle
grep -qa "depth.Z\|albedo.R" "$work/aov/r.exr" && fail "--aovs none still wrote AOV channels"
expect_exit 0 "" -- render "$work/ok.json" -o "$work/aov/d.exr" --no-preview -q --aovs depth
grep -qa "depth.Z" "$work/aov/d.exr" || fail "--aovs depth lacks depth.Z"
grep -qa "albedo.R" "$work/aov/d.exr" && fail "--aovs depth wrote albedo"
expect_exit 2 "--aovs expects" -- render "$work/ok.json" -o "$work/aov/x.exr" -q --aovs normals
expect_exit 2 "--compression expects" -- render "$work/ok.json" -o "$work/aov/x.exr" -q --compression lzma
[ -e "$work/aov/x.exr" ] && fail "a usage error left an output file"

# Unwritable output: exit 4.
expect_exit 4 "" -- render "$work/ok.json" -o /proc/kasumi/r.exr -q

# SIGINT during a render: exit 130, and the partial image is still written atomically.
"$kasumi" render "$work/ok.json" --res 1600x1000 --spp 512 -o "$work/int/r.exr" --no-preview -q \
  >/dev/null 2>"$work/stderr" &
pid=$!
sleep 1.5
kill -INT "$pid"
wait "$pid"
got=$?
[ "$got" -eq 130 ] || fail "interrupted render exited $got, expected 130: $(cat "$work/stderr")"
[ -s "$work/int/r.exr" ] || fail "interrupted render wrote no partial image"
[ "$(ls -A "$work/int" | wc -l)" -eq 1 ] || fail "stray files after interrupt: $(ls -A "$work/int")"

finish "cli contract"
