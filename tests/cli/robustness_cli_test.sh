#!/usr/bin/env bash
# Bad input through every command: missing, unreadable, truncated and binary files, JSON syntax
# errors, wrong types and out-of-range values at every numeric leaf of a scene holding every
# element type, degenerate geometry, bad --set and animate pointers, bad VDB/CSV/IES/OBJ files and
# unwritable outputs. Each must exit with the documented code (README "Errors and exit codes":
# 2 usage, 3 invalid input, 4 cannot write), say where (file, JSON pointer) and what was expected
# in one line, and leave no output file. Then scale invariance: the same scene at 1e-6 x and
# 1e7 x its size (lengths times s, coefficients over s, intensities times s^2) gives the same
# radiance, and extreme but valid values render without non-finite samples.
# usage: robustness_cli_test.sh KASUMI_BINARY SOURCE_DIR
set -u
kasumi="$1"
src="$2"
source "$(dirname "$0")/cli_lib.sh"
# An AddressSanitizer build reserves terabytes of shadow memory, so it cannot run under an
# address-space limit (`limited` then runs unlimited and the out-of-memory case is skipped).
# LeakSanitizer checks every run (its exit-time tracer crash on some renders was GCC 12's
# __tls_get_addr interceptor; the sanitized build turns it off, see core/sanitizer_defaults.cpp).
sanitized=0
if ldd "$kasumi" 2>/dev/null | grep -q libasan; then
  sanitized=1
fi

out="$work/out"  # every failing command points its outputs here; it must stay empty
mkdir -p "$out" "$work/s"
no_output() {
  if [ -n "$(ls -A "$out")" ]; then
    fail "output left after a failure ($*): $(ls -A "$out")"
    rm -rf "${out:?}"/* "$out"/.[!.]* 2>/dev/null
  fi
}
# bad CODE PATTERN ARGS...: expect_exit plus a one-line message and no output.
bad() {
  local code="$1" pattern="$2"
  shift 2
  expect_exit "$code" "$pattern" -- "$@"
  # One line; CLI11's usage errors add "Run with --help for more information."
  [ "$(grep -cv "^Run with --help" "$work/stderr")" -le 1 ] ||
    fail "kasumi $* printed more than one line: $(cat "$work/stderr")"
  grep -q "internal error\|Assertion\|runtime error:\|AddressSanitizer" "$work/stderr" &&
    fail "kasumi $* crashed or hit an internal error: $(head -c 400 "$work/stderr")"
  no_output "$*"
}

# A scene with every element type, small enough to render in a blink.
s="$work/s"
cp "$src/data/ies/isotropic_1000lm.ies" "$s/lamp.ies"
cp "$src/data/clouds/cumulus_64.vdb" "$s/cloud.vdb"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\n' >"$s/tri.obj"  # 2nd: zero area
cat >"$s/all.json" <<'JSON'
{
  "camera": {"position": [0, 1.5, 6], "look_at": [0, 1, 0], "up": [0, 1, 0], "fov_deg": 50},
  "film": {"width": 8, "height": 6, "spp": 1},
  "ambient": 0.1, "background": [0.2, 0.3, 0.4],
  "materials": {"white": {"type": "phong", "ka": 0.1, "kd": 0.7, "ks": 0.2, "n": 10},
                "mirror": {"type": "mirror", "kr": 0.9},
                "glass": {"type": "dielectric", "ior": 1.5, "tint": 0.95}},
  "shapes": [
    {"type": "quad", "material": "white", "vertices": [[-5, 0, 5], [5, 0, 5], [5, 0, -5], [-5, 0, -5]]},
    {"type": "sphere", "material": "glass", "center": [-1, 1, 0], "radius": 0.5},
    {"type": "box", "material": "mirror", "min": [1, 0, -1], "max": [2, 1, 0]},
    {"type": "mesh", "material": "white", "file": "tri.obj", "translate": [0, 0, -2], "scale": 0.5}
  ],
  "lights": [
    {"type": "directional", "direction": [0.2, -1, 0.1], "illuminance_lux": 100},
    {"type": "point", "position": [0, 3, 1], "intensity_cd": 50},
    {"type": "spot", "position": [2, 3, 1], "direction": [0, -1, 0], "cone_deg": 30, "falloff_deg": 20, "flux_lm": 300},
    {"type": "goniometric", "position": [-2, 3, 0], "ies": "lamp.ies", "rotation_deg": 10},
    {"type": "line", "from": [-1, 2.5, 1], "to": [1, 2.5, 1], "intensity_cd_per_m": 20, "samples": 2},
    {"type": "polygon", "vertices": [[0, 2.9, 0], [0.5, 2.9, 0], [0.5, 2.9, 0.5]], "luminance_cd_m2": 100, "samples": 2},
    {"type": "sphere", "center": [1, 2, 2], "radius": 0.1, "luminance_cd_m2": 500, "samples": 2}
  ],
  "media": [
    {"type": "homogeneous", "bounds": [[-5, 0, -5], [5, 3, 5]], "sigma_a": 0.01, "sigma_s": [0.05, 0.06, 0.07],
     "phase": {"model": "hg", "g": 0.5}},
    {"type": "vdb", "file": "cloud.vdb", "density_scale": 0.002, "albedo": 0.9,
     "transform": {"translate": [0, 1, -3], "scale": 0.002}}
  ],
  "render": {"seed": 3, "volume": {"step_m": 0.5}, "whitted": {"max_depth": 2}}
}
JSON
expect_exit 0 "" -- check "$s/all.json"
expect_exit 0 "" -- render "$s/all.json" -o "$work/ok/all.exr" --no-preview -v
grep -q "non-finite samples  0$" "$work/stderr" ||
  fail "the all-elements scene (zero-area mesh triangle included) dropped non-finite samples: $(grep non-finite "$work/stderr")"

# Files: missing, a directory, empty, truncated, binary, a syntax error, not an object.
: >"$s/empty.json"
head -c 700 "$s/all.json" >"$s/truncated.json"
head -c 4096 "$kasumi" >"$s/binary.json"
echo '{"film": {"width": 8,}}' >"$s/syntax.json"
echo '[1, 2]' >"$s/array.json"
bad 3 "nothing.json: cannot open file" check "$s/nothing.json"
bad 3 "s: is a directory" check "$s"
bad 3 "empty.json: invalid JSON: parse error at line 1, column 1" check "$s/empty.json"
bad 3 "truncated.json: invalid JSON: parse error at line" plan "$s/truncated.json"
bad 3 "binary.json: invalid JSON" render "$s/binary.json" -o "$out/a.exr" -q
bad 3 "syntax.json: invalid JSON: parse error at line 1, column 22" check "$s/syntax.json"
bad 3 "array.json: / = \[1,2\]: expected an object" check "$s/array.json"
# Numbers beyond double range, keys given twice: the file, line and column, not an internal error.
printf '{"film": {"width": 8,\n  "spp": 1e999}}\n' >"$s/overflow.json"
printf '{"film": {"spp": -1e999}}\n' >"$s/negoverflow.json"
printf '{"film": {"spp": 1},\n "camera": {},\n "film": {"spp": 2}}\n' >"$s/duplicate.json"
bad 3 "overflow.json: invalid JSON: line 2, column 10: number 1e999 is out of range at /film/spp" check "$s/overflow.json"
bad 3 "negoverflow.json: invalid JSON: line 1, column 18: number -1e999 is out of range at /film/spp" plan "$s/negoverflow.json"
bad 3 "duplicate.json: invalid JSON: line 3, column 2: duplicate key \"film\" in /" check "$s/duplicate.json"
for cmd in "render -o $out/a.exr -q" "probe radiance --origin 0,1,5 --direction 0,0,-1" "sequence --frames 0-1 -o $out/f.####.exr -q" \
  "study --vary spp=1,2 -o $out/study"; do
  set -- $cmd
  sub="$1"
  shift
  [ "$sub" = probe ] && { sub="probe $1"; shift; }
  # shellcheck disable=SC2086  # $sub is "probe radiance"
  bad 3 "overflow.json: invalid JSON: line 2, column 10" $sub "$s/overflow.json" "$@"
done
if [ "$(id -u)" -ne 0 ]; then  # root reads anything
  cp "$s/all.json" "$s/unreadable.json" && chmod 000 "$s/unreadable.json"
  bad 3 "unreadable.json: cannot open file: Permission denied" check "$s/unreadable.json"
fi
# Every scene-reading command, on a broken scene: 3 and no output.
bad 3 "truncated.json" probe radiance "$s/truncated.json" --origin 0,1,5 --direction 0,0,-1
bad 3 "truncated.json" probe illuminance "$s/truncated.json" --at 0,0,0 --normal 0,1,0
bad 3 "truncated.json" probe transmittance "$s/truncated.json" --from 0,1,5 --to 0,1,-5
bad 3 "truncated.json" study "$s/truncated.json" --vary spp=1,2 -o "$out/study"
bad 3 "truncated.json" sequence "$s/truncated.json" --frames 0-1 -o "$out/f.####.exr" -q

# Every numeric leaf of the scene, one at a time: a string "nan" must name exactly that leaf and
# ask for a number; 1e39 (beyond single precision) must be refused with the leaf or its parent.
python3 - "$s/all.json" >"$work/leaves" <<'PY'
import json, sys
def walk(v, p):
    if isinstance(v, dict):
        for k, x in v.items():
            yield from walk(x, p + "/" + k.replace("~", "~0").replace("/", "~1"))
    elif isinstance(v, list):
        for i, x in enumerate(v):
            yield from walk(x, p + "/" + str(i))
    elif isinstance(v, (int, float)) and not isinstance(v, bool):
        yield p
for p in walk(json.load(open(sys.argv[1])), ""):
    print(p)
PY
[ "$(wc -l <"$work/leaves")" -gt 100 ] || fail "too few numeric leaves: $(wc -l <"$work/leaves")"
n=0
while read -r leaf; do
  bad 3 "all.json: $leaf = \"nan\": expected an? (number|integer)" check "$s/all.json" --set "$leaf=\"nan\""
  if [ $((n++ % 4)) -eq 0 ]; then  # every fourth leaf: a number beyond single precision
    bad 3 "all.json: ($leaf|${leaf%/*}) = " check "$s/all.json" --set "$leaf=1e39"
  fi
done <"$work/leaves"
# Every string leaf that names a choice: an unknown choice is refused at that leaf.
for leaf in /materials/white/type /shapes/0/type /lights/0/type /media/0/type /media/0/phase/model \
  /shapes/1/material; do
  bad 3 "all.json: $leaf = \"bogus\": unknown" check "$s/all.json" --set "$leaf=\"bogus\""
done

# Out-of-range values, each named with its pointer and the range expected.
chk() { bad 3 "$1" check "$s/all.json" "${@:2}"; }
chk "/media/0/sigma_a = -0.1: must be >= 0" --set /media/0/sigma_a=-0.1
chk "/media/0/sigma_s = \[0.05,-1,0.07\]: must be >= 0 in every channel" --set /media/0/sigma_s/1=-1
chk "/media/1/albedo = 1.5: must be in \[0, 1\]" --set /media/1/albedo=1.5
chk "/media/0/phase/g = 1: must be in \(-1, 1\)" --set /media/0/phase/g=1
chk "/media/0/phase/g = 0.99999999: must be in \(-1, 1\) \(it rounds to the bound" --set /media/0/phase/g=0.99999999
chk "/media/1/density_scale = -1: must be >= 0" --set /media/1/density_scale=-1
chk "/film/width = 100000: must be an integer in \[1, 16384\]" --set /film/width=100000
chk "/film/spp = 0: must be an integer in \[1, 1048576\]" --set /film/spp=0
chk "/film/spp = 1.5: expected an integer" --set /film/spp=1.5
chk "/shapes/1/radius = -0.5: must be > 0" --set /shapes/1/radius=-0.5
chk "/shapes/1/radius = 1e-50: must be > 0 \(it rounds to the bound" --set /shapes/1/radius=1e-50
chk "/shapes/1/radius = 1e\+20: must be <= 1e12 m" --set /shapes/1/radius=1e20
chk "/lights/6/radius = 0: must be > 0" --set /lights/6/radius=0
chk "/lights/1/position/0 = 1e\+30: coordinates must be within" --set /lights/1/position/0=1e30
chk "/camera/position/2 = 1e\+20: coordinates must be within" --set /camera/position/2=1e20
chk "/shapes/2/max = .*must exceed \"min\" on every axis" --set /shapes/2/max/1=0
chk "/shapes/0/vertices = .*quad is degenerate" --set '/shapes/0/vertices=[[0,0,0],[1,0,0],[2,0,0],[3,0,0]]'
chk "/lights/5/vertices = .*" --set '/lights/5/vertices=[[0,2.9,0],[0.5,2.9,0],[1,2.9,0]]'
chk "/lights/4 = .*a line light needs from != to" --set '/lights/4/to=[-1,2.5,1]'
chk "/camera = .*position and look_at must differ" --set '/camera/look_at=[0,1.5,6]'
chk "/camera = .*up must not be parallel to the view direction" --set '/camera/up=[0,-0.5,-6]'
chk "/camera/up = \[0,0,0\]: must be a non-zero vector" --set '/camera/up=[0,0,0]'
chk "/lights/0/direction = \[0,0,0\]: must be a non-zero vector" --set '/lights/0/direction=[0,0,0]'
chk "/lights/2/falloff_deg = 40: must be in \[0, cone_deg\]" --set /lights/2/falloff_deg=40
chk "/lights/1/shadows = \"soft\": unknown shadow mode" --set '/lights/1/shadows="soft"'
chk "/lights/4/shadows = \"scanline\": \"scanline\" shadows need a point, spot, goniometric or directional light" --set '/lights/4/shadows="scanline"'
chk "/materials/glass/ior = 0: must be > 0" --set /materials/glass/ior=0
chk "/render/volume/step_m = 0: must be > 0" --set /render/volume/step_m=0
chk "/render/threads = -1: must be an integer in \[0, 1024\]" --set /render/threads=-1
chk "/film/spq = 3: unknown key \"spq\" \(expected one of: " --set /film/spq=3
chk "/media/0/phase/gg = 0.5: unknown key" --set /media/0/phase/gg=0.5
chk "/lights/3/wattage = 60: unknown key" --set /lights/3/wattage=60
chk "/shapes/1/material = \"paper\": unknown material \(known materials: glass, mirror, white\)" --set '/shapes/1/material="paper"'

# Keys the all-elements scene does not hold, each with a wrong type and a value out of range: the
# sky settings (data/scenes/sky.json), a shadow map, photon mapping, a sun from date and place, and
# an animated value out of range at one key frame (data/scenes/fog_sequence.json).
sky="$src/data/scenes/sky.json"
bad 3 "sky.json: /render/sky/orders = 0: must be an integer in \[1, 64\]" check "$sky" --set /render/sky/orders=0
bad 3 "sky.json: /render/sky/view_steps = \"many\": expected an integer" check "$sky" --set '/render/sky/view_steps="many"'
chk "/lights/1/shadow_map/resolution = 8: must be an integer in \[16, 8192\]" --set '/lights/1/shadows="map"' --set '/lights/1/shadow_map={"resolution": 8}'
chk "/lights/1/shadow_map/pcf_radius = 1.5: expected an integer" --set '/lights/1/shadows="map"' --set '/lights/1/shadow_map={"pcf_radius": 1.5}'
chk "/render/photons/k = 0: must be an integer in \[1, 10000\]" --set '/render/gi="photons"' --set '/render/photons={"k": 0}'
chk "/render/photons/filter = 3: expected a string" --set '/render/gi="photons"' --set '/render/photons={"filter": 3}'
sun='/sun={"latitude_deg": 45, "longitude_deg": 7, "datetime": '
bad 3 "sky.json: /sun/datetime = \"2026-13-40T99:00\": expected ISO 8601 with a zone" check "$sky" --set "$sun\"2026-13-40T99:00\"}"
bad 3 "sky.json: /sun/datetime = 12: expected a string" check "$sky" --set "${sun}12}"
bad 3 "sky.json: /sun/latitude_deg = 95: must be in \[-90, 90\] degrees" check "$sky" --set '/sun={"latitude_deg": 95, "longitude_deg": 7, "datetime": "2026-06-21T12:00:00Z"}'
fogseq="$src/data/scenes/fog_sequence.json"
bad 3 "fog_sequence.json: /media/0/sigma_s = \[0.03,-1.0,0.033\]: must be >= 0 in every channel \(at key frame 239 of /animate\)" \
  check "$fogseq" --set '/animate={"/media/0/sigma_s": [[0, [0.07, 0.072, 0.076]], [239, [0.03, -1, 0.033]]]}'
bad 3 "fog_sequence.json: /animate/~1lights~10~1intensity_cd/1/1 = \"x\": type mismatch" \
  check "$fogseq" --set '/animate={"/lights/0/intensity_cd": [[0, 0], [40, "x"]]}'

# --set and animate pointers.
bad 2 "--set expects /json/pointer=VALUE" check "$s/all.json" --set film/width=3
bad 2 "--set /film/~x: invalid JSON pointer" check "$s/all.json" --set '/film/~x=3'
# A missing parent is created (like mkdir -p); the loader then names what it does not know.
bad 3 "all.json: /nope = \\{\"x\":3\\}: unknown key \"nope\"" check "$s/all.json" --set /nope/x=3
bad 3 "all.json: --set /shapes/9/radius: index 9 is past the end of /shapes \\(4 elements; - appends\\)" check "$s/all.json" --set /shapes/9/radius=3
bad 3 "all.json: --set /film/spp: invalid JSON: line 1, column 1: number 1e999 is out of range" check "$s/all.json" --set /film/spp=1e999
bad 3 "all.json: --set /film: invalid JSON: line 1, column 12: duplicate key \"spp\" in /" check "$s/all.json" --set '/film={"spp": 1, "spp": 2}'
bad 3 "all.json: --set /shapes/x: \"x\" is not an array index" check "$s/all.json" --set /shapes/x=3
bad 3 "all.json: --set /film/width/0: /film/width is not an object or array" check "$s/all.json" --set /film/width/0=3
for a in '{"/nope/x": [[0, 1], [10, 2]]}|/animate/~1nope~1x = .*does not exist in the scene' \
  '{"film/width": [[0, 8]]}|/animate/film~1width = .*must be a JSON pointer' \
  '{"/film/width": 8}|/animate/~1film~1width = 8: expected keyframes' \
  '{"/film/width": [[1, 8], [0, 9]]}|/animate/~1film~1width/1/0 = 0: .*strictly increasing' \
  '{"/film/~q": [[0, 1]]}|/animate/~1film~1~0q = .*not a valid JSON pointer' \
  '{"/camera/fov_deg": [[0, "wide"]]}|/animate/~1camera~1fov_deg/0/1 = "wide": type mismatch'; do
  python3 -c "import json,sys; d=json.load(open(sys.argv[1])); d['animate']=json.loads(sys.argv[2]); json.dump(d, open(sys.argv[3], 'w'))" \
    "$s/all.json" "${a%%|*}" "$s/anim.json"
  bad 3 "anim.json: ${a#*|}" sequence "$s/anim.json" --frames 0-2 -o "$out/f.####.exr" -q
done
# A key value valid at frame 0 but not at its own key frame: check says so.
python3 -c "import json,sys; d=json.load(open(sys.argv[1])); d['animate']={'/media/0/phase/g': [[0, 0.5], [10, 1.5]]}; json.dump(d, open(sys.argv[2], 'w'))" \
  "$s/all.json" "$s/anim.json"
bad 3 "anim.json: /media/0/phase/g = 1.5: must be in \(-1, 1\) \(at key frame 10 of /animate\)" check "$s/anim.json"

# Files a scene refers to: OBJ, IES, VDB, CSV.
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 5\n' >"$s/badindex.obj"
printf 'v 0 0 nan\n' >"$s/nan.obj"
bad 3 "all.json: /shapes/3/file = \"missing.obj\": .*missing.obj: cannot open file" check "$s/all.json" --set /shapes/3/file=missing.obj
bad 3 "all.json: /shapes/3/file = .*badindex.obj:4: vertex index 5 out of range" check "$s/all.json" --set /shapes/3/file=badindex.obj
bad 3 "all.json: /shapes/3/file = .*nan.obj:1: invalid number \"nan\"" check "$s/all.json" --set /shapes/3/file=nan.obj
bad 3 "all.json: /shapes/3/file = .*beyond \+-1e12 m" check "$s/all.json" --set /shapes/3/scale=1e30
# 1e5 x 1e5 candela values announced (40 GB of floats), a handful present.
awk 'BEGIN { print "IESNA:LM-63-2002"; print "TILT=NONE"; print "1 1000 1 100000 100000 1 2 0 0 0"
  print "1 1 100"; for (i = 0; i < 100000; ++i) printf "%.6f\n", i * 180 / 99999
  for (i = 0; i < 100000; ++i) printf "%.6f\n", i * 360 / 99999; print "1 2 3" }' >"$s/huge.ies"
printf 'IESNA:LM-63-2002\nTILT=NONE\n1 1000 1 2 1 1 2 0 0 0\n1 1 100\n0 180\n0\n1e300 5\n' >"$s/overflow.ies"
head -c 200 "$s/lamp.ies" >"$s/short.ies"
bad 3 "all.json: /lights/3/ies = .*missing.ies: cannot open" check "$s/all.json" --set /lights/3/ies=missing.ies
bad 3 "all.json: /lights/3/ies = .*huge.ies:.*file ends before candela values" check "$s/all.json" --set /lights/3/ies=huge.ies
bad 3 "all.json: /lights/3/ies = .*overflow.ies:.*overflows single precision" check "$s/all.json" --set /lights/3/ies=overflow.ies
bad 3 "all.json: /lights/3/ies = .*short.ies:.*file ends before" check "$s/all.json" --set /lights/3/ies=short.ies
bad 3 "all.json: /lights/3/ies = .*binary.json:[0-9]+: " check "$s/all.json" --set /lights/3/ies=binary.json
"$kasumi" make-cloud --res 8 -o "$s/c8.vdb" -q || fail "make-cloud --res 8 failed"
LC_ALL=C sed 's/Tree_float_5_4_3/Tree_int32_5_4_3/' "$s/c8.vdb" >"$s/int.vdb"  # same length
head -c 2000 "$s/c8.vdb" >"$s/truncated.vdb"
bad 3 "all.json: /media/1/file: no such file: .*missing.vdb" check "$s/all.json" --set /media/1/file=missing.vdb
bad 3 "all.json: /media/1/file: .*int.vdb: grid \"density\" is not a float grid" check "$s/all.json" --set /media/1/file=int.vdb
bad 3 "all.json: /media/1/file: .*truncated.vdb: " check "$s/all.json" --set /media/1/file=truncated.vdb
bad 3 "all.json: /media/1/file: .*binary.json: not a VDB file" check "$s/all.json" --set /media/1/file=binary.json
bad 3 "all.json: /media/1/file: .*c8.vdb has no grid \"smoke\"" check "$s/all.json" --set /media/1/file=c8.vdb --set /media/1/grid=smoke
printf '0,1\n180,1\n' >"$s/phase_ok.csv"
printf '0,1\n90,x\n180,1\n' >"$s/phase_bad.csv"
bad 3 "all.json: /media/0/phase/file = \"phase_bad.csv\": .*phase_bad.csv:2" check "$s/all.json" \
  --set '/media/0/phase={"model": "tabulated", "file": "phase_bad.csv"}'
printf 'wavelength_nm,value\n360,1e-5\n450,x\n830,1e-6\n' >"$s/ray_bad.csv"
printf '360,1e-5\n600,1e-5\n500,1e-6\n' >"$s/ray_order.csv"
printf '360,-1e-5\n830,1e-6\n' >"$s/ray_neg.csv"
cat >"$s/sky.json" <<'JSON'
{"film": {"width": 8, "height": 4, "spp": 1}, "atmosphere": {"rayleigh": {"scattering": "ray.csv"}},
 "sun": {"elevation_deg": 20}}
JSON
bad 3 "sky.json: /atmosphere/rayleigh/scattering = .*ray_bad.csv:3: expected two numbers" check "$s/sky.json" --set /atmosphere/rayleigh/scattering=ray_bad.csv
bad 3 "sky.json: /atmosphere/rayleigh/scattering = .*ray_order.csv:3: wavelengths must strictly increase" check "$s/sky.json" --set /atmosphere/rayleigh/scattering=ray_order.csv
bad 3 "sky.json: /atmosphere/rayleigh/scattering = .*ray_neg.csv:1: value must be >= 0" check "$s/sky.json" --set /atmosphere/rayleigh/scattering=ray_neg.csv
bad 3 "sky.json: /atmosphere/rayleigh/scattering = .*missing.csv: cannot open" check "$s/sky.json" --set /atmosphere/rayleigh/scattering=missing.csv
bad 3 "sky.json: /atmosphere/ground_radius_m = -1: must be > 0" check "$s/sky.json" --set /atmosphere/ground_radius_m=-1

# Command-line values: usage errors (2).
bad 2 "--res expects WxH" render "$s/all.json" --res 0x6 -o "$out/a.exr"
bad 2 "--spp" render "$s/all.json" --spp 0 -o "$out/a.exr"
bad 2 "--direction must be a non-zero vector" probe radiance "$s/all.json" --origin 0,1,5 --direction 0,0,0
bad 2 "--origin expects X,Y,Z" probe radiance "$s/all.json" --origin 0,nan,5 --direction 0,0,-1
bad 2 "--estimator" probe transmittance "$s/all.json" --from 0,1,5 --to 0,1,-5 --estimator fast
bad 2 "--size-m" make-cloud --res 8 --size-m nan -o "$out/c.vdb"
bad 2 "--size-m" make-cloud --res 8 --size-m 1e39 -o "$out/c.vdb"
bad 2 "--frames" sequence "$s/all.json" --frames 5-2 -o "$out/f.####.exr" -q
bad 2 "--theta-deg" phase eval --model hg --g 0.5 --theta-deg abc
bad 3 "/g = 1.0: must be in \(-1, 1\)" phase eval --model hg --g 1 --theta-deg 0,90
bad 2 "--res expects WxH, two whole numbers >= 1 \(e.g. 640x360\), got \"0x0\"" render "$s/all.json" --res 0x0 -o "$out/a.exr"
bad 2 "--res expects WxH, two whole numbers >= 1" sequence "$s/all.json" --frames 0-1 --res 8 -o "$out/f.####.exr"
bad 2 "--res expects WxH, two whole numbers >= 1" study "$s/all.json" --vary spp=1,2 --res -4x3 -o "$out/study"
bad 2 "--spp: Value -1 not in range 1 to" render "$s/all.json" --spp -1 -o "$out/a.exr"
bad 2 "--seed: Value -1 not in range 0 to 9223372036854775807$" render "$s/all.json" --seed -1 -o "$out/a.exr"
bad 2 "--seed: Value -1 not in range 0 to 9223372036854775807$" sequence "$s/all.json" --frames 0-1 --seed -1 -o "$out/f.####.exr"
bad 2 "-o \"$out/f.exr\": the output pattern needs a run of '#' for the frame number" \
  sequence "$s/all.json" --frames 0-1 -o "$out/f.exr" -q
# Two outputs with one name: the preview would replace the EXR (it did, silently).
bad 2 "-o .*a.png: its preview PNG beside it would have the same name" render "$s/all.json" -o "$out/a.png" -q
bad 2 "--preview .*is the EXR output \(-o\) too" render "$s/all.json" -o "$out/a.exr" --preview "$out/sub/../a.exr" -q
bad 2 "each frame's preview PNG would replace its EXR" sequence "$s/all.json" --frames 0-1 -o "$out/f.####.png" --preview-dir "$out" -q
# A wrong type deep in the scene: the pointer of the leaf, what it holds and what was expected.
bad 3 "all.json: /media/0/phase = \[\"hg\"\]: expected an object" render "$s/all.json" --set '/media/0/phase=["hg"]' -o "$out/a.exr" -q
bad 3 "all.json: /lights/0/color/1 = \"x\": expected a number" render "$s/all.json" --set '/lights/0/color=[1,"x",1]' -o "$out/a.exr" -q
bad 3 "all.json: /media/1/file: no such file: .*nowhere/missing.vdb" render "$s/all.json" --set /media/1/file=nowhere/missing.vdb -o "$out/a.exr" -q

# Outputs that cannot be written: 4, checked before rendering, and nothing else written.
bad 4 "/proc/kasumi/a.exr: " render "$s/all.json" -o /proc/kasumi/a.exr -q
bad 4 "/proc/kasumi/p.png: " render "$s/all.json" -o "$out/a.exr" --preview /proc/kasumi/p.png -q
mkdir -p "$work/dir.exr"
bad 4 "dir.exr: is a directory" render "$s/all.json" -o "$work/dir.exr" --no-preview -q
bad 4 "/proc/kasumi/c.vdb" make-cloud --res 8 -o /proc/kasumi/c.vdb
bad 4 "/proc/kasumi" sequence "$s/all.json" --frames 0-1 -o "/proc/kasumi/f.####.exr" -q
bad 4 "/proc/kasumi" study "$s/all.json" --vary spp=1,2 -o /proc/kasumi/study -q
bad 4 "/proc/kasumi" phase plot --model hg --g 0.5 -o /proc/kasumi/hg.svg
# An output directory that cannot be made (its parent is a file), and one that cannot be
# written to (root writes anywhere, so only when not root).
bad 4 "all.json/a.exr: cannot create directory .*all.json: Not a directory" render "$s/all.json" -o "$s/all.json/a.exr" -q
bad 4 "all.json/f.0000.exr: cannot create directory" sequence "$s/all.json" --frames 0-1 -o "$s/all.json/f.####.exr" -q
if [ "$(id -u)" -ne 0 ]; then
  mkdir -p "$work/readonly" && chmod 555 "$work/readonly"
  bad 4 "readonly/a.exr: cannot create a temporary file beside it: Permission denied" \
    render "$s/all.json" -o "$work/readonly/a.exr" -q
  [ -z "$(ls -A "$work/readonly")" ] || fail "files left in a read-only directory"
fi
# A FIFO (or a device) as output: refused, not replaced by the rename (as root, -o /dev/null
# used to replace the device node with a regular file).
mkfifo "$work/fifo.exr"
bad 4 "fifo.exr: not a regular file \(a device, FIFO or socket\)" render "$s/all.json" -o "$work/fifo.exr" -q
bad 4 "fifo.exr: not a regular file" render "$s/all.json" -o "$out/a.exr" --preview "$work/fifo.exr" -q
[ -p "$work/fifo.exr" ] || fail "the FIFO output was replaced"
if mknod "$work/null.exr" c 1 3 2>/dev/null; then
  bad 4 "null.exr: not a regular file" render "$s/all.json" -o "$work/null.exr" -q
  [ -c "$work/null.exr" ] || fail "a device node output was replaced by a file"
fi

# Scale invariance: lengths x s, sigma / s, point intensity x s^2 leave every radiance unchanged
# (same random numbers, so only rounding differs). Absolute epsilons in ray offsets, marching or
# shadow tests would break it at 1e-6 or 1e7.
scaled() {
  python3 - "$1" >"$s/scaled_$1.json" <<'PY'
import json, sys
k = float(sys.argv[1])
P = lambda p: [k * x for x in p]
print(json.dumps({
  "camera": {"position": P([0, 1.5, 6]), "look_at": P([0, 1, 0]), "fov_deg": 40},
  "film": {"width": 4, "height": 4, "spp": 4},
  "materials": {"white": {"type": "phong", "kd": 0.7, "ks": 0.2, "n": 10}},
  "shapes": [{"type": "quad", "material": "white", "vertices": [P(v) for v in [[-5, 0, 5], [5, 0, 5], [5, 0, -5], [-5, 0, -5]]]},
             {"type": "sphere", "material": "white", "center": P([0.5, 0.5, 0]), "radius": 0.5 * k}],
  "lights": [{"type": "point", "position": P([-1, 3, 1]), "intensity_cd": 50 * k * k},
             {"type": "directional", "direction": [0.3, -1, -0.2], "illuminance_lux": 20}],
  "media": [{"type": "homogeneous", "bounds": [P([-5, 0, -5]), P([5, 3, 5])],
             "sigma_a": 0.02 / k, "sigma_s": 0.1 / k, "phase": {"model": "hg", "g": 0.4}}],
  "render": {"volume": {"step_m": 0.5 * k}}}))
PY
}
declare -A origin=([1]="0,1.5,6" [1e-6]="0,1.5e-6,6e-6" [1e7]="0,1.5e7,6e7")
probe_y() {  # luminance along a ray from the camera position, in units of the scene
  "$kasumi" probe radiance "$s/scaled_$1.json" --spp 16 --origin "${origin[$1]}" --direction "$2" \
    2>"$work/stderr" | sed -n 's/.*"luminance_cd_m2": *\([-0-9.eE+]*\).*/\1/p'
}
for k in 1 1e-6 1e7; do scaled "$k"; done
for dir in "0.1,-0.25,-1" "-0.15,-0.1,-1" "0,0.2,-1"; do  # floor, sphere, fog against the sky
  y1=$(probe_y 1 "$dir")
  for k in 1e-6 1e7; do
    yk=$(probe_y "$k" "$dir")
    awk -v a="$y1" -v b="$yk" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(b != "" && d <= 2e-3 * a + 1e-6) }' ||
      fail "radiance along $dir changes with scale $k: $y1 at 1 m, ${yk:-error $(cat "$work/stderr")} at $k"
  done
done

# Extreme but valid values and hard cases render with no non-finite samples and no crash: a
# camera grazing the floor, inside the sphere light, at the point light, in the polygon light's
# plane; denormal coefficients; a point light on the floor, a line light lying on it, a two-sided
# polygon light coplanar with it.
for sets in /media/0/sigma_s=1e30 /media/0/sigma_a=1e-30 /lights/1/intensity_cd=1e30 \
  /shapes/1/radius=1e-30 /camera/fov_deg=1e-3 /camera/fov_deg=179.9 /media/0/phase/g=0.99999 \
  /media/0/phase/g=-0.99999 '/lights/1/position=[0,1e-7,1]' '/camera/up=[1e-30,1,0]' \
  '/camera/position=[0,0,6]|/camera/look_at=[0,0,0]' '/camera/position=[1,2,2]|/camera/look_at=[0,1,0]' \
  '/camera/position=[0,3,1]|/camera/look_at=[0,0,0]' '/camera/position=[0,2.9,0.2]|/camera/look_at=[0,0,0]' \
  '/media/0/sigma_a=1e-40|/media/0/sigma_s=1e-40' '/lights/1/position=[0,0,0]|/camera/position=[0,1,3]' \
  '/lights/4/from=[-1,0,1]|/lights/4/to=[1,0,1]' \
  '/lights/5/vertices=[[0,0,0],[0.5,0,0],[0.5,0,0.5]]|/lights/5/two_sided=true'; do
  IFS='|' read -r -a set <<<"$sets"
  args=()
  for x in "${set[@]}"; do args+=(--set "$x"); done
  expect_exit 0 "" -- render "$s/all.json" "${args[@]}" --res 16x12 -o "$work/x/e.exr" --no-preview -v
  grep -q "non-finite samples  0$" "$work/stderr" ||
    fail "render $sets dropped non-finite samples: $(grep -i "non-finite\|error" "$work/stderr" | head -3)"
done

# Illuminance at points on the lights themselves: at the point light, on the sphere light, on
# the line light, in the polygon light's plane (grazing). JSON writes a NaN as null.
for at in "0,3,1 --normal 0,1,0" "1.1,2,2 --normal 1,0,0" "0,2.5,1 --normal 0,-1,0" \
  "0.25,2.9,0.1 --normal 1,0,0"; do
  # shellcheck disable=SC2086  # $at holds two options
  expect_exit 0 "" -- probe illuminance "$s/all.json" --at $at --samples 64
  grep -qiE "nan|inf|null" "$work/stdout" && fail "probe illuminance --at $at: $(tr -d ' \n' <"$work/stdout")"
done

# What a hostile user tries next. `bounded` runs kasumi under a hard kill (SIGTERM is taken as a
# cancellation request, so a plain timeout would not end a hung render) and fails on a hang.
bounded() {
  local limit="$1"
  shift
  timeout -s KILL "$limit" "$kasumi" "$@" >"$work/stdout" 2>"$work/stderr"
  local got=$?
  [ "$got" -ne 137 ] || fail "kasumi $* did not end within $limit s"
  return "$got"
}
# limited KB ARGS...: the next kasumi runs under an address-space limit of KB kilobytes (no
# subshell, so failures still count).
limited() {
  local kb="$1"
  shift
  if [ "$sanitized" -eq 1 ]; then
    "$@"
    return
  fi
  printf '#!/usr/bin/env bash\nulimit -v %s\nexec "%s" "$@"\n' "$kb" "$kasumi" >"$work/limited.sh"
  chmod +x "$work/limited.sh"
  local real="$kasumi"
  kasumi="$work/limited.sh"
  "$@"
  local got=$?
  kasumi="$real"
  return "$got"
}
# A march step of 1e-30 m: the step count overflowed int (no in-scattering at all) or, in grids,
# no node moved forward (the render never ended). Now at most 65536 nodes per ray, with a warning.
python3 -c "import json,sys; d=json.load(open(sys.argv[1])); d['media']=d['media'][:1]; json.dump(d, open(sys.argv[2], 'w'))" \
  "$s/all.json" "$s/fog_only.json"
bounded 120 render "$s/fog_only.json" --set /render/volume/step_m=1e-30 --res 2x2 -o "$work/x/step.exr" \
  --no-preview -v
grep -q "warning: the march step .* 1e-30 m needed more than 65536 nodes" "$work/stderr" ||
  fail "step_m 1e-30: no warning about the bounded march: $(tail -3 "$work/stderr")"
grep -q "non-finite samples  0$" "$work/stderr" || fail "step_m 1e-30: non-finite samples"
bounded 120 probe transmittance "$s/all.json" --set /render/volume/step_m=1e-30 --estimator march \
  --from 0,1,-1 --to 0,1,-5 --samples 4 ||
  fail "step_m 1e-30 through a grid: exit $?: $(head -c 300 "$work/stderr")"
grep -qiE "nan|inf|null" "$work/stdout" && fail "probe transmittance step_m 1e-30: $(cat "$work/stdout")"
# Density scales of 1e6 and 1e30 on the cloud, alone (one grid: the trackers walk dense bricks cell
# by cell) under every tracker and both integrators: finite, no non-finite sample.
python3 -c "import json,sys; d=json.load(open(sys.argv[1])); d['media']=d['media'][1:]; json.dump(d, open(sys.argv[2], 'w'))" \
  "$s/all.json" "$s/cloud_only.json"
for scale in 1e6 1e30; do
  for est in delta ratio residual-ratio unbiased-march; do
    for integ in single multiple; do
      bounded 120 render "$s/cloud_only.json" --set /media/0/density_scale=$scale --set "/render/volume/estimator=\"$est\"" \
        --set "/render/volume/integrator=\"$integ\"" --res 4x3 -o "$work/x/dense.exr" --no-preview -v
      grep -q "non-finite samples  0$" "$work/stderr" ||
        fail "density_scale $scale $est $integ: $(grep -i "non-finite\|error" "$work/stderr" | head -2)"
    done
  done
done
# A .vdb cut anywhere in its header or its first grid's metadata, or a PNG named .vdb: exit 3 naming
# the file and what was expected (the 300-byte cut made OpenVDB allocate until std::bad_alloc).
printf '\x89PNG\r\n\x1a\n\0\0\0\rIHDR' >"$s/image.vdb"
bad 3 "all.json: /media/1/file: .*image.vdb: not a VDB file" check "$s/all.json" --set /media/1/file=image.vdb
for cut in 7 40 61 100 124 200 300 1000; do
  head -c "$cut" "$s/c8.vdb" >"$s/cut.vdb"
  limited 4000000 bad 3 "all.json: /media/1/file: .*cut.vdb: (truncated|not a VDB file|.*bytes left in the file)" \
    check "$s/all.json" --set /media/1/file=cut.vdb
done
# Scene files: empty object (renders the defaults), nested 100000 deep (the error printer overflowed
# the stack), /dev/zero (was read until memory ran out), a unicode path.
echo '{}' >"$s/empty_object.json"
expect_exit 0 "" -- render "$s/empty_object.json" --res 4x3 -o "$work/x/empty.exr" --no-preview -q
python3 -c "print('{\"film\": ' + '[' * 100000 + ']' * 100000 + '}')" >"$s/deep.json"
bad 3 "deep.json: invalid JSON: line 1, column 265: nested deeper than 256 levels" check "$s/deep.json"
limited 4000000 bounded 60 check /dev/zero
[ "$?" -eq 3 ] && grep -q "/dev/zero: larger than 64 MiB" "$work/stderr" ||
  fail "check /dev/zero: $(head -c 300 "$work/stderr")"
mkdir -p "$work/façade 霞"
cp "$s/all.json" "$s/lamp.ies" "$s/cloud.vdb" "$s/tri.obj" "$work/façade 霞/"
mv "$work/façade 霞/all.json" "$work/façade 霞/scène 霞.json"
expect_exit 0 "" -- render "$work/façade 霞/scène 霞.json" --res 4x3 -o "$work/façade 霞/out é.exr" -q
[ -s "$work/façade 霞/out é.exr" ] && [ -s "$work/façade 霞/out é.png" ] ||
  fail "unicode paths: outputs missing: $(ls "$work/façade 霞")"
bad 3 "façade 霞/missing é.json: cannot open file" check "$work/façade 霞/missing é.json"
# Outputs: the root directory, a trailing slash, a directory as the preview.
bad 4 "/: is a directory" render "$s/all.json" -o / -q
bad 4 "out/: is a directory" render "$s/all.json" -o "$out/" -q
bad 4 "is a directory" render "$s/all.json" -o "$out/a.exr" --preview "$work" -q
# A film too large for memory (16384 x 16384 under a 2 GB address-space limit): exit 1 saying so.
if [ "$sanitized" -eq 0 ]; then
  limited 2000000 bad 1 "out of memory" render "$s/all.json" --res 16384x16384 -o "$out/a.exr" -q
fi
# SIGINT during a render of 2^20 samples per pixel: cancellation is polled per sample, so the
# render stops within a few seconds of the signal (not after a whole tile of such pixels), exits
# 130 and leaves only complete files (written atomically: no temporary left behind).
mkdir -p "$work/int"
"$kasumi" render "$s/all.json" --spp 1048576 --res 16x12 -o "$work/int/a.exr" -v 2>"$work/int.err" &
pid=$!
# A job started with & by a script ignores SIGINT until kasumi installs its handler, which it does
# right after printing the plan (-v): wait for the plan (up to 60 s: a sanitized build on a busy
# machine loads slowly) rather than a fixed time, then a little longer.
for _ in $(seq 600); do grep -q "^plan:" "$work/int.err" 2>/dev/null && break; sleep 0.1; done
sleep 0.5
kill -INT "$pid"
for _ in $(seq 100); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
if kill -0 "$pid" 2>/dev/null; then
  kill -KILL "$pid"
  fail "render --spp 1048576 still running 10 s after SIGINT"
fi
wait "$pid"
code=$?
[ "$code" -eq 130 ] && grep -q "interrupted" "$work/int.err" ||
  fail "render interrupted by SIGINT exited $code, expected 130 and a message: $(cat "$work/int.err")"
leftover=$(ls -A "$work/int" | grep -v '^a\.exr$\|^a\.png$')
[ -z "$leftover" ] || fail "interrupted render left temporary files: $leftover"

finish "robustness cli"
