#!/usr/bin/env bash
# End-to-end checks of `kasumi phase eval|mie|validate|plot`: outputs (CSV, JSON, table, SVG),
# model options in every spelling, and exit codes: 2 bad arguments, 3 invalid values, 4 cannot
# write (5, a failed validation, has no deterministic trigger: see validate below).
# usage: phase_cli_test.sh KASUMI_BINARY SOURCE_DIR
set -u
kasumi="$1"
src="$2"
source "$(dirname "$0")/cli_lib.sh"

# expect_stdout EXPECTED -- ARGS...: exit 0 and exactly EXPECTED on stdout.
expect_stdout() {
  local expected="$1"
  shift 2
  local got
  got="$("$kasumi" "$@" 2>"$work/stderr")" || fail "kasumi $* exited $?: $(head -c 600 "$work/stderr")"
  [ "$got" = "$expected" ] || fail "kasumi $* printed '$got', expected '$expected'"
}

# eval: CSV at the given angles; HG at g = -0.5 is 0.75/(4π 2.25^1.5) forward, 0.75/(4π 0.25^1.5)
# backward; lists as a,b,c or A:B:N; options as --g V, --g=V, -g V; negative values.
hg=$'theta_deg,value\n0,0.01768388257\n90,0.04270575261\n180,0.4774648293'
expect_stdout "$hg" -- phase eval --model hg --g -0.5 --theta-deg 0,90,180
expect_stdout "$hg" -- phase eval --theta-deg=0:180:3 --g=-0.5 --model=hg
expect_stdout "$hg" -- phase eval -g -0.5 --model hg --theta-deg 0:180:3
expect_stdout $'theta_deg,value\n0,0.07957747155' -- phase eval --model isotropic --theta-deg 0
expect_stdout $'theta_deg,value\n90,0.05968310366' -- phase eval --model rayleigh --theta-deg 90
# Half forward, half backward HG: the mean of the two values above at either end.
expect_stdout $'theta_deg,value\n0,0.2475743559\n180,0.2475743559' -- \
  phase eval --model double-hg --g1 0.5 --g2 -0.5 --w 0.5 --theta-deg 0,180
expect_exit 0 "" -- phase eval --model jendersie-deon --diameter-um 10 --theta-deg 0,1,2
expect_exit 0 "" -- phase eval --model mie --m 1.33,0 --radius-um 1 --wavelength-nm 500 --theta-deg 0
expect_exit 0 "" -- phase eval --model mie --m 1.33 --distribution lognormal \
  --median-radius-um 0.3 --sigma 0.3 --n-radii 8 --theta-deg 0
printf '0,1\n90,1\n180,1\n' >"$work/flat.csv"
expect_stdout $'theta_deg,value\n45,0.07957747155' -- \
  phase eval --model tabulated --file "$work/flat.csv" --theta-deg 45

expect_exit 2 "--theta-deg" -- phase eval --model hg --g 0.5
expect_exit 2 "--theta-deg expects a number, got 'abc'" -- phase eval --model hg --g 0.5 --theta-deg abc
expect_exit 2 "--theta-deg: N must be a positive integer" -- phase eval --model hg --g 0.5 --theta-deg 0:1:0
expect_exit 3 "--theta-deg values must be in \[0, 180\]" -- phase eval --model hg --g 0.5 --theta-deg 181
expect_exit 2 "--model NAME is required" -- phase eval --theta-deg 0
expect_exit 2 "--g given twice for one model" -- phase eval --model hg --g 0.5 --g 0.3 --theta-deg 0
expect_exit 2 "--model given twice" -- phase eval --model hg --model hg --g 0.5 --theta-deg 0
expect_exit 2 "not expected" -- phase eval --model hg --g 0.5 --gg 1 --theta-deg 0
expect_exit 2 "not expected" -- phase eval --model hg --g 0.5 --theta-deg 0 stray
expect_exit 2 "--m expects a number" -- phase eval --model mie --m 1.33,x --x 1 --theta-deg 0
expect_exit 3 "command line: /g = 1.0: must be in \(-1, 1\)" -- phase eval --model hg --g 1 --theta-deg 0
expect_exit 3 "unknown key \"w\" \(expected one of: g, model\)" -- phase eval --model hg --g 0.5 --w 1 --theta-deg 0
expect_exit 3 "unknown phase model" -- phase eval --model hgg --theta-deg 0

# mie: Bohren & Huffman's appendix sphere (x = 3.14 at 632.8 nm; the docs' figures).
"$kasumi" phase mie --radius-um 0.525 --wavelength-nm 632.8 --m 1.55,0 --theta-deg 0:180:3 \
  >"$work/mie.json" 2>"$work/stderr" || fail "phase mie exited $?: $(cat "$work/stderr")"
python3 - "$work/mie.json" <<'PY' || fail "phase mie JSON"
import json, sys
j = json.load(open(sys.argv[1]))
assert abs(j["qext"] - 3.105426) < 2e-6 and abs(j["qback"] - 2.925341) < 2e-6, j
assert abs(j["g"] - 0.633137) < 2e-6 and j["qabs"] == 0.0, j
assert j["theta_deg"] == [0, 90, 180] and len(j["s1"]) == 3 and len(j["s1"][0]) == 2, j
assert set(j) == {"x", "m", "qext", "qsca", "qabs", "qback", "g", "n_terms", "convention",
                  "theta_deg", "s1", "s2"}, sorted(j)
PY
expect_exit 0 "" -- phase mie -x 2 -m 1.5 --x 3
grep -q '"x": 3.0' "$work/stdout" || fail "phase mie: the last --x counts"
expect_exit 2 "mie needs --m RE,IM" -- phase mie --x 3
expect_exit 2 "give either --x or --radius-um" -- phase mie --x 3 --radius-um 1 --m 1.5
expect_exit 2 "mie needs --x X or --radius-um" -- phase mie --m 1.5
expect_exit 2 "--m expects RE,IM" -- phase mie --x 3 --m 1,0,1
expect_exit 2 "not expected" -- phase mie --x 3 --m 1.5 --model hg
expect_exit 3 "--m real part must be > 0" -- phase mie --x 3 --m -1
expect_exit 3 "--m imaginary part must be >= 0" -- phase mie --x 3 --m 1.5,-0.1
expect_exit 3 "--radius-um must be > 0" -- phase mie --radius-um 0 --m 1.5
expect_exit 3 "size parameter must be in \(0, 1e5\]" -- phase mie --x 1e6 --m 1.5

# validate: the decision rule, then a table of checks with p-values; exit 0 when all pass, 5 when
# one fails. No correct model fails deterministically at the default rate, so the failure is
# forced by a run rate of 0.1: seed 2's chi-square p-value, 0.0304, is then below alpha = 0.1.
expect_exit 0 "" -- phase validate --model hg --g 0.3 --samples 1000 --seed 3
head -1 "$work/stdout" | grep -qE "^decision rule: false-failure rate 0.0001 for the run, Sidak over 1 statistical check\(s\): a check fails when its p-value <= 0.0001; 1000 samples$" ||
  fail "phase validate: decision rule line"
sed -n 2p "$work/stdout" | grep -qE "^check +result +value +expected +tolerance +p_value +detail" ||
  fail "phase validate: header"
grep -qE "^chi_square +pass +[0-9.e-]+ +1 +0.0001 +[0-9.e-]+ " "$work/stdout" ||
  fail "phase validate: chi_square row with its p-value"
grep -qE "^normalisation +pass +.* - +" "$work/stdout" || fail "phase validate: no p-value for a deterministic check"
expect_exit 0 "" -- phase validate --model hg --g 0.3 --samples 100000 --seed 2 --n-tests 4
head -1 "$work/stdout" | grep -q "Sidak over 4 statistical check(s): a check fails when its p-value <= 2.5e-05" ||
  fail "phase validate: --n-tests splits the rate"
expect_exit 5 "phase validate: hg failed at least one check" -- phase validate --model hg --g 0.3 --samples 100000 --seed 2 --significance 0.1
grep -qE "^chi_square +FAIL +0.0304" "$work/stdout" || fail "phase validate: the failing row"
expect_exit 2 "--significance must be in \(0, 1\)" -- phase validate --model hg --g 0.3 --significance 1
expect_exit 2 "--n-tests must be an integer in \[1, 1e6\]" -- phase validate --model hg --g 0.3 --n-tests 0
expect_exit 2 "--samples must be an integer in \[1000, 1e9\]" -- phase validate --model hg --g 0.3 --samples 10
expect_exit 2 "--seed must be a non-negative integer" -- phase validate --model hg --g 0.3 --seed -1

# plot: a well-formed SVG with one line per model, its legend, both axes and their labels.
expect_exit 0 "" -- phase plot --model hg --g 0.8 --model jendersie-deon --diameter-um 10 \
  --model rayleigh -o "$work/p.svg"
python3 - "$work/p.svg" <<'PY' || fail "phase plot SVG"
import sys, xml.etree.ElementTree as ET
ns = "{http://www.w3.org/2000/svg}"
root = ET.parse(sys.argv[1]).getroot()  # raises on malformed XML
assert root.tag == ns + "svg", root.tag
texts = [t.text for t in root.iter(ns + "text")]
for label in ["hg g=0.8", "jendersie-deon diameter-um=10", "rayleigh",
              "scattering angle θ (degrees, 0 = forward)", "p(θ) [1/sr]"]:
    assert label in texts, (label, texts)
for tick in ["0", "30", "60", "90", "120", "150", "180", "1", "10"]:
    assert tick in texts, (tick, texts)
lines = [p for p in root.iter(ns + "polyline")]
assert len(lines) == 3, len(lines)
colours = set()
for line in lines:
    pts = [tuple(map(float, p.split(","))) for p in line.get("points").split()]
    assert len(pts) == 721, len(pts)
    xs = [x for x, _ in pts]
    assert xs == sorted(xs) and xs[0] < xs[-1], "x runs from 0 to 180 degrees"
    colours.add(line.get("stroke"))
assert len(colours) == 3, colours
# HG g = 0.8 falls from forward to backward: y grows downwards on the page.
hg = [tuple(map(float, p.split(","))) for p in lines[0].get("points").split()]
assert hg[0][1] < hg[-1][1], (hg[0], hg[-1])
# Rayleigh is symmetric about 90 degrees.
ray = [tuple(map(float, p.split(","))) for p in lines[2].get("points").split()]
assert abs(ray[0][1] - ray[-1][1]) < 0.05 and ray[360][1] > ray[0][1], (ray[0], ray[360])
PY
expect_exit 0 "" -- phase plot --model hg --g 0.5 --output "$work/q.svg"
[ -s "$work/q.svg" ] || fail "phase plot --output wrote nothing"
expect_exit 2 "--output is required" -- phase plot --model hg --g 0.5
expect_exit 2 "plot needs at least one --model" -- phase plot -o "$work/r.svg"
expect_exit 2 "model parameters must follow a --model" -- phase plot --g 0.5 --model hg -o "$work/r.svg"
expect_exit 2 "--g given twice for one model" -- phase plot --model hg --g 0.5 --g 0.1 -o "$work/r.svg"
expect_exit 3 "/g = 2.0: must be in" -- phase plot --model hg --g 0.5 --model hg --g 2 -o "$work/r.svg"
[ -e "$work/r.svg" ] && fail "phase plot wrote a file after an error"
expect_exit 4 "cannot write /proc/kasumi/p.svg" -- phase plot --model hg --g 0.5 -o /proc/kasumi/p.svg
expect_exit 2 "" -- phase
expect_exit 0 "" -- phase plot --help
grep -q -- "--diameter-um" "$work/stdout" || fail "phase plot --help lists the model parameters"

finish phase_cli
