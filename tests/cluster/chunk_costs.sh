#!/usr/bin/env bash
# Per-frame cost of a sequence on a throw-away single-node Slurm cluster (slurm_lib.sh) with 1, 6
# and 24 frames per array task: the figures of docs/cluster.md, "Chunking". Not a test.
#   chunk_costs.sh KASUMI_BINARY SOURCE_DIR [FRAMES] [KASUMI FLAGS...]
#   e.g. chunk_costs.sh build/release/apps/kasumi . 0-47 --res 1280x720 --spp 1
# Every kasumi process runs under /usr/bin/time (CPU seconds, peak memory); the wall time is from
# the first task's start to the last task's end (scontrol, 1 s resolution). Needs root.
set -uo pipefail
kasumi="$(realpath "${1:?usage: chunk_costs.sh KASUMI_BINARY SOURCE_DIR [FRAMES] [FLAGS...]}")"
src="$(realpath "${2:?usage: chunk_costs.sh KASUMI_BINARY SOURCE_DIR [FRAMES] [FLAGS...]}")"
frames="${3:-0-47}"
shift 3 2>/dev/null || shift $#
flags=("$@")
# The fixed exposure the measurements in docs/cluster.md were taken with ("auto" adds meter
# renders at each task's start: docs/sequences.md#auto-exposure).
[ "${#flags[@]}" -eq 0 ] && flags=(--res 1280x720 --spp 1 --set /render/preview/exposure_stops=-11)
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
# shellcheck source=tests/cluster/slurm_lib.sh
source "$here/slurm_lib.sh"
cluster_install || exit $?
work="$(mktemp -d /tmp/kasumi-chunks.XXXXXX)"
chmod 755 "$work"
trap 'cluster_stop; rm -rf "$work"' EXIT
cluster_start "$work/cluster" || exit 1

cat >"$work/kasumi-timed" <<WRAP
#!/bin/sh
exec /usr/bin/time -a -o "\$TIME_LOG" -f "%e %U %S %M" "$kasumi" "\$@"
WRAP
chmod +x "$work/kasumi-timed"
count=$(( ${frames#*-} - ${frames%-*} + 1 ))
echo "frames $frames ($count), kasumi ${flags[*]}; load $(cut -d' ' -f1-3 /proc/loadavg)"
printf '%-16s %6s %14s %14s %12s %10s\n' "frames a task" tasks "CPU s a frame" \
  "wall s a frame" "wall total" "peak RSS"
for per in 1 6 24; do
  mkdir -p "$work/jobs"
  out="$(cd "$work/jobs" && MOVIE=none FRAMES_PER_TASK=$per KASUMI="$work/kasumi-timed" \
    TIME_LOG="$work/time.$per" \
    SBATCH_ARGS="--chdir=$work/jobs --cpus-per-task=1 --mem=2G" \
    bash "$src/scripts/slurm/submit_sequence.sh" "$src/data/scenes/sunset_sequence.json" \
    "$frames" "$work/per$per/s.####.exr" -- "${flags[@]}" -q)"
  job="$(sed -n 's/^frames: job \([0-9]*\) .*/\1/p' <<<"$out")"
  sheet="$(sed -n 's/.*contact sheet: job \([0-9]*\).*/\1/p' <<<"$out")"
  while [ -n "$(squeue -h -j "$job,$sheet" -o %i)" ]; do sleep 1; done
  states="$(scontrol -o show job "$job" | grep -o 'JobState=[A-Z]*' | sort -u | tr '\n' ' ')"
  [ "$states" = "JobState=COMPLETED " ] || echo "per $per: $states"
  first="$(scontrol -o show job "$job" | grep -o 'StartTime=[^ ]*' | cut -d= -f2 | sort |
    head -n 1)"
  last="$(scontrol -o show job "$job" | grep -o 'EndTime=[^ ]*' | cut -d= -f2 | sort |
    tail -n 1)"
  wall=$(( $(date -d "$last" +%s) - $(date -d "$first" +%s) ))
  # The contact sheet job (last line of the log) is not a frame task.
  head -n -1 "$work/time.$per" | awk -v n="$count" -v per="$per" -v wall="$wall" '
    { cpu += $2 + $3; tasks++; if ($4 > rss) rss = $4 }
    END { printf "%-16s %6d %14.3f %14.3f %10d s %7.0f MB\n", per, tasks, cpu / n, wall / n,
          wall, rss / 1024 }'
done
