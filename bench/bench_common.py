"""Shared pieces of the peer benchmarks (bench/vdb_render_bench.py, bench/povray_bench.py, ...).

- run(cmd): run a process, exit with its output on failure; returns (CompletedProcess, wall s,
  CPU s). CPU time is the child's user + system time (resource.getrusage(RUSAGE_CHILDREN)
  before and after, so call it from one thread only): on a shared, loaded machine it is steadier
  than wall time.
- render_kasumi(...): `kasumi render` with -v, parsed render statistics.
- compare(...): bench/vdb_image_compare's JSON (RMSE of an image against the mean of two
  reference halves, with the reference's own noise removed).
- loglog_time_at_error(points, error): time at a given error on a measured error-vs-time curve,
  interpolated linearly in (log time, log error).
- markdown_table(header, rows), write_csv(path, header, rows).
"""
import csv
import json
import math
import re
import resource
import subprocess
import sys
import time


def _children_cpu_s():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run(cmd, **kw):
    cpu0 = _children_cpu_s()
    t0 = time.perf_counter()
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, **kw)
    wall = time.perf_counter() - t0
    cpu = _children_cpu_s() - cpu0
    if p.returncode != 0:
        sys.exit("failed (%d): %s\n%s%s" % (p.returncode, " ".join(cmd), p.stdout, p.stderr))
    return p, wall, cpu


_STAT_RE = re.compile(r"\s+(time|density lookups|lookups/s/core|camera rays/s|all rays/s|"
                      r"transmittance rays|free flights|threads)\s+([0-9.eE+-]+)")


def render_kasumi(kasumi, scene_path, out, spp, seed, threads, extra=()):
    """Renders SCENE_PATH to OUT; returns (render time s from -v, wall s, CPU s, stats dict)."""
    cmd = [kasumi, "render", scene_path, "-o", out, "--no-preview", "--spp", str(spp),
           "--seed", str(seed), "--threads", str(threads), "-v"] + list(extra)
    p, wall, cpu = run(cmd)
    stats = {}
    for line in p.stderr.splitlines():
        m = _STAT_RE.match(line)
        if m:
            stats[m.group(1)] = float(m.group(2))
    return stats.get("time", wall), wall, cpu, stats


def compare(compare_tool, ref_a, ref_b, image, scale=None):
    cmd = [compare_tool, ref_a, ref_b, image] + ([] if scale is None else ["%.9g" % scale])
    p, _, _ = run(cmd)
    return json.loads(p.stdout)


def loglog_time_at_error(points, error):
    """points: [(time, error)] of one renderer's quality sweep. Returns the time at ERROR,
    interpolated linearly in log-log between the two neighbouring measured errors (after
    taking the lower convex hull in time: a slower point with a larger error is dropped), or
    None when ERROR lies outside the measured range."""
    pts = sorted((t, e) for t, e in points if t > 0 and e > 0)
    front = []
    for t, e in pts:  # Pareto front: error strictly falling as time grows
        if not front or e < front[-1][1]:
            front.append((t, e))
    for (t0, e0), (t1, e1) in zip(front, front[1:]):
        if e1 <= error <= e0:
            if e0 == e1:
                return t0
            f = (math.log(error) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(t0) + f * (math.log(t1) - math.log(t0)))
    if front and abs(front[0][1] - error) <= 1e-12 * error:
        return front[0][0]
    return None


def markdown_table(header, rows):
    out = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for r in rows:
        out.append("| " + " | ".join(str(c) for c in r) + " |")
    return "\n".join(out)


def write_csv(path, header, rows):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        w.writerows(rows)
