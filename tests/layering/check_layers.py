#!/usr/bin/env python3
"""The folder layering of docs/architecture.md: a file includes only its own folder and folders of
lower layers. Folders of the same layer (phase and lights, volume and surface, study and
sequence) do not include each other.

usage: check_layers.py SOURCE_DIR      exit 0 when every #include "folder/file.h" points down
       check_layers.py --self-test     plants an upward and a sideways include in a scratch tree
                                       and requires both to be reported (exit 0 if they are)
"""
import os
import re
import sys
import tempfile

# Bottom-up; a folder may include folders of strictly lower rank and itself. A sub-folder
# (volume/grid) is a library of its own with its own rank.
LAYERS = [
    ["core"],
    ["phase", "lights"],
    ["volume/grid"],
    ["volume", "surface"],
    ["sky"],
    ["scene"],
    ["render"],
    ["gi/photon"],
    ["gi"],
    ["study", "sequence"],
    ["apps", "python"],
]
RANK = {folder: rank for rank, folders in enumerate(LAYERS) for folder in folders}

# Upward includes tolerated while they are being removed; empty: none is. The check fails on any
# include not listed here and on a listed one that is gone (so the list only shrinks).
ALLOWED = set()

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def folder_of(path):
    """The deepest layered folder holding `path` (relative, '/'-separated), or None."""
    parts = path.split("/")[:-1]
    for n in range(len(parts), 0, -1):
        folder = "/".join(parts[:n])
        if folder in RANK:
            return folder
    return None


def violations(root):
    found = []
    for top in sorted({f.split("/")[0] for f in RANK}):
        for dirpath, _, files in os.walk(os.path.join(root, top)):
            for name in sorted(files):
                if not name.endswith((".h", ".cpp")):
                    continue
                path = os.path.relpath(os.path.join(dirpath, name), root).replace(os.sep, "/")
                here = folder_of(path)
                if here is None:
                    continue
                text = open(os.path.join(root, path), encoding="utf-8", errors="replace").read()
                for included in INCLUDE.findall(text):
                    there = folder_of(included)
                    if there is None or there == here:
                        continue
                    if RANK[there] >= RANK[here]:
                        found.append((path, included, here, there))
    return found


def check(root):
    found = violations(root)
    bad = [v for v in found if (v[0], v[1]) not in ALLOWED]
    stale = ALLOWED - {(v[0], v[1]) for v in found}
    for path, included, here, there in bad:
        kind = "sideways" if RANK[there] == RANK[here] else "upward"
        print("%s: includes %s: %s include (%s is layer %d, %s is layer %d)"
              % (path, included, kind, here, RANK[here], there, RANK[there]))
    for path, included in sorted(stale):
        print("%s: no longer includes %s: remove it from ALLOWED" % (path, included))
    print("layering: %d upward or sideways includes (%d allowed), %d stale allowances"
          % (len(found), len(found) - len(bad), len(stale)))
    return 1 if bad or stale else 0


def self_test():
    with tempfile.TemporaryDirectory() as root:
        for path, text in {
            "core/math.h": "#pragma once\n",
            "render/renderer.h": '#include "core/math.h"\n',
            "core/planted.h": '#include "render/renderer.h"\n',
            "phase/planted.cpp": '#include "lights/light.h"\n',
            "lights/light.h": '#include "core/math.h"\n',
        }.items():
            os.makedirs(os.path.join(root, os.path.dirname(path)), exist_ok=True)
            open(os.path.join(root, path), "w").write(text)
        found = {(v[0], v[1]) for v in violations(root)}
        want = {("core/planted.h", "render/renderer.h"), ("phase/planted.cpp", "lights/light.h")}
        if found != want:
            print("self-test: reported %s, planted %s" % (sorted(found), sorted(want)))
            return 1
        print("self-test: both planted includes reported")
        return 0


if __name__ == "__main__":
    if sys.argv[1:] == ["--self-test"]:
        sys.exit(self_test())
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    sys.exit(check(sys.argv[1]))
