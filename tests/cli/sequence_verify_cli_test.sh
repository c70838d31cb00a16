#!/usr/bin/env bash
# The sequence manifest and `kasumi sequence --verify` (docs/sequences.md#manifest): a clean run
# verifies (exit 0); a deleted frame is missing, a changed scene or setting makes frames stale,
# a flipped byte in an EXR makes it corrupt, an EXR without its record is unrecorded (exit 5,
# one line per frame on stdout); records written by separate runs (array tasks) merge.
# usage: sequence_verify_cli_test.sh KASUMI_BINARY SOURCE_DIR
set -u
kasumi="$1"
src="$2"
source "$(dirname "$0")/cli_lib.sh"
scene="$src/data/scenes/fog_sequence.json"
tiny=(--res 32x18 --spp 1 --threads 1)
out="$work/s/fog.####.exr"

# Frames 0-5 as two "tasks" (0-2 and 3-5), each writing its own records.
expect_exit 0 "" -- sequence "$scene" --frames 0-2 -o "$out" "${tiny[@]}" -q --no-contact-sheet
expect_exit 0 "" -- sequence "$scene" --frames 3-5 -o "$out" "${tiny[@]}" -q --no-contact-sheet
[ "$(find "$work/s" -name 'fog.*.manifest.json' | wc -l)" -eq 6 ] || fail "not 6 records"
python3 - "$work/s/fog.0004.manifest.json" <<'PY' || fail "record content"
import json, socket, sys
r = json.load(open(sys.argv[1]))
assert r["frame"] == 4 and r["file"] == "fog.0004.exr", r
assert r["scene_hash"].startswith("fnv1a64:") and r["exr_hash"].startswith("fnv1a64:"), r
assert r["settings"]["width"] == 32 and r["settings"]["height"] == 18 and r["settings"]["spp"] == 1
assert r["host"] == socket.gethostname() and r["render_seconds"] >= 0 and "seed" in r, r
PY
expect_exit 0 "verify: 6 frames: 6 ok, 0 missing, 0 stale, 0 corrupt, 0 unrecorded" -- \
  sequence "$scene" --frames 0-5 -o "$out" "${tiny[@]}" --verify
[ -s "$work/stdout" ] && fail "a clean verify printed frames: $(cat "$work/stdout")"
# --verify renders nothing.
expect_exit 5 "1 missing" -- sequence "$scene" --frames 0-6 -o "$out" "${tiny[@]}" --verify
[ -e "$work/s/fog.0006.exr" ] && fail "--verify rendered a frame"

# Missing: a deleted frame.
rm "$work/s/fog.0001.exr"
expect_exit 5 "verify: 6 frames: 5 ok, 1 missing" -- sequence "$scene" --frames 0-5 -o "$out" \
  "${tiny[@]}" --verify
grep -qE "^frame 000001  missing  " "$work/stdout" || fail "missing: $(cat "$work/stdout")"
# Corrupt: one byte of frame 2 flipped (the file stays readable in size).
python3 - "$work/s/fog.0002.exr" <<'PY'
import sys
data = bytearray(open(sys.argv[1], "rb").read())
data[len(data) // 2] ^= 0x01
open(sys.argv[1], "wb").write(data)
PY
expect_exit 5 "4 ok, 1 missing, 0 stale, 1 corrupt" -- sequence "$scene" --frames 0-5 -o "$out" \
  "${tiny[@]}" --verify
grep -qE "^frame 000002  corrupt .*content fnv1a64:[0-9a-f]{16}, recorded" "$work/stdout" ||
  fail "corrupt: $(cat "$work/stdout")"
# Corrupt: an unreadable record.
echo '{"frame": 3' >"$work/s/fog.0003.manifest.json"
expect_exit 5 "3 ok, 1 missing, 0 stale, 2 corrupt" -- sequence "$scene" --frames 0-5 \
  -o "$out" "${tiny[@]}" --verify
grep -qE "^frame 000003  corrupt .*not a frame record" "$work/stdout" ||
  fail "unreadable record: $(cat "$work/stdout")"
# Unrecorded: an EXR without a record.
rm "$work/s/fog.0004.manifest.json"
expect_exit 5 "1 unrecorded" -- sequence "$scene" --frames 0-5 -o "$out" "${tiny[@]}" --verify
# Stale: the scene changed (a --set), or a setting outside the document (--compression).
expect_exit 5 "0 ok, 1 missing, 2 stale, 2 corrupt, 1 unrecorded" -- sequence "$scene" \
  --frames 0-5 -o "$out" "${tiny[@]}" --set /render/seed=9 --verify
grep -qE "^frame 000005  stale .*the scene changed" "$work/stdout" ||
  fail "stale scene: $(cat "$work/stdout")"
expect_exit 5 "2 stale" -- sequence "$scene" --frames 0-5 -o "$out" "${tiny[@]}" \
  --compression piz --verify
grep -qE "^frame 000005  stale .*settings .*recorded" "$work/stdout" ||
  fail "stale settings: $(cat "$work/stdout")"
# A changed scene file: the animation edited.
sed 's/"seed": 1/"seed": 2/' "$scene" >"$work/changed.json"
grep -q '"seed": 2' "$work/changed.json" || fail "the scene edit did not apply"
expect_exit 5 "2 stale" -- sequence "$work/changed.json" --frames 0-5 -o "$out" "${tiny[@]}" \
  --verify

# A pattern without an extension gets a record per frame all the same.
expect_exit 0 "" -- sequence "$scene" --frames 0-1 -o "$work/n/fog.####" "${tiny[@]}" -q \
  --no-contact-sheet
[ -s "$work/n/fog.0000.manifest.json" ] && [ -s "$work/n/fog.0001.manifest.json" ] ||
  fail "records of an extension-less pattern: $(ls "$work/n")"
expect_exit 0 "2 ok" -- sequence "$scene" --frames 0-1 -o "$work/n/fog.####" "${tiny[@]}" --verify

# Rendering the missing and the stale again (without --skip-existing) makes it clean.
expect_exit 0 "" -- sequence "$scene" --frames 0-5 -o "$out" "${tiny[@]}" -q --no-skip-existing \
  --no-contact-sheet
expect_exit 0 "6 ok" -- sequence "$scene" --frames 0-5 -o "$out" "${tiny[@]}" --verify

finish sequence_verify_cli
