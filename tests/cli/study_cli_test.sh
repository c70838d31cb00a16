#!/usr/bin/env bash
# End-to-end checks of `kasumi study`: a 2x2 study at a tiny resolution writes study.csv (one
# row per combination, the Pareto front marked), study.md and study.svg; bad arguments are usage
# errors (exit 2) and bad values input errors naming the file and JSON pointer (exit 3), with no
# output written. Also the plan's render.quality line and the per-stage render statistics.
# usage: study_cli_test.sh KASUMI_BINARY SOURCE_DIR
set -u
kasumi="$1"
src="$2"
source "$(dirname "$0")/cli_lib.sh"

cat >"$work/fog.json" <<JSON
{
  "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
  "film": {"width": 320, "height": 200, "spp": 64},
  "lights": [{"type": "point", "position": [0.5, 1, 0], "intensity_cd": 100}],
  "media": [{"type": "homogeneous", "bounds": [[-3, -3, -3], [3, 3, 3]],
             "sigma_a": 0.05, "sigma_s": 0.3, "phase": {"model": "hg", "g": 0.5}}],
  "render": {"seed": 2}
}
JSON

expect_exit 0 "wrote" -- study "$work/fog.json" --vary /render/volume/step_m=0.5,0.1 \
  --vary spp=1,8 --res 12x8 --repeats 2 --reference-spp 128 --threads 1 -o "$work/s1"
for f in study.csv study.md study.svg; do
  [ -s "$work/s1/$f" ] || fail "study wrote no $f"
done
ls -a "$work/s1" | grep -q tmp && fail "study left a temporary file"
if [ -s "$work/s1/study.csv" ]; then
  python3 - "$work/s1/study.csv" <<'PY' || fail "study.csv content"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 4, rows
assert [r["/render/volume/step_m"] for r in rows] == ["0.5", "0.5", "0.1", "0.1"], rows
assert [r["spp"] for r in rows] == ["1", "8", "1", "8"], rows
assert all(r["repeats"] == "2" for r in rows), rows
assert any(r["pareto"] == "1" for r in rows), rows
# More samples at the same step cut the error (variance ~ 1/spp; 8x fewer samples leave
# several times the relative MSE).
for step in ("0.5", "0.1"):
    e = {r["spp"]: float(r["rel_mse"]) for r in rows if r["/render/volume/step_m"] == step}
    assert e["1"] > 2 * e["8"], e
PY
fi
grep -q "Reference: 128 spp" "$work/s1/study.md" || fail "study.md does not describe the reference"
grep -q "<svg" "$work/s1/study.svg" || fail "study.svg is not an SVG"

# A reference file of the wrong size is an input error.
expect_exit 0 "" -- render "$work/fog.json" --res 6x4 --spp 4 -o "$work/small.exr" --no-preview -q
expect_exit 3 "reference is 6x4" -- study "$work/fog.json" --vary spp=1,2 --res 12x8 \
  --reference "$work/small.exr" -o "$work/s2"
[ -e "$work/s2" ] && fail "a failed study created its output directory"

expect_exit 2 "KEY=V1" -- study "$work/fog.json" --vary spp -o "$work/s3"
expect_exit 2 "JSON pointer" -- study "$work/fog.json" --vary step_m=1,2 -o "$work/s3"
expect_exit 2 "given twice" -- study "$work/fog.json" --vary spp=1,2 --vary /film/spp=3 -o "$work/s3"
expect_exit 2 "" -- study "$work/fog.json" --vary spp=1,2
expect_exit 3 "fog.json: /render/volume/step_m" -- study "$work/fog.json" \
  --vary /render/volume/step_m=0.1,-1 --res 4x4 -o "$work/s3"
[ -e "$work/s3" ] && fail "a failed study created its output directory"

# '*' in a pointer, object values merged into each light, and --time build+render: one row per
# value; a '*' that meets no array is an input error naming the file and pointer.
expect_exit 0 "wrote" -- study "$work/fog.json" --res 6x4 --repeats 1 --reference-spp 4 \
  --time build+render --vary '/lights/*={"intensity_cd":50},{"intensity_cd":100}' -o "$work/s4"
grep -q "intensity_cd=50" "$work/s4/study.md" 2>/dev/null || fail "study.md lacks the merged value"
grep -q "each building the scene's runtime" "$work/s4/study.md" 2>/dev/null ||
  fail "study.md does not say the build is timed"
expect_exit 3 "fog.json: /shapes/\*/x" -- study "$work/fog.json" --vary '/shapes/*/x=1,2' \
  --res 4x4 -o "$work/s5"
expect_exit 2 "" -- study "$work/fog.json" --vary spp=1,2 --time all -o "$work/s5"
[ -e "$work/s5" ] && fail "a failed study created its output directory"

# A probe study: transmittance against the exact Beer-Lambert value, one CSV row per estimator.
expect_exit 0 "wrote" -- study "$work/fog.json" --probe transmittance --from 0,0,-5 --to 0,0,5 \
  --exact beer-lambert --vary /render/volume/estimator=march,ratio --spp 1000 --repeats 1 \
  -o "$work/p1"
grep -q "exact Beer-Lambert" "$work/p1/study.md" 2>/dev/null || fail "probe study.md lacks the exact reference"
expect_exit 2 "need --probe" -- study "$work/fog.json" --exact 1,1,1 --vary spp=1,2 -o "$work/p2"
expect_exit 2 "needs exactly --origin and --direction" -- study "$work/fog.json" \
  --probe radiance --from 0,0,0 --to 0,0,1 --vary spp=1,2 -o "$work/p2"
expect_exit 2 "is for --probe transmittance" -- study "$work/fog.json" --probe radiance \
  --origin 0,0,5 --direction 0,0,-1 --exact beer-lambert --vary spp=1,2 -o "$work/p2"
expect_exit 2 "--exact expects X,Y,Z" -- study "$work/fog.json" --probe transmittance \
  --from 0,0,-5 --to 0,0,5 --exact 1,2 --vary spp=1,2 -o "$work/p2"
[ -e "$work/p2" ] && fail "a failed probe study created its output directory"

# render.quality: the plan prints the level's choice; an unknown level is a located input error.
expect_exit 0 "" -- plan "$work/fog.json" --set /render/quality=draft
grep -q "run   quality: draft: set /render/volume/step_m = 1.6;" "$work/stdout" || fail "plan lacks the quality line"
grep -q "single scattering chosen by draft" "$work/stdout" || fail "plan lacks the integrator choice"
expect_exit 3 "fog.json: /render/quality" -- plan "$work/fog.json" --set /render/quality=ultra

# Render statistics per stage: -v prints each stage's time and the skipped stages; the EXR
# carries the times and the plan (string attributes, readable in the file's header).
expect_exit 0 "time render" -- render "$work/fog.json" --res 6x4 --spp 1 -o "$work/v.exr" \
  --no-preview -v
for key in "time load" "time build" "time write" "skipped stages"; do
  grep -q "$key" "$work/stderr" || fail "render -v lacks \"$key\""
done
for key in kasumi/time/load_s kasumi/time/build_s kasumi/time/render_s kasumi/plan/skipped; do
  grep -aq "$key" "$work/v.exr" || fail "EXR metadata lacks $key"
done
# The build stage's parts: the fog has media but no shapes, so media are timed and no BVH.
grep -aq "kasumi/time/build/media_s" "$work/v.exr" || fail "EXR metadata lacks time/build/media_s"
grep -aq "time/build/bvh" "$work/v.exr" && fail "a scene without shapes reports a BVH build"
grep -q "time build/media" "$work/stderr" || fail "render -v lacks \"time build/media\""
# The EXR writer adds the "kasumi/" prefix once; callers must not add it again.
grep -aq "kasumi/kasumi/" "$work/v.exr" && fail "EXR metadata keys carry the prefix twice"

finish "study cli"
