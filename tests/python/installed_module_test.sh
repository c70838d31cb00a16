#!/usr/bin/env bash
# The installed Python package works without the build tree: `cmake --install --component
# python` into a throw-away DESTDIR, then a render that needs both dlopen'ed modules (OpenVDB,
# forced with KASUMI_VDB_DIRECT=0; OpenColorIO, for the PNG preview's view) must map them from
# the installed package, not from the build tree the binaries remember.
# usage: installed_module_test.sh BUILD_DIR PYTHON SOURCE_DIR
set -euo pipefail
build="$1" python="$2" src="$3"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
DESTDIR="$tmp/root" cmake --install "$build" --component python >/dev/null
init="$(find "$tmp/root" -path '*/kasumi/__init__.py' | head -1)"
[ -n "$init" ] || { echo "FAIL: no kasumi/__init__.py installed"; exit 1; }
package="$(dirname "$init")"
for module in libkasumi_vdb.so libkasumi_ocio.so libkasumi_exr.so; do
  [ -f "$package/$module" ] || { echo "FAIL: $module not installed beside the extension"; exit 1; }
done
cd "$tmp"
KASUMI_VDB_DIRECT=0 PYTHONPATH="$(dirname "$package")" PYTHONDONTWRITEBYTECODE=1 \
  "$python" - "$package" "$src/data/scenes/cloud.json" <<'PY'
import os, sys
package, scene_path = sys.argv[1], sys.argv[2]
import kasumi
assert os.path.dirname(os.path.realpath(kasumi.__file__)) == os.path.realpath(package), kasumi.__file__
scene = kasumi.Scene.load(scene_path)
scene.set("/film/width", 16)
scene.set("/film/height", 9)
result = scene.render(spp=1, threads=1)
result.write_png("preview.png")
assert os.path.getsize("preview.png") > 0
mapped = {}
with open("/proc/self/maps") as maps:
    for line in maps:
        path = line.split()[-1] if len(line.split()) >= 6 else ""
        for module in ("libkasumi_vdb.so", "libkasumi_ocio.so"):
            if path.endswith("/" + module):
                mapped[module] = os.path.dirname(os.path.realpath(path))
for module in ("libkasumi_vdb.so", "libkasumi_ocio.so"):
    assert module in mapped, module + " was never loaded"
    assert mapped[module] == os.path.realpath(package), module + " loaded from " + mapped[module]
print("installed package loads its modules from", package)
PY
