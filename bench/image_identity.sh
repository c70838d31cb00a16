#!/usr/bin/env bash
# Bit-identity of rendered images across a change (a restructuring must not move one bit).
#   bench/image_identity.sh render KASUMI DIR   render every shipped scene (small film, few
#                                               samples, two frames of animated scenes) into DIR
#   bench/image_identity.sh compare DIR_A DIR_B every image of A has the same pixels in B
# Images are written uncompressed; compare reads each EXR's pixel chunks (everything after the
# header and offset table), so header metadata that names the time or host does not count.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
mode="${1:-}"

render() {
  local kasumi="$1" dir="$2" scene name frames
  mkdir -p "$dir"
  for scene in "$root"/data/scenes/*.json; do
    name="$(basename "$scene" .json)"
    frames="0"
    grep -q '"animate"' "$scene" && frames="0 7"
    for frame in $frames; do
      if ! "$kasumi" render "$scene" -q --res 96x54 --spp 4 --threads 2 --frame "$frame" \
        --compression none --no-preview -o "$dir/$name.$frame.exr" 2>"$dir/$name.$frame.err"; then
        echo "$name frame $frame: exit $? ($(head -c 200 "$dir/$name.$frame.err"))"
      fi
    done
  done
}

compare() {
  python3 - "$1" "$2" <<'PY'
import os, struct, sys
a, b = sys.argv[1], sys.argv[2]

def pixels(path):
    data = open(path, "rb").read()
    p, lines = 8, None
    while data[p] != 0:
        n = data.index(b"\0", p); t = data.index(b"\0", n + 1)
        (size,) = struct.unpack("<i", data[t + 1:t + 5])
        if data[p:n] == b"dataWindow":
            x0, y0, x1, y1 = struct.unpack("<4i", data[t + 5:t + 21]); lines = y1 - y0 + 1
        p = t + 5 + size
    return data[p + 1 + 8 * lines:]  # uncompressed: one chunk a scan line

names = sorted(f for f in os.listdir(a) if f.endswith(".exr"))
bad = 0
for f in names:
    other = os.path.join(b, f)
    if not os.path.exists(other):
        print("missing in %s: %s" % (b, f)); bad += 1
    elif pixels(os.path.join(a, f)) != pixels(other):
        print("differs: %s" % f); bad += 1
print("%d images compared, %d differ or are missing" % (len(names), bad))
sys.exit(1 if bad or not names else 0)
PY
}

case "$mode" in
  render) render "$2" "$3" ;;
  compare) compare "$2" "$3" ;;
  *) echo "usage: $0 render KASUMI DIR | compare DIR_A DIR_B" >&2; exit 2 ;;
esac
