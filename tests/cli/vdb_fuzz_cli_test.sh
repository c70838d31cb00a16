#!/usr/bin/env bash
# Damaged and hostile .vdb files through the whole CLI path (the direct reader, then OpenVDB's
# for what it declines): a cloud from `make-cloud --res 8`, cut at many lengths, single bytes set
# to 0xFF or 0x00, and 4-byte fields overwritten with huge or negative counts. `kasumi check`
# must exit 0 or 3 (docs: 3 = invalid input file) within 20 s and under 4 GB of address space,
# print one line naming the file on 3, and never hit a sanitizer report, an assertion or an
# internal error; a mutant that checks must also give a finite radiance probe. Without STRIDE a
# fixed set of mutants (about 10 runs; ctest); `vdb_fuzz_cli_test.sh KASUMI SRC STRIDE` sweeps
# every STRIDE-th offset (STRIDE 97: 422 runs, 13 min wall at load 6-9) for a long local run.
# The fixed set holds what the sweep found: with `make-cloud --res 8 --seed 5`, bytes 00 00 00
# 80 written at 8970, 9165 or 9360 set a bit of a 4-level node's child mask, and OpenVDB's
# fallback, reading every leaf's values 64 bytes late, allocated a garbage chunk size (out of
# memory, exit 1; now the direct reader refuses the file, exit 3); byte 8 = 0xff (file format
# 255) made OpenVDB print a WARN line on stdout, breaking probe's JSON (now on stderr).
# usage: vdb_fuzz_cli_test.sh KASUMI_BINARY SOURCE_DIR [STRIDE]
set -u
kasumi="$1"
src="$2"
stride="${3:-0}"
source "$(dirname "$0")/cli_lib.sh"

sanitized=0
if ldd "$kasumi" 2>/dev/null | grep -q libasan; then
  sanitized=1 # ASan reserves terabytes of address space: no ulimit -v
fi

"$kasumi" make-cloud --res 8 --seed 5 -o "$work/c8.vdb" -q || fail "make-cloud failed"
cat >"$work/scene.json" <<JSON
{
  "camera": {"position": [0, 30, 400], "look_at": [0, 30, 0]},
  "film": {"width": 8, "height": 6, "spp": 1},
  "lights": [{"type": "directional", "direction": [0, -1, 0], "illuminance_lux": 1000}],
  "media": [{"type": "vdb", "file": "m.vdb", "density_scale": 0.02, "albedo": 0.9}]
}
JSON
size=$(stat -c %s "$work/c8.vdb")
runs=0

# run_mutant WHAT: checks $work/m.vdb.
run_mutant() {
  local what="$1" limit=""
  runs=$((runs + 1))
  [ "$sanitized" -eq 0 ] && limit="ulimit -v 4000000;"
  bash -c "$limit exec timeout -s KILL 20 \"\$0\" check \"\$1\"" "$kasumi" "$work/scene.json" \
    >"$work/stdout" 2>"$work/stderr"
  local got=$?
  if [ "$got" -ne 0 ] && [ "$got" -ne 3 ]; then
    fail "$what: check exited $got: $(head -c 400 "$work/stderr")"
    return
  fi
  if grep -q "internal error\|Assertion\|runtime error:\|AddressSanitizer\|LeakSanitizer" \
    "$work/stderr"; then
    fail "$what: $(head -c 400 "$work/stderr")"
    return
  fi
  if [ "$got" -eq 3 ]; then
    grep -q "m.vdb" "$work/stderr" || fail "$what: the message does not name the file: $(cat "$work/stderr")"
    [ "$(wc -l <"$work/stderr")" -le 1 ] || fail "$what: more than one line: $(cat "$work/stderr")"
    return
  fi
  timeout -s KILL 20 "$kasumi" probe radiance "$work/scene.json" --origin 0,30,400 \
    --direction 0,0,-1 --spp 4 >"$work/stdout" 2>"$work/stderr"
  got=$?
  if [ "$got" -ne 0 ] && [ "$got" -ne 3 ]; then
    fail "$what: probe exited $got: $(head -c 400 "$work/stderr")"
  elif [ "$got" -eq 0 ]; then
    python3 -c "import json,math,sys; j=json.load(open(sys.argv[1])); sys.exit(0 if all(math.isfinite(v) and v >= 0 for v in j['radiance']) else 1)" \
      "$work/stdout" || fail "$what: radiance $(cat "$work/stdout")"
  fi
}

# put OFFSET HEX_BYTES: overwrites bytes of a copy of the cloud.
put() {
  cp "$work/c8.vdb" "$work/m.vdb"
  printf "$2" | dd of="$work/m.vdb" bs=1 seek="$1" conv=notrunc status=none
}

cp "$work/c8.vdb" "$work/m.vdb"
run_mutant "unmutated"
if [ "$stride" -eq 0 ]; then
  for cut in 100 2000 9000; do
    head -c "$cut" "$work/c8.vdb" >"$work/m.vdb"
    run_mutant "cut at $cut"
  done
  for at in 8 300 5000; do
    put "$at" '\xff'
    run_mutant "byte $at = 0xff"
  done
  for at in 8970 9165 9360; do
    put "$at" '\x00\x00\x00\x80'
    run_mutant "int32 -2^31 at $at"
  done
  stride=$((size + 1))  # no sweep
fi
for ((cut = 0; cut < size; cut += stride)); do
  head -c "$cut" "$work/c8.vdb" >"$work/m.vdb"
  run_mutant "cut at $cut"
done
for ((at = 0; at < size; at += stride)); do
  put "$at" '\xff'
  run_mutant "byte $at = 0xff"
  put "$at" '\x00'
  run_mutant "byte $at = 0x00"
done
for ((at = 0; at + 4 <= size; at += 2 * stride + 1)); do
  put "$at" '\xff\xff\xff\x7f'
  run_mutant "int32 2^31-1 at $at"
  put "$at" '\x00\x00\x00\x80'
  run_mutant "int32 -2^31 at $at"
done

finish "vdb fuzz cli ($runs mutants of a $size-byte file, each to exit 0 or 3)"
