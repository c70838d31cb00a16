#!/usr/bin/python3
"""Benchmark (not a test): Scene.render() from Python against `kasumi render` on the same scene,
and the time of `import kasumi`.

    PYTHONPATH=build/release/python bench/python_render.py [--cli build/release/apps/kasumi]

Both sides render the same film with the same seed, spp and threads; their render times
(render_image alone: the EXR's kasumi/render_seconds for the CLI, RenderResult.seconds for the
module) are taken in alternating runs so load drifts hit both, and compared by their medians.
The wall time of a whole call (load, build, render; the CLI's process start and EXR write too)
is printed beside them. Target (issue 21): the module's render within 3 % of the CLI's.
"""
import argparse
import os
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time

import kasumi

ROOT = pathlib.Path(__file__).resolve().parents[1]


def import_seconds(runs=7):
    code = "import time; s = time.perf_counter(); import kasumi; print(time.perf_counter() - s)"
    return statistics.median(
        float(subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                             check=True, env=os.environ).stdout) for _ in range(runs))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--cli", default=str(ROOT / "build" / "release" / "apps" / "kasumi"))
    parser.add_argument("--scene", default=str(ROOT / "data" / "scenes" / "fog_height.json"))
    parser.add_argument("--res", default="320x180")
    parser.add_argument("--spp", type=int, default=16)
    parser.add_argument("--threads", type=int, default=1)
    parser.add_argument("--runs", type=int, default=7, help="runs of each side")
    args = parser.parse_args()

    width, height = (int(v) for v in args.res.split("x"))
    scene = kasumi.Scene.load(args.scene)
    scene.set("/film/width", width)
    scene.set("/film/height", height)
    cli_render, cli_wall, py_render, py_wall = [], [], [], []
    with tempfile.TemporaryDirectory() as tmp:
        exr = os.path.join(tmp, "cli.exr")
        for _ in range(args.runs):
            start = time.perf_counter()
            subprocess.run([args.cli, "render", args.scene, "--res", args.res, "--spp",
                            str(args.spp), "--seed", "1", "--threads", str(args.threads), "-o",
                            exr, "--no-preview", "-q"], check=True)
            cli_wall.append(time.perf_counter() - start)
            cli_render.append(float(kasumi.read_exr(exr)[1]["render_seconds"]))
            start = time.perf_counter()
            result = scene.render(spp=args.spp, seed=1, threads=args.threads)
            py_wall.append(time.perf_counter() - start)
            py_render.append(result.seconds)
            del result

    def ms(values):
        return f"{1e3 * statistics.median(values):9.1f} (min {1e3 * min(values):9.1f})"

    print(f"{pathlib.Path(args.scene).name} {args.res}, {args.spp} spp, {args.threads} thread(s), "
          f"{args.runs} alternating runs each, load average {os.getloadavg()[0]:.1f}")
    print(f"{'':22s} {'render ms: median':>28s} {'call wall ms: median':>28s}")
    print(f"{'kasumi render (CLI)':22s} {ms(cli_render)} {ms(cli_wall)}")
    print(f"{'Scene.render (Python)':22s} {ms(py_render)} {ms(py_wall)}")
    ratio = statistics.median(py_render) / statistics.median(cli_render)
    print(f"render time python / cli: {ratio:.3f} (target <= 1.03)")
    print(f"import kasumi: {1e3 * import_seconds():.1f} ms median of 7 (target < 200 ms)")


if __name__ == "__main__":
    main()
