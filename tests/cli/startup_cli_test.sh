#!/usr/bin/env bash
# What a kasumi process loads: OpenVDB only through its module (libkasumi_vdb.so, dlopen'd on
# the first .vdb read or write), so commands and scenes without grids never load it; a VDB scene
# in the common layout is read without it (volume/grid/vdb_direct.h), and through it with
# KASUMI_VDB_DIRECT=0 (also the path of every other layout); a missing or foreign module is a
# clear runtime error (exit 1) naming the paths tried, with no output written. OpenColorIO likewise (libkasumi_ocio.so,
# only for the PNG preview), and OpenEXR's C++ library (libkasumi_exr.so, not for ZIP output). And `--aovs none` writes exactly R, G, B, A. Every subcommand is
# listed by --help and parses its own --help when named first (apps/main.cpp declares only it).
# usage: startup_cli_test.sh KASUMI_BINARY SOURCE_DIR
set -u
kasumi="$1"
src="$2"
source "$(dirname "$0")/cli_lib.sh"

# loaded_libs ARGS...: runs kasumi under the dynamic loader's trace; prints the files it loaded.
loaded_libs() { LD_DEBUG=files "$kasumi" "$@" 2>&1 >/dev/null | grep -o 'file=[^ ]*' | sort -u; }

libs=$(loaded_libs --version)
echo "$libs" | grep -q "file=" || fail "LD_DEBUG=files shows nothing: $libs"
echo "$libs" | grep -q "openvdb\|kasumi_vdb" && fail "--version loads OpenVDB: $libs"
echo "$libs" | grep -q "OpenColorIO\|kasumi_ocio" && fail "--version loads OpenColorIO: $libs"

cat >"$work/fog.json" <<JSON
{
  "camera": {"position": [0, 1, 5], "look_at": [0, 1, 0]},
  "film": {"width": 8, "height": 6, "spp": 1},
  "lights": [{"type": "directional", "direction": [0, -1, 0], "illuminance_lux": 1000}],
  "media": [{"type": "homogeneous", "sigma_a": 0.01, "sigma_s": 0.05}]
}
JSON
libs=$(loaded_libs render "$work/fog.json" -o "$work/fog.exr" --no-preview -q)
echo "$libs" | grep -q "openvdb\|kasumi_vdb" && fail "a scene without grids loads OpenVDB: $libs"
echo "$libs" | grep -q "OpenColorIO\|kasumi_ocio" && fail "a render without preview loads OpenColorIO: $libs"
# The default ZIP EXR is written through OpenEXR's core library; its C++ library only through
# the OpenEXR module (libkasumi_exr.so), for piz, rle and none (and reading EXRs).
echo "$libs" | grep -q "libOpenEXR-\|kasumi_exr" && fail "a zip render loads OpenEXR's C++ library: $libs"
libs=$(loaded_libs render "$work/fog.json" -o "$work/piz.exr" --no-preview -q --compression piz)
echo "$libs" | grep -q "kasumi_exr" || fail "a piz render did not load the OpenEXR module: $libs"
KASUMI_EXR_MODULE=/nonexistent/libkasumi_exr.so expect_exit 1 \
  "OpenEXR module.*/nonexistent/libkasumi_exr.so \(no such file\).*KASUMI_EXR_MODULE" -- \
  render "$work/fog.json" -o "$work/rle.exr" --no-preview -q --compression rle
[ -e "$work/rle.exr" ] && fail "an EXR was written without the OpenEXR module"
KASUMI_EXR_MODULE=/nonexistent/libkasumi_exr.so expect_exit 0 "" -- \
  render "$work/fog.json" -o "$work/zip.exr" --no-preview -q
# The PNG preview loads the OpenColorIO module; without it, exit 1 naming the path tried.
libs=$(loaded_libs render "$work/fog.json" -o "$work/p/fog.exr" -q)
echo "$libs" | grep -q "kasumi_ocio" || fail "the preview did not load the OpenColorIO module: $libs"
[ -s "$work/p/fog.png" ] || fail "no preview written"
KASUMI_OCIO_MODULE=/nonexistent/libkasumi_ocio.so expect_exit 1 \
  "OpenColorIO module.*/nonexistent/libkasumi_ocio.so \(no such file\).*KASUMI_OCIO_MODULE" -- \
  render "$work/fog.json" -o "$work/q/fog.exr" -q
[ -e "$work/q/fog.png" ] && fail "a preview was written without the OpenColorIO module"
# Without grids the module is not needed at all.
KASUMI_VDB_MODULE=/nonexistent/libkasumi_vdb.so expect_exit 0 "" -- render "$work/fog.json" -o "$work/fog2.exr" --no-preview -q

# A grid scene renders without the module (the direct reader), and through it when told to.
expect_exit 0 "" -- make-cloud --res 16 --seed 3 -o "$work/c16.vdb"
cat >"$work/cloud.json" <<JSON
{
  "camera": {"position": [0, 500, 3000], "look_at": [0, 500, 0]},
  "film": {"width": 8, "height": 6, "spp": 1},
  "lights": [{"type": "directional", "direction": [0, -1, 0], "illuminance_lux": 1000}],
  "media": [{"type": "vdb", "file": "c16.vdb", "density_scale": 0.02, "albedo": 0.9}]
}
JSON
libs=$(loaded_libs render "$work/cloud.json" -o "$work/cloud.exr" --no-preview -q)
echo "$libs" | grep -q "openvdb\|kasumi_vdb" && fail "the direct reader's grid loaded OpenVDB: $libs"
[ -s "$work/cloud.exr" ] || fail "the grid scene wrote no image"
libs=$(KASUMI_VDB_DIRECT=0 loaded_libs render "$work/cloud.json" -o "$work/cloud2.exr" --no-preview -q)
echo "$libs" | grep -q "kasumi_vdb" || fail "KASUMI_VDB_DIRECT=0 did not load the module: $libs"
[ -s "$work/cloud2.exr" ] || fail "the grid scene wrote no image through the module"

# A missing module: exit 1, the path tried and the variable to set; nothing written.
KASUMI_VDB_DIRECT=0 KASUMI_VDB_MODULE=/nonexistent/libkasumi_vdb.so expect_exit 1 \
  "OpenVDB module.*/nonexistent/libkasumi_vdb.so \(no such file\).*KASUMI_VDB_MODULE" -- \
  render "$work/cloud.json" -o "$work/missing.exr" --no-preview -q
[ -e "$work/missing.exr" ] && fail "a render without its module wrote an image"
KASUMI_VDB_MODULE=/nonexistent/libkasumi_vdb.so expect_exit 1 "/nonexistent/libkasumi_vdb.so" -- \
  make-cloud --res 8 --seed 1 -o "$work/none.vdb"
[ -e "$work/none.vdb" ] && fail "make-cloud without its module wrote a grid"
# A file that is not a loadable module.
echo "not a library" >"$work/fake.so"
KASUMI_VDB_DIRECT=0 KASUMI_VDB_MODULE="$work/fake.so" expect_exit 1 "OpenVDB module.*fake.so \(" -- \
  check "$work/cloud.json"

# exr_channels FILE: the channel names of an EXR header's chlist attribute, comma-separated.
exr_channels() { python3 "$(dirname "$0")/exr_header.py" "$1" channels; }
expect_exit 0 "" -- render "$work/fog.json" -o "$work/none.exr" --no-preview -q --aovs none
[ "$(exr_channels "$work/none.exr")" = "A,B,G,R" ] || fail "--aovs none: channels $(exr_channels "$work/none.exr")"
expect_exit 0 "" -- render "$work/fog.json" -o "$work/all.exr" --no-preview -q
[ "$(exr_channels "$work/all.exr")" = "A,B,G,R,albedo.B,albedo.G,albedo.R,depth.Z,surface.B,surface.G,surface.R,transmittance.B,transmittance.G,transmittance.R,volume.B,volume.G,volume.R" ] ||
  fail "default --aovs all: channels $(exr_channels "$work/all.exr")"
expect_exit 0 "" -- render "$work/fog.json" -o "$work/tv.exr" --no-preview -q --aovs transmittance,depth
[ "$(exr_channels "$work/tv.exr")" = "A,B,G,R,depth.Z,transmittance.B,transmittance.G,transmittance.R" ] ||
  fail "--aovs transmittance,depth: channels $(exr_channels "$work/tv.exr")"

# Only the subcommand named first is declared (apps/main.cpp); --help, an unknown or a missing
# name still see them all, and each one named first parses its own options.
subcommands="render plan check probe phase make-cloud sequence movie study"
expect_exit 0 "" -- --help
cp "$work/stdout" "$work/help"
for sub in $subcommands; do
  grep -q "^  $sub " "$work/help" || fail "--help does not list $sub"
  expect_exit 0 "" -- "$sub" --help
  grep -q "^Usage: .* $sub \[OPTIONS\]" "$work/stdout" || fail "$sub --help: $(head -c 200 "$work/stdout")"
done
expect_exit 2 "A subcommand is required" -- bogus
expect_exit 2 "A subcommand is required" --
expect_exit 2 "not expected: plan" -- render "$work/fog.json" plan --no-preview -q

finish "startup cli"
