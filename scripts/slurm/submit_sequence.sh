#!/usr/bin/env bash
# Submits a kasumi sequence to Slurm: an array job of frames (sequence.sbatch), after it
# succeeds the contact sheet job (contact_sheet.sbatch), and after that the movie job
# (movie.sbatch). Prints the three job ids.
#
# usage: submit_sequence.sh SCENE FRAMES OUTPUT [-- KASUMI FLAGS...]
#   e.g. submit_sequence.sh data/scenes/fog_sequence.json 0-239 'out/fog.####.exr' -- --spp 64
# Environment: FRAMES_PER_TASK (default 1), MAX_PARALLEL (array tasks at once, default 0: no
# limit), PREVIEW_DIR, KASUMI (binary; default: kasumi on PATH), SBATCH_ARGS (more sbatch flags,
# e.g. "--partition=cpu --account=abc"), SBATCH (the sbatch command; tests point it at a stub),
# MOVIE (the movie's path; default out/<name>.mp4 beside the frames; "none": no movie job),
# MOVIE_FPS (default 24).
set -euo pipefail

if [ $# -lt 3 ]; then
  sed -n '2,13p' "$0" >&2
  exit 2
fi
scene="$1" frames="$2" output="$3"
shift 3
[ "${1:-}" = "--" ] && shift
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
sbatch="${SBATCH:-sbatch}"
per="${FRAMES_PER_TASK:-1}"

if ! [[ "$frames" =~ ^([0-9]+)-([0-9]+)(:([0-9]+))?$ ]]; then
  echo "submit_sequence.sh: FRAMES must be A-B[:step], got '$frames'" >&2
  exit 2
fi
first="${BASH_REMATCH[1]}" last="${BASH_REMATCH[2]}" step="${BASH_REMATCH[4]:-1}"
count=$(( (last - first) / step + 1 ))
if [ "$per" -le 1 ]; then
  array="$first-$last:$step"                         # index = frame
else
  array="0-$(( (count + per - 1) / per - 1 ))"       # index = chunk
fi
[ "${MAX_PARALLEL:-0}" -gt 0 ] && array="$array%$MAX_PARALLEL"

# Slurm refuses an array index >= MaxArraySize (default 1001) with only "Invalid job array
# specification": name the limit and the chunk size that fits (frames past 1000 need chunks).
top=$(( (count + per - 1) / per - 1 ))                 # the last chunk
[ "$per" -le 1 ] && top=$((first + (count - 1) * step))  # the last frame
max_array="$( (scontrol show config 2>/dev/null || true) |
  sed -n 's/^MaxArraySize *= *\([0-9]*\).*/\1/p')"
if [ -n "$max_array" ] && [ "$top" -ge "$max_array" ]; then
  need=$(( (count + max_array - 1) / max_array ))
  [ "$need" -lt 2 ] && need=2
  echo "submit_sequence.sh: array index $top >= MaxArraySize $max_array of this cluster;" \
    "use FRAMES_PER_TASK=$need or more" >&2
  exit 2
fi

export SCENE="$scene" OUTPUT="$output" FRAMES="$frames" FRAMES_PER_TASK="$per"
export KASUMI="${KASUMI:-kasumi}" KASUMI_ARGS="$*" PREVIEW_DIR="${PREVIEW_DIR:-}"
# shellcheck disable=SC2086  # SBATCH_ARGS is split into words on purpose
frames_job=$("$sbatch" --parsable ${SBATCH_ARGS:-} --array="$array" --export=ALL \
  "$here/sequence.sbatch")
frames_job="${frames_job%%;*}"
# shellcheck disable=SC2086
sheet_job=$("$sbatch" --parsable ${SBATCH_ARGS:-} --dependency="afterok:$frames_job" \
  --kill-on-invalid-dep=yes --export=ALL "$here/contact_sheet.sbatch")
sheet_job="${sheet_job%%;*}"
if [ "${MOVIE:-}" = none ]; then
  echo "frames: job $frames_job (array $array); contact sheet: job $sheet_job"
  exit 0
fi
export MOVIE="${MOVIE:-}" MOVIE_FPS="${MOVIE_FPS:-24}"
# shellcheck disable=SC2086
movie_job=$("$sbatch" --parsable ${SBATCH_ARGS:-} --dependency="afterok:$sheet_job" \
  --kill-on-invalid-dep=yes --export=ALL "$here/movie.sbatch")
echo "frames: job $frames_job (array $array); contact sheet: job $sheet_job;" \
  "movie: job ${movie_job%%;*}"
