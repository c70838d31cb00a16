#!/usr/bin/env bash
# `kasumi render` and `kasumi sequence` write a frame through one writer (render/frame_output.h):
# the same scene, frame and seed give EXRs with the same kasumi/* metadata keys and the same
# values for the keys that do not measure time. Also checks the comparison can fail: a file
# written by another program (a planted key) is told apart.
# usage: exr_metadata_cli_test.sh KASUMI_BINARY SOURCE_DIR
set -u
kasumi="$1"
src="$2"
source "$(dirname "$0")/cli_lib.sh"
header() { python3 "$(dirname "$0")/exr_header.py" "$@"; }
scene="$src/data/scenes/fog_sequence.json"
tiny=(--res 32x18 --spp 1 --seed 7)

expect_exit 0 "" -- render "$scene" "${tiny[@]}" --frame 3 --no-preview -q -o "$work/render.exr"
expect_exit 0 "" -- sequence "$scene" "${tiny[@]}" --frame 3 -q -o "$work/seq/frame.####.exr"
render_keys="$(header "$work/render.exr" attr-names:kasumi/)"
sequence_keys="$(header "$work/seq/frame.0003.exr" attr-names:kasumi/)"
[ -n "$render_keys" ] || fail "render wrote no kasumi/* metadata"
[ "$render_keys" = "$sequence_keys" ] ||
  fail "kasumi/* keys differ: render [$render_keys], sequence [$sequence_keys]"
for key in version frame spp seed units interrupted plan/ran plan/skipped stats/camera_rays; do
  r="$(header "$work/render.exr" "attr:kasumi/$key")"
  s="$(header "$work/seq/frame.0003.exr" "attr:kasumi/$key")"
  [ "$r" != "-" ] || fail "render lacks kasumi/$key"
  [ "$r" = "$s" ] || fail "kasumi/$key: render '$r', sequence '$s'"
done
[ "$(header "$work/render.exr" attr:kasumi/frame)" = "3" ] || fail "kasumi/frame is not 3"

# The check itself: a file with one key more is told apart.
python3 - "$work/render.exr" "$work/planted.exr" <<'PY'
import struct, sys
data = open(sys.argv[1], "rb").read()
value = b"planted"
attr = b"kasumi/planted\0string\0" + struct.pack("<i", len(value)) + value
open(sys.argv[2], "wb").write(data[:8] + attr + data[8:])
PY
[ "$(header "$work/planted.exr" attr-names:kasumi/)" != "$render_keys" ] ||
  fail "a planted key was not seen"

finish "exr metadata"
