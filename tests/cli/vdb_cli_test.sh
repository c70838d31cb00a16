#!/usr/bin/env bash
# End-to-end checks of the VDB side of the CLI: make-cloud writes a grid that scenes load,
# probe transmittance prints the contract's JSON with exact answers where they are known, and
# grid errors are input errors naming file and JSON path.
# usage: vdb_cli_test.sh KASUMI_BINARY SOURCE_DIR
set -u
kasumi="$1"
src="$2"
source "$(dirname "$0")/cli_lib.sh"

# json_field FILE EXPR: evaluates a Python expression over the parsed JSON as `j`.
json_field() { python3 -c "import json,sys; j=json.load(open('$1')); print($2)"; }

expect_exit 0 "wrote" -- make-cloud --res 16 --seed 3 -o "$work/clouds/c16.vdb"
[ -s "$work/clouds/c16.vdb" ] || fail "make-cloud wrote no file"
ls "$work/clouds" | grep -q tmp && fail "make-cloud left a temporary file"

cat >"$work/cloud.json" <<JSON
{
  "camera": {"position": [0, 500, 3000], "look_at": [0, 500, 0]},
  "film": {"width": 16, "height": 12, "spp": 2},
  "lights": [{"type": "directional", "direction": [0, -1, 0], "illuminance_lux": 1000}],
  "media": [{"type": "vdb", "file": "clouds/c16.vdb", "density_scale": 0.02, "albedo": 0.9},
            {"type": "homogeneous", "bounds": [[-10, -10, -10], [10, 10, 10]], "sigma_a": 0.05, "sigma_s": 0}],
  "render": {"volume": {}}
}
JSON
expect_exit 0 "" -- check "$work/cloud.json"
expect_exit 0 "" -- plan "$work/cloud.json"
grep -q "VDB grid" "$work/stdout" || fail "plan does not mention the grid: $(cat "$work/stdout")"
grep -q "residual-ratio" "$work/stdout" || fail "plan does not state the default estimator"

# Homogeneous box of sigma_t 0.05 crossed over 20 m: T = exp(-1) for every estimator.
for e in march delta ratio residual-ratio unbiased-march; do
  expect_exit 0 "" -- probe transmittance "$work/cloud.json" --from -15,0,0 --to 15,0,0 --estimator $e --samples 4000
  ok=$(json_field "$work/stdout" "abs(j['transmittance'][0] - 0.36787944) <= 4 * j['stderr'][0] + 1e-5 and j['estimator'] == '$e' and j['samples'] == 4000 and len(j['stderr']) == 3")
  [ "$ok" = "True" ] || fail "probe transmittance --estimator $e: $(cat "$work/stdout")"
done
# Through the cloud: finite, in [0, 1], and estimators agree within their errors.
expect_exit 0 "" -- probe transmittance "$work/cloud.json" --from -600,420,0 --to 600,420,0 --estimator residual-ratio --samples 2000
cp "$work/stdout" "$work/rr.json"
expect_exit 0 "" -- probe transmittance "$work/cloud.json" --from -600,420,0 --to 600,420,0 --estimator march --samples 200
ok=$(python3 -c "
import json; a=json.load(open('$work/rr.json')); b=json.load(open('$work/stdout'))
t=a['transmittance'][0]; print(0.0 < t < 1.0 and abs(t - b['transmittance'][0]) < 5 * a['stderr'][0] + 0.02)")
[ "$ok" = "True" ] || fail "cloud transmittance: residual-ratio $(cat "$work/rr.json") vs march $(cat "$work/stdout")"

# Radiance works with every integrator and estimator.
for i in single multiple; do
  for e in march delta ratio residual-ratio; do
    expect_exit 0 "" -- probe radiance "$work/cloud.json" --origin 0,420,2000 --direction 0,0,-1 --spp 16 \
      --set /render/volume='{"integrator": "'$i'", "estimator": "'$e'"}'
    ok=$(json_field "$work/stdout" "all(v == v and v >= 0 for v in j['radiance'])")
    [ "$ok" = "True" ] || fail "probe radiance $i $e: $(cat "$work/stdout")"
  done
done

# Errors: input errors name file and JSON path (exit 3); usage errors exit 2.
expect_exit 3 "cloud.json: /media/0/file.*no such file" -- check "$work/cloud.json" --set /media/0/file=nothing.vdb
expect_exit 3 "cloud.json: /media/0/file.*no grid \"smoke\"" -- check "$work/cloud.json" --set /media/0/grid=smoke
expect_exit 3 "/render/volume/estimator" -- check "$work/cloud.json" --set /render/volume='{"estimator": "guess"}'
expect_exit 3 "/media/0/albedo" -- check "$work/cloud.json" --set /media/0/albedo=1.5
expect_exit 2 "--estimator" -- probe transmittance "$work/cloud.json" --from 0,0,0 --to 1,0,0 --estimator guess
expect_exit 2 "--to" -- probe transmittance "$work/cloud.json" --from 0,0,0 --to 1,0

# The committed scene checks on a fresh clone.
expect_exit 0 "" -- check "$src/data/scenes/cloud.json"

finish "vdb cli"
