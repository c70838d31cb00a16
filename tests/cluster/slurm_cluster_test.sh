#!/usr/bin/env bash
# A real single-node Slurm cluster renders data/scenes/sunset_sequence.json through
# scripts/slurm/submit_sequence.sh (docs/cluster.md):
#   slurm_cluster_test.sh KASUMI_BINARY SOURCE_DIR
# - 48 frames as an array of one frame a task and of 6 frames a task: every frame bit-identical
#   to a local `kasumi sequence` run (pixel data; EXR headers carry the time), the contact
#   sheet job starts only after the array succeeded (afterok), and the movie job after it (48
#   frames at 24 fps, checked with ffprobe);
# - scancel of a running task, then a resubmit: no partial frame, finished frames untouched
#   (nothing rendered twice), the rest rendered;
# - a task whose frame cannot be written fails the array; neither contact sheet nor movie runs;
# - Slurm's --signal warning before the time limit stops the running frame cleanly (exit 143,
#   finished frames kept, no temporary) and the task is requeued until the chunk is done.
# Needs root (installs Debian's slurmctld slurmd slurm-client munge if missing); exits 77 (ctest
# SKIP) when they are missing and this is not root. Everything it writes is under one temporary
# directory, and the daemons it starts are stopped by pid on exit, whatever happens.
set -uo pipefail

kasumi="$(realpath "${1:?usage: slurm_cluster_test.sh KASUMI_BINARY SOURCE_DIR}")"
src="$(realpath "${2:?usage: slurm_cluster_test.sh KASUMI_BINARY SOURCE_DIR}")"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
started=$SECONDS
# shellcheck source=tests/cluster/slurm_lib.sh
source "$here/slurm_lib.sh"

if [ "$(id -u)" -ne 0 ]; then
  echo "SKIP: the cluster test needs root (it starts munged as user munge and slurmd as root)"
  exit 77
fi
cluster_install
rc=$?
[ "$rc" -ne 0 ] && exit "$rc"

work="$(mktemp -d /tmp/kasumi-cluster.XXXXXX)"
cleanup() {
  cluster_stop
  if [ "${KEEP_CLUSTER_DIR:-0}" = 1 ]; then
    echo "kept $work"
  else
    rm -rf "$work"
  fi
}
trap cleanup EXIT
trap 'exit 130' INT TERM
chmod 755 "$work"  # munged runs as user munge
touch "$work/marker"  # files written after this, outside $work, are a failure

failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
step() { echo "[$((SECONDS - started)) s] $*"; }

scene="$src/data/scenes/sunset_sequence.json"
slurm="$src/scripts/slurm"
# A fixed preview exposure: "auto" would add up to 24 meter renders to every task (docs/cluster.md).
flags=(--res 48x27 --spp 1 --compression none --set /render/preview/exposure_stops=-11)
mkdir -p "$work/jobs"
cluster_start "$work/cluster" || exit 1

# Jobs are small on this node: one CPU and little memory a task (the scripts ask for more);
# their logs go to $work/jobs.
export KASUMI="$kasumi"
base_sbatch="--chdir=$work/jobs --cpus-per-task=1 --mem=256M"

# submit NAME [ENV=VALUE...] -- SUBMIT_ARGS...: runs submit_sequence.sh; sets frames_job,
# sheet_job and movie_job from its output.
submit() {
  local name="$1" out
  shift
  local envs=()
  while [ "$1" != "--" ]; do envs+=("$1"); shift; done
  shift
  out="$(env SBATCH_ARGS="$base_sbatch ${EXTRA_SBATCH:-}" "${envs[@]}" \
    bash "$slurm/submit_sequence.sh" "$@" 2>&1)" || {
    fail "$name: submit_sequence.sh failed: $out"
    frames_job="" sheet_job="" movie_job=""
    return 1
  }
  frames_job="$(sed -n 's/^frames: job \([0-9]*\) .*/\1/p' <<<"$out")"
  sheet_job="$(sed -n 's/.*contact sheet: job \([0-9]*\).*/\1/p' <<<"$out")"
  movie_job="$(sed -n 's/.*movie: job \([0-9]*\).*/\1/p' <<<"$out")"
  step "$name: $out"
}

# extend_signal_job: once the warned task (the last check) has requeued itself, gives it a
# 10-minute limit, so one more run finishes the chunk (else every run is warned again 5-35 s in,
# and on a loaded machine that takes many runs).
signal_job="" signal_extended=0
extend_signal_job() {
  [ -n "$signal_job" ] && [ "$signal_extended" = 0 ] || return 0
  [ "$(field "$signal_job" Restarts)" -ge 1 ] 2>/dev/null || return 0
  scontrol update JobId="$signal_job" TimeLimit=10 && signal_extended=1
}

# wait_jobs SECONDS ID...: waits until no job (or array task) of the ids is pending or running.
wait_jobs() {
  local limit="$1" start=$SECONDS ids
  shift
  ids="$(IFS=,; echo "$*")"
  while [ -n "$(squeue -h -j "$ids" -o %i 2>/dev/null)" ]; do
    extend_signal_job
    if [ $((SECONDS - start)) -ge "$limit" ]; then
      fail "jobs $ids still queued after $limit s: $(squeue -j "$ids" 2>&1 | head -n 5)"
      return 1
    fi
    sleep 0.5
  done
}

# field ID NAME: NAME=value of every job or array task of ID (one line each, scontrol -o).
field() { scontrol -o show job "$1" 2>/dev/null | grep -o "\<$2=[^ ]*" | cut -d= -f2-; }

# all_states ID: the distinct states of a job or of all the tasks of an array.
all_states() { field "$1" JobState | sort -u | tr '\n' ' ' | sed 's/ $//'; }

# compare_frames LOCAL_DIR SLURM_DIR: every EXR of LOCAL_DIR has the same pixel bytes in SLURM_DIR.
compare_frames() { python3 "$here/exr_pixels.py" compare "$1" "$2"; }

# no_partial DIR: no hidden temporary of an atomic write is left in DIR.
no_partial() {
  local left
  left="$(find "$1" -name '.*.tmp' 2>/dev/null)"
  [ -z "$left" ] || fail "partial files left in $1: $left"
}

# Slurm's warning before the time limit stops the frame in flight cleanly; the task requeues
# itself and, skipping the finished frames, completes the chunk. slurmctld checks time limits
# every 30 s and warns up to 30 s early: --signal=B:USR1@25 of a 1-minute limit comes 5 to 35 s
# into the task, so the chunk must hold more: 50 s of frames (640x360, 16 spp) on one core, timed
# here on two local frames (so a fast or a loaded machine gets more or fewer frames). It runs on
# one CPU while the other checks use the other; its results are checked last.
dir="$work/signal"
sig_flags=(--res 640x360 --spp 16 --compression none
  --set /render/preview/exposure_stops=-11)
"$kasumi" sequence "$scene" --frames 0-1 -o "$work/signal_local/s.####.exr" "${sig_flags[@]}" \
  --threads 1 --no-contact-sheet 2>"$work/signal_local.log" || fail "signal: local run failed"
per_frame="$(sed -n 's/.*; \([0-9.]*\) s per rendered frame.*/\1/p' "$work/signal_local.log")"
sig_frames="$(awk -v t="${per_frame:-1}" \
  'BEGIN { n = int(50 / t) + 1; print (n < 12 ? 12 : n > 240 ? 240 : n) }')"
step "signal: $per_frame s a frame on one core: $sig_frames frames in the warned task"
EXTRA_SBATCH="--time=1 --signal=B:USR1@25" submit signal MOVIE=none \
  FRAMES_PER_TASK="$sig_frames" -- "$scene" "0-$((sig_frames - 1))" "$dir/s.####.exr" -- "${sig_flags[@]}"
signal_job="$frames_job" signal_sheet="$sheet_job"

step "local reference: kasumi sequence frames 0-47 ${flags[*]}"
"$kasumi" sequence "$scene" --frames 0-47 -o "$work/local/s.####.exr" "${flags[@]}" -q \
  --no-contact-sheet || fail "local sequence run failed"

# The comparison itself must see one flipped bit in the pixels and not the header's time.
mkdir -p "$work/flip"
cp "$work/local/s.0007.exr" "$work/flip/"
compare_frames "$work/flip" "$work/local" >/dev/null || fail "a frame differs from itself"
python3 "$here/exr_pixels.py" flip-bit "$work/flip/s.0007.exr"
compare_frames "$work/flip" "$work/local" >/dev/null && fail "one flipped pixel bit went unseen"

# An array of one frame a task and of 6 frames a task.
for per in 1 6; do
  dir="$work/per$per"
  submit "per$per" FRAMES_PER_TASK="$per" -- "$scene" 0-47 "$dir/s.####.exr" -- "${flags[@]}" -q
  [ -n "$frames_job" ] || continue
  wait_jobs 150 "$frames_job" "$sheet_job" "$movie_job"
  tasks="$(field "$frames_job" JobState | wc -l)"
  expected=$((per == 1 ? 48 : 8))
  [ "$tasks" -eq "$expected" ] || fail "per$per: $tasks array tasks, expected $expected"
  [ "$(all_states "$frames_job")" = COMPLETED ] ||
    fail "per$per: array states $(all_states "$frames_job")"
  [ "$(all_states "$sheet_job")" = COMPLETED ] ||
    fail "per$per: contact sheet job $(all_states "$sheet_job"):" \
      "$(cat "$work/jobs/kasumi-sheet-$sheet_job.log")"
  last_end="$(field "$frames_job" EndTime | sort | tail -n 1)"
  sheet_start="$(field "$sheet_job" StartTime)"
  [[ "$sheet_start" > "$last_end" || "$sheet_start" = "$last_end" ]] ||
    fail "per$per: contact sheet started $sheet_start before the last task ended ($last_end)"
  [ "$(field "$sheet_job" Dependency)" = "(null)" ] ||
    fail "per$per: sheet dependency left: $(field "$sheet_job" Dependency)"
  [ -s "$dir/s.contact_sheet.png" ] || fail "per$per: no contact sheet"
  compare_frames "$work/local" "$dir" || fail "per$per: frames differ from the local run"
  # The movie job, after the contact sheet: all 48 frames, at 24 fps.
  [ "$(all_states "$movie_job")" = COMPLETED ] ||
    fail "per$per: movie job $(all_states "$movie_job"):" \
      "$(cat "$work/jobs/kasumi-movie-$movie_job.log")"
  [[ "$(field "$movie_job" StartTime)" > "$(field "$sheet_job" EndTime)" ||
    "$(field "$movie_job" StartTime)" = "$(field "$sheet_job" EndTime)" ]] ||
    fail "per$per: the movie job started before the contact sheet ended"
  movie="$(ffprobe -v error -count_frames -select_streams v:0 \
    -show_entries stream=nb_read_frames,r_frame_rate -of csv=p=0 "$dir/s.mp4" 2>&1)"
  [ "$movie" = "24/1,48" ] || fail "per$per: movie $dir/s.mp4: ffprobe says '$movie'"
  no_partial "$dir"
done

# mtimes DIR: name, inode and modification time of every frame (an atomic rewrite changes all).
mtimes() { find "$1" -name 's.*.exr' -printf '%f %i %T@\n' | sort; }

# scancel of a running task (one task of all 48 frames, cancelled after a few), then a resubmit.
dir="$work/cancel"
submit cancel FRAMES_PER_TASK=48 -- "$scene" 0-47 "$dir/s.####.exr" -- "${flags[@]}"
if [ -n "$frames_job" ]; then
  start=$SECONDS
  until [ "$(find "$dir" -name 's.*.exr' 2>/dev/null | wc -l)" -ge 4 ] ||
    [ $((SECONDS - start)) -ge 60 ]; do sleep 0.05; done
  scancel "${frames_job}_0"
  wait_jobs 60 "$frames_job" "$sheet_job" "$movie_job"
  done_before="$(find "$dir" -name 's.*.exr' | wc -l)"
  state="$(all_states "$frames_job")"
  [ "$state" = CANCELLED ] || fail "cancel: task state $state (cancelled after $done_before frames)"
  [ "$done_before" -lt 48 ] || fail "cancel: scancel came after the last frame"
  [ "$(all_states "$sheet_job")" = CANCELLED ] ||
    fail "cancel: contact sheet job $(all_states "$sheet_job") after a cancelled array"
  [ -e "$dir/s.contact_sheet.png" ] && fail "cancel: a contact sheet of a cancelled array"
  [ "$(all_states "$movie_job")" = CANCELLED ] ||
    fail "cancel: movie job $(all_states "$movie_job") after a cancelled array"
  no_partial "$dir"
  kept="$(mtimes "$dir")"
  step "cancel: $done_before frames before scancel; resubmitting"
  submit resubmit FRAMES_PER_TASK=48 -- "$scene" 0-47 "$dir/s.####.exr" -- "${flags[@]}"
  wait_jobs 120 "$frames_job" "$sheet_job" "$movie_job"
  [ "$(all_states "$frames_job") $(all_states "$sheet_job")" = "COMPLETED COMPLETED" ] ||
    fail "resubmit: states $(all_states "$frames_job") / $(all_states "$sheet_job")"
  log="$work/jobs/kasumi-frames-${frames_job}_0.log"
  grep -q "48 frames: $((48 - done_before)) rendered, $done_before skipped" "$log" ||
    fail "resubmit: not $((48 - done_before)) rendered and $done_before skipped:" \
      "$(tail -n 3 "$log")"
  [ "$kept" = "$(mtimes "$dir" | head -n "$done_before")" ] ||
    fail "resubmit: frames finished before scancel were written again"
  compare_frames "$work/local" "$dir" || fail "resubmit: frames differ from the local run"
  no_partial "$dir"
fi

# A frame that cannot be written (its preview path is a directory: renaming the finished PNG
# into place fails) fails its task, the array is FAILED and the contact sheet never runs.
dir="$work/fail"
mkdir -p "$dir/previews/s.0003.png"
submit fail PREVIEW_DIR="$dir/previews" -- "$scene" 0-5 "$dir/out/s.####.exr" -- "${flags[@]}" -q
if [ -n "$frames_job" ]; then
  wait_jobs 60 "$frames_job" "$sheet_job" "$movie_job"
  state3="$(scontrol -o show job "${frames_job}_3" | grep -o 'JobState=[A-Z]* .*ExitCode=[0-9:]*' |
    sed 's/ .*ExitCode/ ExitCode/')"
  [ "$state3" = "JobState=FAILED ExitCode=4:0" ] || fail "fail: task 3 is '$state3'"
  [ "$(all_states "$frames_job")" = "COMPLETED FAILED" ] ||
    fail "fail: array states $(all_states "$frames_job")"
  sheet="$(scontrol -o show job "$sheet_job" | grep -o 'JobState=[A-Z]* Reason=[A-Za-z]*')"
  [ "$sheet" = "JobState=CANCELLED Reason=DependencyNeverSatisfied" ] ||
    fail "fail: contact sheet job is '$sheet'"
  # A job that ran has its log (slurmd opens --output at launch) and maybe a contact sheet. Not
  # RunTime: a pending job cancelled for its dependency may show a second of it (seen once in CI).
  [ -e "$work/jobs/kasumi-sheet-${sheet_job}.log" ] &&
    fail "fail: the contact sheet job ran (RunTime $(field "$sheet_job" RunTime))"
  [ -n "$(find "$dir" -name '*contact_sheet*')" ] && fail "fail: a contact sheet of a failed array"
  [ "$(all_states "$movie_job")" = CANCELLED ] || fail "fail: movie job $(all_states "$movie_job")"
  [ -e "$dir/out/s.mp4" ] && fail "fail: a movie of a failed array"
  [ -e "$dir/out/s.0003.exr" ] && fail "fail: frame 3 has an EXR"
  [ "$(find "$dir/out" -name 's.*.exr' | wc -l)" -eq 5 ] || fail "fail: not 5 frames written"
  no_partial "$dir"
fi

# An array past the cluster's MaxArraySize (100 here, 1001 by default) is refused before sbatch,
# naming the chunk size that fits; nothing is submitted.
# The newest job id slurmctld knows (finished jobs stay listed for MinJobAge, 300 s): a count of
# queued jobs would also change when earlier scenarios' cancelled jobs leave the queue.
newest_job() { scontrol -o show jobs 2>/dev/null | grep -o '^JobId=[0-9]*' | cut -d= -f2 | sort -n | tail -1; }
newest_before="$(newest_job)"
out="$(SBATCH_ARGS="$base_sbatch" bash "$slurm/submit_sequence.sh" "$scene" 0-239 \
  "$work/big/s.####.exr" 2>&1)"
rc=$?
if [ "$rc" -ne 2 ] || ! grep -q "MaxArraySize 100 .*FRAMES_PER_TASK=3 or more" <<<"$out"; then
  fail "array 0-239 with MaxArraySize 100: exit $rc: $out"
fi
[ "$(newest_job)" = "$newest_before" ] || fail "a refused array submitted jobs (newest job $(newest_job), was $newest_before)"

# The warning before the time limit (submitted first, above).
frames_job="$signal_job" sheet_job="$signal_sheet" dir="$work/signal"
if [ -n "$frames_job" ]; then
  wait_jobs 240 "$frames_job" "$sheet_job"
  log="$work/jobs/kasumi-frames-${frames_job}_0.log"
  restarts="$(field "$frames_job" Restarts)"
  state="$(all_states "$frames_job") $(all_states "$sheet_job")"
  step "signal: $state after $restarts requeue(s); $(grep -c '^sequence: .* frames:' "$log") runs"
  grep -q "the frame in flight was dropped" "$log" ||
    fail "signal: no frame was stopped by the warning: $(tail -n 4 "$log")"
  grep -q "time limit near: .*requeueing" "$log" || fail "signal: the task did not requeue itself"
  [ "$restarts" -ge 1 ] || fail "signal: the task was not requeued"
  [ "$state" = "COMPLETED COMPLETED" ] || fail "signal: states $state (contact sheet exit" \
    "$(field "$sheet_job" ExitCode)): $(tail -n 2 "$log") $(cat "$work"/jobs/kasumi-sheet-*.log)"
  [ "$(find "$dir" -name 's.*.exr' | wc -l)" -eq "$sig_frames" ] ||
    fail "signal: not $sig_frames frames"
  no_partial "$dir"
  # The last two frames were rendered after a requeue: the same bits as a local run (and the
  # first two, before the warning).
  "$kasumi" sequence "$scene" --frames "$((sig_frames - 2))-$((sig_frames - 1))" \
    -o "$work/signal_local/s.####.exr" \
    "${sig_flags[@]}" -q --no-contact-sheet || fail "signal: local run failed"
  compare_frames "$work/signal_local" "$dir" || fail "signal: frames differ from the local run"
fi

cluster_stop
leaked="$(find /etc/slurm /etc/munge /run/munge /run/slurm* /var/run/munge /var/spool/slurm* \
  /var/log/slurm* /var/log/munge /var/lib/munge /var/lib/slurm* -newer "$work/marker" \
  2>/dev/null)"
[ -z "$leaked" ] || fail "files written outside $work: $leaked"

echo "cluster test: $failures failure(s) in $((SECONDS - started)) s"
[ "$failures" -eq 0 ]
