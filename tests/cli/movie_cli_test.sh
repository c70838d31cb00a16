#!/usr/bin/env bash
# `kasumi sequence --movie` and `kasumi movie`: the H.264 movie of a sequence checked with
# ffprobe (frame count, size made even, frame rate, codec), its pictures against the previews
# (same view and exposure), a missing frame (exit 3, named), no ffmpeg on PATH (exit 2, names
# the Debian package), a failing ffmpeg (exit 4): never a movie or a temporary left behind.
# usage: movie_cli_test.sh KASUMI_BINARY SOURCE_DIR
set -u
kasumi="$1"
src="$2"
source "$(dirname "$0")/cli_lib.sh"
scene="$src/data/scenes/sunset_sequence.json"
tiny=(--res 33x19 --spp 1)  # odd on purpose: yuv420p needs even sizes

if ! command -v ffprobe >/dev/null || ! command -v ffmpeg >/dev/null; then
  echo "FAIL: ffmpeg/ffprobe not installed (Debian package ffmpeg; scripts/bootstrap.sh)"
  exit 1
fi

# probe FILE: "frames width height rate codec pix_fmt" of the first video stream.
probe() {
  ffprobe -v error -count_frames -select_streams v:0 \
    -show_entries stream=nb_read_frames,width,height,r_frame_rate,codec_name,pix_fmt \
    -of default=nw=1 "$1" | sort | awk -F= '{v[$1] = $2}
      END {print v["nb_read_frames"], v["width"], v["height"], v["r_frame_rate"],
                 v["codec_name"], v["pix_fmt"]}'
}
# mean_rgb FILE [FILTER]: the mean 8-bit value of the first picture (ffmpeg decodes it).
mean_rgb() {
  ffmpeg -v error -i "$1" -frames:v 1 ${2:+-vf "$2"} -f rawvideo -pix_fmt rgb24 - |
    python3 -c 'import sys; b = sys.stdin.buffer.read(); print(sum(b) / len(b))'
}
no_leftovers() {  # DIR: no temporary of core/atomic_file
  [ -z "$(find "$1" -name '.*.tmp' 2>/dev/null)" ] || fail "temporaries left in $1: $(ls -a "$1")"
}

# A sequence and its movie in one command: 12 frames, 33x19 padded to 34x20, 24 fps.
expect_exit 0 "movie: $work/s/sunset.mp4 \(12 frames, 34x20, 24 fps" -- sequence "$scene" \
  --frames 0-11 "${tiny[@]}" -o "$work/s/sunset.####.exr" --preview-dir "$work/p" \
  --movie "$work/s/sunset.mp4"
[ "$(probe "$work/s/sunset.mp4")" = "12 34 20 24/1 h264 yuv420p" ] ||
  fail "sequence --movie: ffprobe says '$(probe "$work/s/sunset.mp4")'"
no_leftovers "$work/s"

# The movie shows what the previews show: the same view and exposure ("auto", -13.6 stops at frame 0;
# without it the frame would be white), up to H.264's loss.
movie_mean="$(mean_rgb "$work/s/sunset.mp4" crop=33:19:0:0)"
png_mean="$(mean_rgb "$work/p/sunset.0000.png")"
python3 -c "import sys; sys.exit(abs($movie_mean - $png_mean) > 6)" ||
  fail "movie frame 0 mean $movie_mean, preview mean $png_mean"

# The standalone command: frames found on disk, its own frame rate, default name.
expect_exit 0 "" -- movie "$work/s/sunset.####.exr" --fps 30 -q
[ "$(probe "$work/s/sunset.mp4")" = "12 34 20 30/1 h264 yuv420p" ] ||
  fail "movie --fps 30 (default name): ffprobe says '$(probe "$work/s/sunset.mp4")'"
expect_exit 0 "" -- movie "$work/s/sunset.####.exr" --frames 2-10:2 -o "$work/m/five.mp4" -q
[ "$(probe "$work/m/five.mp4" | cut -d' ' -f1)" = 5 ] || fail "--frames 2-10:2 is not 5 frames"

# A missing frame: exit 3 naming it, nothing written.
rm "$work/s/sunset.0005.exr"
expect_exit 3 "frame 5 is missing \($work/s/sunset.0005.exr\)" -- \
  movie "$work/s/sunset.####.exr" -o "$work/s/gap.mp4"
[ -e "$work/s/gap.mp4" ] && fail "a movie with a missing frame was written"
expect_exit 3 "frame 5 is missing" -- sequence "$scene" --frames 0-11 "${tiny[@]}" \
  -o "$work/s/sunset.####.exr" --contact-sheet-only --movie "$work/s/gap.mp4"
[ -e "$work/s/gap.mp4" ] && fail "sequence --movie with a missing frame wrote a movie"
expect_exit 3 "no frame found" -- movie "$work/none/x.####.exr" -o "$work/x.mp4"

# No ffmpeg on PATH: exit 2 naming the package, no movie, no temporary.
printf '#!/bin/sh\nPATH=/nonexistent exec "%s" "$@"\n' "$kasumi" >"$work/kasumi_no_path"
chmod +x "$work/kasumi_no_path"
real_kasumi="$kasumi"
kasumi="$work/kasumi_no_path"
expect_exit 2 "install the Debian package ffmpeg" -- \
  movie "$work/s/sunset.####.exr" --frames 0-4 -o "$work/nf/nf.mp4"
kasumi="$real_kasumi"
[ -n "$(ls -A "$work/nf" 2>/dev/null)" ] && fail "no ffmpeg, yet files: $(ls -A "$work/nf")"

# An ffmpeg that fails half-way: exit 4, no movie under the final name, no temporary.
mkdir -p "$work/bin" "$work/ff"
printf '#!/bin/sh\nhead -c 100 >/dev/null\necho "fake ffmpeg: failing" >&2\nexit 1\n' \
  >"$work/bin/ffmpeg"
chmod +x "$work/bin/ffmpeg"
PATH="$work/bin:$PATH" expect_exit 4 "ff.mp4: ffmpeg exited with status 1" -- \
  movie "$work/s/sunset.####.exr" --frames 0-4 -o "$work/ff/ff.mp4"
grep -q "fake ffmpeg: failing" "$work/stderr" || fail "ffmpeg's own message was not passed on"
[ -n "$(ls -A "$work/ff")" ] && fail "a failed ffmpeg left files: $(ls -A "$work/ff")"

# Usage: a pattern without '#'; --movie of a single farm frame.
expect_exit 2 "run of '#'" -- movie "$work/s/sunset.exr" -o "$work/u.mp4"
expect_exit 2 "--movie needs the whole --frames" -- sequence "$scene" --frames 0-11 --frame 3 \
  -o "$work/s/sunset.####.exr" --movie "$work/u.mp4"
[ -e "$work/u.mp4" ] && fail "a usage error wrote a movie"

finish movie_cli
