#!/bin/sh
# Builds OpenVDB's vdb_render (the peer of bench/vdb_render_bench.py) from its one source file
# against the installed libopenvdb-dev, without any download: Debian 12 ships libopenvdb-dev
# 10.0.1 but no package with the tool.
#
#     bench/build_vdb_render.sh SRC_GIT_DIR OUT_DIR [REV]
#
# SRC_GIT_DIR: a (bare) git directory of github.com/AcademySoftwareFoundation/openvdb;
# REV: the tag or commit to take openvdb_cmd/vdb_render/main.cc from (default: v<installed
# version>, e.g. v10.0.1, so the source matches the library's headers). Writes
# OUT_DIR/vdb_render (EXR and PNG output enabled, -O3, no -march=native) and
# OUT_DIR/vdb_render.rev (the commit built). Needs libopenvdb-dev, libopenexr-dev, libimath-dev,
# libtbb-dev, libpng-dev, libboost-dev and a C++17 compiler.
set -eu
if [ $# -lt 2 ]; then
    echo "usage: $0 SRC_GIT_DIR OUT_DIR [REV]" >&2
    exit 2
fi
src=$1
out=$2
ver=$(sed -n 's/^#define OPENVDB_LIBRARY_VERSION_STRING "\(.*\)"/\1/p' /usr/include/openvdb/version.h)
if [ -z "$ver" ]; then
    ver=$(printf '%s.%s.%s' \
        "$(sed -n 's/^#define OPENVDB_LIBRARY_MAJOR_VERSION_NUMBER \([0-9]*\)/\1/p' /usr/include/openvdb/version.h)" \
        "$(sed -n 's/^#define OPENVDB_LIBRARY_MINOR_VERSION_NUMBER \([0-9]*\)/\1/p' /usr/include/openvdb/version.h)" \
        "$(sed -n 's/^#define OPENVDB_LIBRARY_PATCH_VERSION_NUMBER \([0-9]*\)/\1/p' /usr/include/openvdb/version.h)")
fi
rev=${3:-v$ver}
commit=$(git --git-dir="$src" rev-parse --verify "$rev^{commit}") || {
    echo "$0: $src has no revision $rev (installed OpenVDB: $ver)" >&2
    exit 3
}
mkdir -p "$out"
git --git-dir="$src" show "$commit:openvdb_cmd/vdb_render/main.cc" > "$out/vdb_render_main.cc"
${CXX:-g++} -std=c++17 -O3 -DNDEBUG -DOPENVDB_USE_EXR -DOPENVDB_USE_PNG \
    -I/usr/include/OpenEXR -I/usr/include/Imath \
    "$out/vdb_render_main.cc" -o "$out/vdb_render" \
    -lopenvdb -lOpenEXR -lIex -lImath -lpng -ltbb -lpthread
echo "$commit ($rev) openvdb_cmd/vdb_render/main.cc, installed OpenVDB $ver" > "$out/vdb_render.rev"
echo "built $out/vdb_render from $(cat "$out/vdb_render.rev")"
