#!/usr/bin/env bash
# film.denoise on the command line: a bad value exits 3 naming /film/denoise; a denoised render
# writes the raw beauty as noisy.R/G/B and says so in its metadata, a raw one writes neither;
# `kasumi plan` names the denoise stage, ran or skipped.
# usage: denoise_cli_test.sh KASUMI_BINARY SOURCE_DIR
set -u
kasumi="$1"
src="$2"
source "$(dirname "$0")/cli_lib.sh"
header() { python3 "$(dirname "$0")/exr_header.py" "$@"; }
scene="$src/data/scenes/cloud.json"
tiny=(--res 24x14 --spp 4 --seed 3 --no-preview -q)

expect_exit 3 "/film/denoise" -- render "$scene" "${tiny[@]}" -o "$work/x.exr" --set '/film/denoise="oidn"'
expect_exit 3 "/film/denoise/radius" -- render "$scene" "${tiny[@]}" -o "$work/x.exr" \
  --set '/film/denoise={"radius": 0}'
expect_exit 3 "/film/denoise" -- check "$scene" -q --set /film/denoise=7
expect_exit 3 "/film/denoise/select" -- render "$scene" "${tiny[@]}" -o "$work/x.exr" \
  --set '/film/denoise={"select": 2}'

expect_exit 0 "" -- render "$scene" "${tiny[@]}" -o "$work/on.exr" --set '/film/denoise="nlm"'
expect_exit 0 "" -- render "$scene" "${tiny[@]}" -o "$work/off.exr"
case "$(header "$work/on.exr" channels)" in
  *noisy.R*) ;;
  *) fail "a denoised render has no noisy.R: $(header "$work/on.exr" channels)" ;;
esac
case "$(header "$work/off.exr" channels)" in
  *noisy.R*) fail "a raw render has noisy.R" ;;
esac
[ "$(header "$work/on.exr" attr:kasumi/denoise)" != "-" ] || fail "no kasumi/denoise metadata"
[ "$(header "$work/off.exr" attr:kasumi/denoise)" = "-" ] || fail "raw render says denoised"

expect_exit 0 "" -- plan "$scene" --set '/film/denoise="nlm"'
grep -qE "run +denoise: non-local means" "$work/stdout" || fail "plan: $(cat "$work/stdout")"
expect_exit 0 "" -- plan "$scene" --set '/film/denoise={"select": true}'
grep -qE "run +denoise: .*select: .*SURE" "$work/stdout" || fail "plan: $(cat "$work/stdout")"
expect_exit 0 "" -- render "$scene" "${tiny[@]}" -o "$work/sel.exr" --set '/film/denoise={"select": true}'
case "$(header "$work/sel.exr" attr:kasumi/denoise)" in
  *select*) ;;
  *) fail "metadata does not name the selection: $(header "$work/sel.exr" attr:kasumi/denoise)" ;;
esac
expect_exit 0 "" -- plan "$scene"
grep -qE "denoise: film.denoise is \"off\"" "$work/stdout" || fail "plan: $(cat "$work/stdout")"
finish denoise_cli
