#!/usr/bin/python3
"""Benchmark (not a test): kasumi.phase eval on 10^6 angles from Python against the same C++
loop (eval_precise over a std::vector inside the extension), and the import time.

    PYTHONPATH=build/release/python bench/python_phase_eval.py

Targets (issue 21): Python within 1.5x of the C++ loop; `import kasumi` under 0.2 s.
Min and median of repeated runs; the machine's load is printed because it moves both.
"""
import os
import statistics
import subprocess
import sys
import time

import numpy as np

import kasumi

N = 1_000_000
REPEATS = 15


def seconds(f):
    """(min, median) over REPEATS runs of f; f returns its own time when it measures itself."""
    times = []
    for _ in range(REPEATS):
        start = time.perf_counter()
        inner = f()
        times.append(inner if isinstance(inner, float) else time.perf_counter() - start)
    return min(times), statistics.median(times)


def import_seconds():
    code = "import time; s = time.perf_counter(); import kasumi; print(time.perf_counter() - s)"
    runs = [float(subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                                 check=True, env=os.environ).stdout) for _ in range(7)]
    return statistics.median(runs)


def main():
    print(f"load average {os.getloadavg()[0]:.1f}, {N} angles, {REPEATS} runs each")
    mu = np.random.default_rng(1).uniform(-1.0, 1.0, N)
    print("ms as min / median; 'fresh': p.eval(mu) allocating its result, 'out=': writing into "
          "a reused array; ratio = python min / c++ min")
    print(f"{'model':32s} {'fresh':>13s} {'out=':>13s} {'c++ loop':>13s} {'ratio':>6s} {'out=':>6s}")
    buffer = np.empty_like(mu)
    for d in [{"model": "hg", "g": 0.8}, {"model": "draine", "g": 0.5, "alpha": 0.8},
              {"model": "rayleigh"}, {"model": "mie", "m": 1.33, "x": 30.0}]:
        p = kasumi.phase.make(d)
        fresh = seconds(lambda: p.eval(mu))
        out = seconds(lambda: p.eval(mu, out=buffer))
        cpp = seconds(lambda: kasumi.phase._cpp_eval_seconds(p, mu))
        name = ", ".join(f"{k}={v}" for k, v in d.items())
        cells = " ".join(f"{a * 1e3:6.2f}/{b * 1e3:6.2f}" for a, b in (fresh, out, cpp))
        print(f"{name:32s} {cells} {fresh[0] / cpp[0]:6.2f} {out[0] / cpp[0]:6.2f}")
    print(f"import kasumi: {import_seconds() * 1e3:.0f} ms (median of 7 fresh interpreters)")


if __name__ == "__main__":
    main()
