#!/usr/bin/env bash
# End-to-end checks of `kasumi sequence` and the Slurm scripts: usage and input errors, a
# 24-frame run (frames, one log line each, summary, contact sheet), skip-existing leaving files
# untouched, a failed write (exit 4, later frames not written), --aovs/--compression,
# SIGINT/SIGTERM exit codes with no partial or temporary files, a run killed with
# SIGKILL resumed by a rerun, `render --frame`, and the sbatch scripts run by hand.
# usage: sequence_cli_test.sh KASUMI_BINARY SOURCE_DIR
set -u
kasumi="$1"
src="$2"
source "$(dirname "$0")/cli_lib.sh"
scene="$src/data/scenes/fog_sequence.json"
tiny=(--res 32x18 --spp 1)

count_files() { find "$1" -maxdepth 1 -name "$2" 2>/dev/null | wc -l; }
# Temporaries of core/atomic_file: .<name>.<pid>.<n>.tmp
count_temps() { find "$1" -maxdepth 1 -name '.*.tmp' 2>/dev/null | wc -l; }
mtimes() { stat -c '%n %y' "$1"/*.exr 2>/dev/null; }

# Usage errors: exit 2, nothing written.
expect_exit 2 "'#'" -- sequence "$scene" --frames 0-3 -o "$work/u/frame.exr" "${tiny[@]}"
expect_exit 2 "--frames" -- sequence "$scene" --frames 5-3 -o "$work/u/f.####.exr"
expect_exit 2 "--frames" -- sequence "$scene" --frames 0-3:0 -o "$work/u/f.####.exr"
expect_exit 2 "--frames A-B" -- sequence "$scene" -o "$work/u/f.####.exr"
expect_exit 2 "not a frame of" -- sequence "$scene" --frames 0-10:2 --frame 3 -o "$work/u/f.####.exr"
[ -e "$work/u" ] && fail "a usage error wrote output"

# Animation errors: exit 3, one line naming the file and the JSON pointer.
cat >"$work/bad.json" <<'JSON'
{"lights": [{"type": "point", "position": [0, 1, 0], "intensity_cd": 10}],
 "animate": {"/lights/0/intensity_cd": [[0, 1], [9, 5], [9, 6]]}}
JSON
expect_exit 3 "bad.json: /animate/~1lights~10~1intensity_cd/2/0 = 9: duplicate key frame" -- \
  sequence "$work/bad.json" --frames 0-3 -o "$work/b/f.####.exr"
expect_exit 3 "bad.json: /animate/~1lights~10~1intensity_cd/2/0" -- render "$work/bad.json" -o "$work/b.exr" -q
expect_exit 3 "bad.json: /animate" -- check "$work/bad.json"
[ "$(wc -l <"$work/stderr")" -eq 1 ] || fail "error message is not one line: $(cat "$work/stderr")"
[ -e "$work/b" ] || [ -e "$work/b.exr" ] && fail "an input error wrote output"

# An animated scene checks, and renders one frame with `render --frame`.
expect_exit 0 "" -- check "$scene"
expect_exit 0 "" -- render "$scene" --frame 30 "${tiny[@]}" -o "$work/r/f30.exr" -q
[ -s "$work/r/f30.exr" ] || fail "render --frame wrote no EXR"

# An error in a key-framed value at `render --frame N` names the key frames around N, as
# `sequence` and `check` do: spp keyed 1 at frame 0 and 3 at frame 4 is 1.5 at frame 1 (not an
# integer); key frame 4 is valid; an error in a value not animated gets only the frame.
cat >"$work/spp.json" <<'JSON'
{"camera": {"position": [0, 1, 5], "look_at": [0, 1, 0]},
 "film": {"width": 4, "height": 3, "spp": 1},
 "lights": [{"type": "directional", "direction": [0, -1, 0], "illuminance_lux": 1000}],
 "animate": {"/film/spp": [[0, 1], [4, 3]]}}
JSON
expect_exit 3 "spp.json: /film/spp = 1.5: expected an integer \(at frame 1 of /animate; /film/spp between key frames 0 and 4\)$" \
  -- render "$work/spp.json" --frame 1 -o "$work/spp/f1.exr" -q
expect_exit 3 "/film/spp = 2.5: .*\(at frame 3 of /animate; /film/spp between key frames 0 and 4\)$" \
  -- render "$work/spp.json" --frame 3 -o "$work/spp/f3.exr" -q
expect_exit 3 "spp.json: /film/width = 0: .*\(at frame 2 of /animate\)$" \
  -- render "$work/spp.json" --frame 2 --set /film/width=0 -o "$work/spp/f2.exr" -q
expect_exit 0 "" -- render "$work/spp.json" --frame 4 -o "$work/spp/f4.exr" -q
[ -e "$work/spp/f1.exr" ] || [ -e "$work/spp/f3.exr" ] || [ -e "$work/spp/f2.exr" ] &&
  fail "a rejected frame wrote output"
# Frame 0 too, where `check` and `render` (default --frame 0) read the scene: key frame 0.
expect_exit 3 "spp.json: /film/spp = 0.5: expected an integer \(at key frame 0 of /animate\)$" \
  -- check "$work/spp.json" --set '/animate/~1film~1spp/0/1=0.5'
expect_exit 3 "spp.json: /film/spp = 0.5: expected an integer \(at key frame 0 of /animate\)$" \
  -- render "$work/spp.json" --set '/animate/~1film~1spp/0/1=0.5' -o "$work/spp/f0.exr" -q
[ -e "$work/spp/f0.exr" ] && fail "a rejected frame 0 wrote output"

# 24 frames: every file, one log line per frame with its time, a summary, the contact sheet.
expect_exit 0 "" -- sequence "$scene" --frames 0-23 -o "$work/seq/fog.####.exr" "${tiny[@]}" \
  --preview-dir "$work/prev"
[ "$(count_files "$work/seq" 'fog.00[0-2][0-9].exr')" -eq 24 ] || fail "not 24 frames: $(ls "$work/seq")"
[ "$(count_files "$work/prev" 'fog.00[0-2][0-9].png')" -eq 24 ] || fail "not 24 previews"
[ "$(grep -cE '^frame 0000[0-9][0-9]  [0-9.]+ s \(scene' "$work/stderr")" -eq 24 ] ||
  fail "not one log line per frame: $(head -c 600 "$work/stderr")"
grep -q "reused bvh, 3 meshes" "$work/stderr" || fail "the log does not say what was reused"
grep -qE '^sequence: 24 frames: 24 rendered, 0 skipped' "$work/stderr" || fail "no summary"
[ -s "$work/prev/fog.contact_sheet.png" ] || fail "no contact sheet in the preview dir"
grep -q "contact sheet: $work/prev/fog.contact_sheet.png (24 frames, 0 missing)" "$work/stderr" ||
  fail "the contact sheet is not reported"
[ "$(count_temps "$work/seq")" -eq 0 ] || fail "temporary files left behind"

# Skip-existing (the default): nothing rendered, files untouched.
before="$(mtimes "$work/seq")"
expect_exit 0 "24 skipped" -- sequence "$scene" --frames 0-23 -o "$work/seq/fog.####.exr" "${tiny[@]}"
[ "$before" = "$(mtimes "$work/seq")" ] || fail "skip-existing touched existing frames"
expect_exit 0 "1 rendered, 0 skipped" -- sequence "$scene" --frame 4 --no-skip-existing \
  -o "$work/seq/fog.####.exr" "${tiny[@]}"
[ "$before" = "$(mtimes "$work/seq")" ] && fail "--no-skip-existing did not rewrite frame 4"

# A failed write (frame 3's name taken by a directory) while later frames render in the
# background: exit 4 naming the file, frames 0-2 kept, nothing after frame 3, no temporaries.
mkdir -p "$work/werr/fog.0003.exr/inside"
expect_exit 4 "$work/werr/fog.0003.exr" -- sequence "$scene" --frames 0-7 --no-skip-existing \
  -o "$work/werr/fog.####.exr" "${tiny[@]}"
[ "$(count_files "$work/werr" 'fog.000[0-2].exr')" -eq 3 ] || fail "write error: frames 0-2 missing"
[ "$(count_files "$work/werr" 'fog.000[4-7].exr')" -eq 0 ] || fail "write error: later frames written"
[ "$(count_temps "$work/werr")" -eq 0 ] || fail "write error: temporary files left"
[ -e "$work/werr/fog.contact_sheet.png" ] && fail "write error: a contact sheet was written"

# AOV and compression choices: bad values are usage errors; good ones write every frame.
expect_exit 2 "--aovs" -- sequence "$scene" --frames 0-1 -o "$work/u/f.####.exr" --aovs normals
expect_exit 2 "--compression" -- sequence "$scene" --frames 0-1 -o "$work/u/f.####.exr" \
  --compression dwaa
expect_exit 0 "3 rendered" -- sequence "$scene" --frames 0-2 -o "$work/aov/fog.####.exr" \
  "${tiny[@]}" --aovs depth,albedo --compression rle
[ "$(count_files "$work/aov" 'fog.000[0-2].exr')" -eq 3 ] || fail "--aovs/--compression: frames missing"

# SIGINT and SIGTERM: exit 130 / 143, finished frames kept, no partial file, no temporaries.
for sig in INT TERM; do
  dir="$work/sig$sig"
  "$kasumi" sequence "$scene" --frames 0-239 -o "$dir/fog.####.exr" --res 64x36 --spp 2 \
    --no-contact-sheet 2>"$work/sig.log" &
  pid=$!
  for _ in $(seq 1 300); do
    [ "$(count_files "$dir" '*.exr')" -ge 2 ] && break
    sleep 0.05
  done
  kill -s "$sig" "$pid"
  wait "$pid"
  got=$?
  want=130
  [ "$sig" = TERM ] && want=143
  [ "$got" -eq "$want" ] || fail "SIG$sig: exit $got, expected $want"
  grep -q "interrupted" "$work/sig.log" || fail "SIG$sig: no interrupted message"
  [ "$(count_temps "$dir")" -eq 0 ] || fail "SIG$sig: temporary files left"
  n="$(count_files "$dir" '*.exr')"
  [ "$n" -ge 2 ] && [ "$n" -lt 240 ] || fail "SIG$sig: $n frames written"
done

# SIGKILL mid-sequence: no partial file under a final name; a rerun completes the rest and
# leaves the finished frames untouched; reading every frame back (the contact sheet) succeeds.
dir="$work/killed"
"$kasumi" sequence "$scene" --frames 0-23 -o "$dir/fog.####.exr" --res 64x36 --spp 1 -q &
pid=$!
for _ in $(seq 1 400); do
  [ "$(count_files "$dir" '*.exr')" -ge 3 ] && break
  sleep 0.02
done
kill -9 "$pid"
wait "$pid" 2>/dev/null
done_before="$(count_files "$dir" '*.exr')"
[ "$done_before" -lt 24 ] || fail "SIGKILL came too late to test resuming ($done_before frames)"
kept="$(mtimes "$dir")"
expect_exit 0 "$done_before skipped" -- sequence "$scene" --frames 0-23 -o "$dir/fog.####.exr" \
  --res 64x36 --spp 1
[ "$(count_files "$dir" 'fog.00[0-2][0-9].exr')" -eq 24 ] || fail "the rerun did not complete"
[ "$kept" = "$(mtimes "$dir" | head -n "$done_before")" ] || fail "the rerun rewrote finished frames"
expect_exit 0 "24 frames, 0 missing" -- sequence "$scene" --frames 0-23 -o "$dir/fog.####.exr" \
  --contact-sheet-only --contact-sheet "$work/killed_sheet.png"
[ -s "$work/killed_sheet.png" ] || fail "no contact sheet from the resumed frames"

# Slurm scripts, run by hand: an array task per frame and per chunk, idempotent reruns, the
# contact sheet job, and the submitter's dependency wiring (sbatch replaced by a stub).
slurm="$src/scripts/slurm"
export KASUMI="$kasumi" SCENE="$scene" FRAMES=0-23 OUTPUT="$work/farm/fog.####.exr"
export KASUMI_ARGS="--res 32x18 --spp 1 -q"
SLURM_ARRAY_TASK_ID=3 bash "$slurm/sequence.sbatch" || fail "array task 3 failed"
[ -s "$work/farm/fog.0003.exr" ] || fail "array task 3 wrote no frame 3"
[ "$(count_files "$work/farm" '*.exr')" -eq 1 ] || fail "array task 3 wrote other frames"
before="$(mtimes "$work/farm")"
SLURM_ARRAY_TASK_ID=3 bash "$slurm/sequence.sbatch" || fail "rerun of task 3 failed"
[ "$before" = "$(mtimes "$work/farm")" ] || fail "rerun of task 3 was not idempotent"
SLURM_ARRAY_TASK_ID=30 bash "$slurm/sequence.sbatch" 2>/dev/null && fail "task 30 of 0-23 succeeded"
FRAMES_PER_TASK=5 SLURM_ARRAY_TASK_ID=4 bash "$slurm/sequence.sbatch" || fail "chunk 4 failed"
[ "$(count_files "$work/farm" 'fog.002[0-3].exr')" -eq 4 ] || fail "chunk 4 is not frames 20-23"
bash "$slurm/contact_sheet.sbatch" 2>/dev/null || fail "contact sheet job failed"
[ -s "$work/farm/fog.contact_sheet.png" ] || fail "contact sheet job wrote no sheet"
# The movie job: frames 1-2 missing fail it (exit 3) with no movie; frames 20-23 make one.
MOVIE="$work/farm/fog.mp4" bash "$slurm/movie.sbatch" 2>/dev/null
[ $? -eq 3 ] || fail "movie job with missing frames did not exit 3"
[ -e "$work/farm/fog.mp4" ] && fail "movie job with missing frames wrote a movie"
FRAMES=20-23 MOVIE="$work/farm/fog.mp4" bash "$slurm/movie.sbatch" 2>/dev/null ||
  fail "movie job of frames 20-23 failed"
[ -s "$work/farm/fog.mp4" ] || fail "movie job wrote no movie"
cat >"$work/sbatch" <<'STUB'
#!/usr/bin/env bash
echo "$*" >>"$SBATCH_LOG"
echo "$((1000 + $(wc -l <"$SBATCH_LOG")))"
STUB
chmod +x "$work/sbatch"
SBATCH="$work/sbatch" SBATCH_LOG="$work/sbatch.log" MAX_PARALLEL=8 \
  bash "$slurm/submit_sequence.sh" "$scene" 0-239 "$work/farm/fog.####.exr" -- --spp 4 \
  >"$work/submit.out" || fail "submit_sequence.sh failed"
grep -q -- "--array=0-239:1%8 .*sequence.sbatch" "$work/sbatch.log" || fail "array job: $(cat "$work/sbatch.log")"
grep -q -- "--dependency=afterok:1001 .*contact_sheet.sbatch" "$work/sbatch.log" ||
  fail "contact sheet job does not depend on the array: $(cat "$work/sbatch.log")"
grep -q -- "--dependency=afterok:1002 .*movie.sbatch" "$work/sbatch.log" ||
  fail "movie job does not depend on the contact sheet: $(cat "$work/sbatch.log")"
grep -q "job 1001.*job 1002.*movie: job 1003" "$work/submit.out" ||
  fail "submitter output: $(cat "$work/submit.out")"
: >"$work/sbatch.log"
FRAMES_PER_TASK=10 SBATCH="$work/sbatch" SBATCH_LOG="$work/sbatch.log" \
  bash "$slurm/submit_sequence.sh" "$scene" 0-239 "$work/farm/fog.####.exr" >/dev/null
grep -q -- "--array=0-23 " "$work/sbatch.log" || fail "chunked array: $(cat "$work/sbatch.log")"

finish "sequence cli"
