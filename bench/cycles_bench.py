#!/usr/bin/python3
"""Peer benchmark: kasumi against Blender Cycles on the same VDB cloud, Principled Volume and
sun, single and multiple scattering, compared at equal error (each renderer against its own
converged reference).

    bench/cycles_bench.py [--build build/release] [--scenes cumulus,wdas] [--image 256]
                          [--runs 5] [--threads 2] [--quick]

--quick trades precision for time (about a quarter of the full run's time): 64x64 images, 3
timed rounds, 64-sample Cycles and 256-spp kasumi references, Cycles 4 and 16 samples at step
rate 1 only with the error target at 16 samples in both modes, and a kasumi spp ladder in steps
of 4x (1, 4, 16, 64, 256). Options given explicitly still win.

Skips Cycles (exit 0, with a message) when `blender` is not on PATH.

Matching (the Blender side is bench/cycles_scene.py, which states each setting): the same VDB
(kasumi's `make-cloud` cumulus, and the WDAS cloud from ../shared/data when present), the
medium sigma_t = density_scale * d, sigma_s = albedo * sigma_t, Henyey-Greenstein g (Principled
Volume: Density, Color, black Absorption Color, Anisotropy), a white delta sun of the same
irradiance (Cycles' sun strength is scene-linear irradiance, kasumi's illuminance_lux is the
same number), the same pinhole camera (kasumi +Y up mapped to Blender +Z up by a rotation of
+90 degrees about X), pixel-centre sampling on both sides (kasumi film.jitter false, Cycles box
filter of 0.01 pixel), black background, no surfaces. Single scattering: kasumi integrator
"single", Cycles volume_bounces 0. Multiple: kasumi "multiple" with max_depth 33 scattering
events, Cycles volume_bounces 32 (direct light at the first event plus 32 bounces = 33 events).

Error: each renderer's image against its own converged reference, two independent halves
(different seeds) whose own noise is measured and removed (bench/vdb_image_compare.cpp); the
figure is that corrected RMSE over the reference's mean (relative RMSE). kasumi's reference is
its unbiased residual-ratio tracker; Cycles' is many samples at a small volume step rate (its
heterogeneous volumes are ray marched: the step is biased, its error is noise + step bias). The
two converged references are compared too: relative RMSE after one global scale (the ratio of
their means), which says how well the two renderers compute the same picture.

Equal error: each renderer sweeps its quality settings (kasumi: samples per pixel for each
configuration, or the step at 1 spp for the march; Cycles: samples x volume step rate); the
error target is Cycles' own error at its default step rate 1 and --target-spp-single or
--target-spp-multiple samples. Each renderer's time at that error is read off its
error-vs-time curve, interpolated linearly in log-log between the two measured points that
bracket it (bench_common.loglog_time_at_error). Those bracketing points are then re-timed
in --runs alternating rounds (Cycles, kasumi, Cycles, ...) and the medians used. Times: "render"
is each program's own render time (kasumi -v `time`; Cycles: Blender's "Time:" from the first
sample to "Finished", i.e. without scene synchronisation), "call" adds Cycles' scene
synchronisation (grid loading, volume mesh, BVH), "process" is the whole process (kasumi: the
wall time of `kasumi render`; Cycles: Blender's start-up, measured when the long-lived Blender
process starts, plus the render call). CPU time is user + system of all threads.
"""
import argparse
import json
import math
import os
import re
import shutil
import statistics
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_common import (compare, loglog_time_at_error, markdown_table,  # noqa: E402
                          render_kasumi, run, write_csv)

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
WDAS = os.path.join(os.path.dirname(ROOT), "shared", "data", "wdas_cloud_sixteenth.vdb")

# Scenes in kasumi's frame (+Y up, metres). The cumulus's medium and sun are those of
# data/scenes/cloud.json (backlit, HG g = 0.8: a silver lining); the WDAS cloud's those of
# data/scenes/cloud_wdas.json. Cameras framed for a square image.
SCENES = {
    "cumulus": {"eye": [0.0, 480.0, 1500.0], "target": [8.0, 418.0, 0.0], "up": [0, 1, 0],
                "fov_deg": 30.0, "sun_toward": [-0.25, 0.45, -0.86], "irradiance": 10.0,
                "density_scale": 0.04, "albedo": 0.99, "g": 0.8},
    "wdas": {"eye": [-150.0, 0.0, 650.0], "target": [0.0, 45.0, 0.0], "up": [0, 1, 0],
             "fov_deg": 40.0, "sun_toward": [-0.3, 0.45, 0.84], "irradiance": 10.0,
             "density_scale": 0.08, "albedo": 0.99, "g": 0.8},
}

MULTIPLE_EVENTS = 33  # kasumi max_depth; Cycles volume_bounces = MULTIPLE_EVENTS - 1

# kasumi configurations per mode (name, render.volume settings); the first is the unbiased
# reference estimator.
KASUMI_CONFIGS = {
    "single": [
        ("residual-ratio", {"estimator": "residual-ratio"}),
        # The classic march (biased, O(step^2)): every node adds its in-scattered light with a
        # marched shadow ray, so one sample per pixel already has little noise.
        # Swept over the step at 1 spp (coarse to fine) instead of over spp.
        ("march, 1 spp", {"estimator": "march"}),
        # The light cache (docs/volumes.md) is left out here: on this backlit cloud (HG 0.8,
        # silver lining) its bias alone is a relative RMSE of 0.5 (the image 11% too dark),
        # above every error target.
    ],
    "multiple": [
        ("residual-ratio", {"estimator": "residual-ratio"}),
        ("residual-ratio + light cache", {"estimator": "residual-ratio", "light_cache": True}),
        # Russian roulette on next-event estimation (docs/volumes.md; unbiased): the WDAS
        # cloud is lit from behind the camera, so most events backscatter (HG 0.8) and skip
        # their shadow walk.
        ("residual-ratio + NEE roulette", {"estimator": "residual-ratio", "nee_roulette": True}),
        # What render.quality's levels choose for clouds (scene/quality.cpp; unbiased): the
        # shadow rays' roulette on the light cache's contribution and the camera segment's T
        # from the first free flight.
        ("residual-ratio + shadow roulette + first flight",
         {"estimator": "residual-ratio", "shadow_roulette": 0.05,
          "camera_transmittance": "first_flight"}),
    ],
}


def normalized(v):
    n = math.sqrt(sum(c * c for c in v))
    return [c / n for c in v]


def kasumi_scene(sc, vdb, image, mode, volume):
    vol = dict(volume, integrator=mode)
    if mode == "multiple":
        vol["max_depth"] = MULTIPLE_EVENTS
    return {
        "camera": {"position": sc["eye"], "look_at": sc["target"], "up": sc["up"],
                   "fov_deg": sc["fov_deg"]},
        "film": {"width": image, "height": image, "spp": 1, "jitter": False},
        "background": [0, 0, 0],
        "lights": [{"name": "sun", "type": "directional",
                    "direction": [-c for c in normalized(sc["sun_toward"])],
                    "illuminance_lux": sc["irradiance"], "color": [1, 1, 1]}],
        "media": [{"name": "cloud", "type": "vdb", "file": os.path.abspath(vdb),
                   "grid": "density", "density_scale": sc["density_scale"],
                   "albedo": sc["albedo"], "phase": {"model": "hg", "g": sc["g"]}}],
        "render": {"seed": 1, "volume": vol},
    }


def proc_cpu_s(pid):
    """User + system CPU seconds of a running process, all threads (/proc/PID/stat)."""
    with open("/proc/%d/stat" % pid) as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


_TIME_RE = re.compile(r"\| Time:([0-9:.]+) \|")


def blender_seconds(stamp):
    s = 0.0
    for part in stamp.split(":"):
        s = s * 60.0 + float(part)
    return s


class Cycles:
    """A long-lived Blender process running bench/cycles_scene.py (its start-up is paid once
    and measured here; it idles on stdin while kasumi runs)."""

    def __init__(self, blender, log_path):
        self.log = open(log_path, "a")
        t0 = time.perf_counter()
        self.p = subprocess.Popen(
            [blender, "-b", "--factory-startup", "-noaudio", "--python",
             os.path.join(ROOT, "bench", "cycles_scene.py")],
            stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=self.log, text=True,
            bufsize=1)
        self._read()
        self.startup_wall_s = time.perf_counter() - t0
        self.startup_cpu_s = proc_cpu_s(self.p.pid)

    def _read(self):
        lines = []
        for line in self.p.stdout:
            if line.startswith("CYCLES_BENCH "):
                obj = json.loads(line[len("CYCLES_BENCH "):])
                if obj.get("ok") is False:
                    sys.exit("cycles_scene.py: %s (log: %s)" % (obj.get("error"), self.log.name))
                return obj, lines
            self.log.write(line)
            lines.append(line)
        sys.exit("blender exited (log: %s)" % self.log.name)

    def call(self, obj):
        self.p.stdin.write(json.dumps(obj) + "\n")
        self.p.stdin.flush()
        return self._read()

    def render(self, samples, step_rate, seed, out):
        obj, lines = self.call({"cmd": "render", "samples": samples, "step_rate": step_rate,
                                "seed": seed, "out": out})
        sync = finished = None
        for line in lines:
            m = _TIME_RE.search(line)
            if not m:
                continue
            if sync is None and re.search(r"\| Sample 0/", line):
                sync = blender_seconds(m.group(1))
            if line.rstrip().endswith("| Finished"):
                finished = blender_seconds(m.group(1))
        if sync is None or finished is None:
            sys.exit("no Cycles timings in Blender's log (%s)" % self.log.name)
        return {"render_s": finished - sync, "sync_s": sync, "call_s": obj["render_call_s"],
                "cpu_s": obj["cpu_s"]}

    def close(self):
        self.call({"cmd": "quit"})
        self.p.wait()
        self.log.close()


def rel(e):
    return e["rmse_corrected"] / e["ref_mean"]


def fmt_s(t):
    return "%.3g s" % t


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build", "release"))
    ap.add_argument("--scenes", default="cumulus,wdas",
                    help="cumulus (make-cloud) and/or wdas (skipped if the file is absent)")
    ap.add_argument("--modes", default="single,multiple")
    ap.add_argument("--res", type=int, default=128, help="make-cloud resolution (voxels/edge)")
    ap.add_argument("--image", type=int, default=None, help="image edge in pixels")
    ap.add_argument("--runs", type=int, default=None, help="alternating timed rounds")
    ap.add_argument("--threads", type=int, default=2, help="threads, both renderers")
    ap.add_argument("--kasumi-ref-spp", type=int, default=None, help="two halves")
    ap.add_argument("--cycles-ref-spp", type=int, default=None, help="two halves")
    ap.add_argument("--cycles-ref-step-rate", type=float, default=0.5)
    ap.add_argument("--cycles-spp", default=None, help="Cycles sample ladder")
    ap.add_argument("--step-rates", default=None, help="Cycles volume step rates swept")
    ap.add_argument("--target-spp-single", type=int, default=None,
                    help="the error target is Cycles' error at this many samples, step rate 1")
    ap.add_argument("--target-spp-multiple", type=int, default=None)
    ap.add_argument("--march-steps", default="8,4,2,1",
                    help="kasumi march steps (voxels) swept at 1 spp, coarse to fine")
    ap.add_argument("--kasumi-spp", default=None,
                    help="kasumi spp ladder (stops once 0.7 x the target is reached)")
    ap.add_argument("--out", default=None,
                    help="default build/cycles_bench, build/cycles_bench_quick with --quick")
    ap.add_argument("--quick", action="store_true",
                    help="smaller images, fewer rounds and sweep points (see the docstring)")
    args = ap.parse_args()
    # Defaults of the full run and of --quick; an option given explicitly wins over both.
    defaults = {"image": (128, 64), "runs": (5, 3), "kasumi_ref_spp": (1024, 256),
                "cycles_ref_spp": (128, 64), "cycles_spp": ("4,16,64", "4,16"),
                "step_rates": ("1,2", "1"), "target_spp_single": (64, 16),
                "target_spp_multiple": (16, 16),
                "kasumi_spp": ("1,2,4,8,16,32,64,128,256,512", "1,4,16,64,256")}
    for name, (full, quick) in defaults.items():
        if getattr(args, name) is None:
            setattr(args, name, quick if args.quick else full)
    if args.out is None:  # the quick run's smaller images must not reuse the full run's files
        args.out = os.path.join(ROOT, "build",
                                "cycles_bench_quick" if args.quick else "cycles_bench")
    blender = shutil.which("blender")
    if blender is None:
        print("cycles_bench: `blender` is not installed (Debian: apt-get install blender); "
              "skipping the Cycles comparison")
        return 0
    kasumi = os.path.join(args.build, "apps", "kasumi")
    tool = os.path.join(args.build, "bench", "vdb_image_compare")
    for path in (kasumi, tool):
        if not os.path.exists(path):
            sys.exit("missing %s: build the targets kasumi and vdb_image_compare" % path)
    os.makedirs(args.out, exist_ok=True)
    t_start = time.perf_counter()
    print("load average at start: %.2f %.2f %.2f; %d cores; %d threads per renderer"
          % (os.getloadavg() + (os.cpu_count(), args.threads)))

    scenes = []
    for name in args.scenes.split(","):
        if name == "cumulus":
            vdb = os.path.join(args.out, "cumulus_%d.vdb" % args.res)
            if not os.path.exists(vdb):
                run([kasumi, "make-cloud", "--res", str(args.res), "--seed", "7", "-o", vdb])
            scenes.append(("cumulus %d³" % args.res, SCENES["cumulus"], vdb))
        elif name == "wdas":
            if os.path.exists(WDAS):
                scenes.append(("WDAS sixteenth", SCENES["wdas"], WDAS))
            else:
                print("WDAS cloud not found at %s: skipped" % WDAS)
        else:
            sys.exit("unknown scene " + name)

    cycles = Cycles(blender, os.path.join(args.out, "blender.log"))
    startups = [(cycles.startup_wall_s, cycles.startup_cpu_s)]
    print("Blender start-up: %.2f s wall, %.2f s CPU" % startups[0])
    results = []
    for label, sc, vdb in scenes:
        tag = label.split()[0].lower()
        for mode in args.modes.split(","):
            key = "%s_%s" % (tag, mode)
            base = os.path.join(args.out, key)
            cycles.call(dict(cmd="setup", vdb=os.path.abspath(vdb), width=args.image,
                             height=args.image, threads=args.threads,
                             volume_bounces=0 if mode == "single" else MULTIPLE_EVENTS - 1,
                             **sc))
            # Each configuration's quality ladder, cheapest first: (label, spp, scene file).
            configs = []
            for i, (cname, volume) in enumerate(KASUMI_CONFIGS[mode]):
                variants = []
                if volume["estimator"] == "march":
                    for step in (float(v) for v in args.march_steps.split(",")):
                        path = "%s_k%d_s%g.json" % (base, i, step)
                        variants.append(("step %g voxels" % step, 1, path,
                                         dict(volume, step_voxels=step)))
                else:
                    path = "%s_k%d.json" % (base, i)
                    variants = [("%d spp" % spp, spp, path, volume)
                                for spp in (int(v) for v in args.kasumi_spp.split(","))]
                for _, _, path, vol in variants:
                    with open(path, "w") as f:
                        json.dump(kasumi_scene(sc, vdb, args.image, mode, vol), f, indent=1)
                configs.append((cname, [v[:3] for v in variants]))

            # References: two independent halves each.
            kref, cref = [], []
            for k, seed in enumerate((1001, 2002)):
                out = "%s_kref%d_%c.exr" % (base, args.kasumi_ref_spp, "ab"[k])
                if not os.path.exists(out):
                    t, _, cpu, _ = render_kasumi(kasumi, configs[0][1][0][2], out,
                                                 args.kasumi_ref_spp // 2, seed, args.threads)
                    print("%s: kasumi reference half %d: %d spp, %.1f s (%.1f s CPU)"
                          % (key, k, args.kasumi_ref_spp // 2, t, cpu))
                kref.append(out)
                out = "%s_cref%d_r%g_%c.exr" % (base, args.cycles_ref_spp,
                                                  args.cycles_ref_step_rate, "ab"[k])
                if not os.path.exists(out):
                    c = cycles.render(args.cycles_ref_spp // 2, args.cycles_ref_step_rate,
                                      seed, out)
                    print("%s: Cycles reference half %d: %d samples, step rate %g, %.1f s "
                          "(%.1f s CPU)" % (key, k, args.cycles_ref_spp // 2,
                                            args.cycles_ref_step_rate, c["call_s"], c["cpu_s"]))
                cref.append(out)
            kself = compare(tool, kref[0], kref[1], kref[0])
            cself = compare(tool, cref[0], cref[1], cref[0])
            scale = kself["ref_mean"] / cself["ref_mean"]
            cross = compare(tool, kref[0], kref[1], cref[0], scale)
            # rmse² = residual² + kasumi reference noise² + scale² Var(one Cycles half), and
            # Var(one half) = E[(A - B)²] / 2 = 2 ref_noise_rmse².
            residual2 = (cross["rmse"] ** 2 - kself["ref_noise_rmse"] ** 2
                         - scale ** 2 * 2.0 * cself["ref_noise_rmse"] ** 2)
            agreement = math.sqrt(max(residual2, 0.0)) / kself["ref_mean"]
            print("%s: references: mean kasumi %.5g, Cycles %.5g (scale %.4f); relative RMSE "
                  "after the scale %.4f (noise removed; kasumi ref noise %.4f, Cycles %.4f)"
                  % (key, kself["ref_mean"], cself["ref_mean"], scale, agreement,
                     kself["ref_noise_rmse"] / kself["ref_mean"],
                     cself["ref_noise_rmse"] / cself["ref_mean"]))

            # Quality sweeps (one run per point).
            rows = []
            cyc_points = {}
            for rate in (float(r) for r in args.step_rates.split(",")):
                for spp in (int(s) for s in args.cycles_spp.split(",")):
                    out = "%s_c_r%g_%d.exr" % (base, rate, spp)
                    c = cycles.render(spp, rate, 7, out)
                    e = rel(compare(tool, cref[0], cref[1], out))
                    cyc_points[(rate, spp)] = (c, e, out)
                    rows.append([key, "Cycles", "step rate %g" % rate, spp, c["render_s"],
                                 c["call_s"], c["cpu_s"], e])
                    print("%s: Cycles step rate %g, %4d samples: render %.3f s (call %.3f s, "
                          "CPU %.3f s), relative RMSE %.4f"
                          % (key, rate, spp, c["render_s"], c["call_s"], c["cpu_s"], e))
            target_spp = args.target_spp_single if mode == "single" else args.target_spp_multiple
            if (1.0, target_spp) not in cyc_points:
                sys.exit("--target-spp-* must be in --cycles-spp and 1 in --step-rates")
            target = cyc_points[(1.0, target_spp)][1]
            kas_points = []
            for ci, (cname, variants) in enumerate(configs):
                pts = []
                for vi, (vlabel, spp, scene) in enumerate(variants):
                    out = "%s_k%d_v%d.exr" % (base, ci, vi)
                    t, wall, cpu, _ = render_kasumi(kasumi, scene, out, spp, 7, args.threads)
                    e = rel(compare(tool, kref[0], kref[1], out))
                    pts.append((vi, t, wall, cpu, e))
                    rows.append([key, "kasumi", "%s, %s" % (cname, vlabel), spp, t, wall, cpu, e])
                    print("%s: kasumi [%s, %s]: render %.3f s (process %.3f s, CPU %.3f s),"
                          " relative RMSE %.4f" % (key, cname, vlabel, t, wall, cpu, e))
                    if e < 0.7 * target:
                        break
                kas_points.append(pts)
            write_csv(base + "_sweep.csv", ["case", "renderer", "setting", "spp", "render_s",
                                            "call_or_process_s", "cpu_s", "relative_rmse"], rows)

            # Cycles' best time at the target error over all step rates (CPU time curve).
            def cyc_bracket():
                curve = [(c["cpu_s"], e, k) for k, (c, e, _) in cyc_points.items()]
                front = sorted(curve)
                best = None
                for t0, e0, k0 in front:
                    for t1, e1, k1 in front:
                        if t1 > t0 and e1 <= target <= e0 and e1 < e0:
                            t = loglog_time_at_error([(t0, e0), (t1, e1)], target)
                            if t is not None and (best is None or t < best[0]):
                                best = (t, k0, k1)
                    if e0 == target and (best is None or t0 < best[0]):
                        best = (t0, k0, k0)
                return best

            _, c_lo, c_hi = cyc_bracket()

            def kas_bracket(pts):
                # The cheapest point already at or below the target: its time bounds kasumi's
                # time at the target from above (the ratio is then an upper bound).
                if pts and pts[0][4] <= target:
                    return (pts[0][0],)
                for (s0, _, _, c0, e0), (s1, _, _, c1, e1) in zip(pts, pts[1:]):
                    if e1 <= target <= e0:
                        return s0, s1
                return None

            brackets = [kas_bracket(p) for p in kas_points]

            # Alternating timed rounds: Cycles' bracketing points, then every kasumi
            # configuration's bracketing spp, repeated.
            ctimes = {k: [] for k in {c_lo, c_hi}}
            ktimes = [{vi: [] for vi in (b or ())} for b in brackets]
            for _ in range(args.runs):
                for k in sorted(ctimes):
                    ctimes[k].append(cycles.render(k[1], k[0], 7,
                                                   cyc_points[k][2].replace(".exr", "_t.exr")))
                for ci, (cname, variants) in enumerate(configs):
                    for vi in sorted(ktimes[ci]):
                        _, spp, scene = variants[vi]
                        out = "%s_k%d_v%d_t.exr" % (base, ci, vi)
                        t, wall, cpu, _ = render_kasumi(kasumi, scene, out, spp, 7, args.threads)
                        ktimes[ci][vi].append({"render_s": t, "process_s": wall, "cpu_s": cpu})

            def med(samples, field):
                return statistics.median(s[field] for s in samples)

            def cyc_at(field):
                pts = [(med(ctimes[k], field), cyc_points[k][1]) for k in sorted(set(ctimes))]
                return loglog_time_at_error(pts, target) if len(pts) == 2 else pts[0][0]

            startup_wall = statistics.median(s[0] for s in startups)
            startup_cpu = statistics.median(s[1] for s in startups)
            c_render, c_call, c_cpu = cyc_at("render_s"), cyc_at("call_s"), cyc_at("cpu_s")
            c_process = c_call + startup_wall
            c_process_cpu = c_cpu + startup_cpu
            entry = {"case": key, "scene": label, "mode": mode, "image": args.image,
                     "threads": args.threads, "target_relative_rmse": target,
                     "target": "Cycles step rate 1, %d samples" % target_spp,
                     "reference_scale_kasumi_over_cycles": scale,
                     "reference_relative_rmse_after_scale": agreement,
                     "cycles": {"brackets": [list(c_lo), list(c_hi)], "render_s": c_render,
                                "call_s": c_call, "process_s": c_process, "cpu_s": c_cpu,
                                "process_cpu_s": c_process_cpu,
                                "runs": {"%g/%d" % k: v for k, v in ctimes.items()}},
                     "kasumi": []}
            for ci, (cname, _) in enumerate(configs):
                if brackets[ci] is None:
                    entry["kasumi"].append({"config": cname, "reached": False})
                    print("%s: kasumi [%s] did not bracket the target %.4f"
                          % (key, cname, target))
                    continue
                errs = {p[0]: p[4] for p in kas_points[ci]}

                def kas_at(field):
                    if len(brackets[ci]) == 1:
                        return med(ktimes[ci][brackets[ci][0]], field)
                    return loglog_time_at_error(
                        [(med(ktimes[ci][s], field), errs[s]) for s in brackets[ci]], target)

                k_render, k_process, k_cpu = (kas_at("render_s"), kas_at("process_s"),
                                              kas_at("cpu_s"))
                ke = {"config": cname, "reached": True,
                      "brackets": [configs[ci][1][vi][0] for vi in brackets[ci]],
                      "bound": len(brackets[ci]) == 1,
                      "relative_rmse": (errs[brackets[ci][0]] if len(brackets[ci]) == 1
                                        else target),
                      "render_s": k_render, "process_s": k_process, "cpu_s": k_cpu,
                      "ratio_render": k_render / c_render if k_render and c_render else None,
                      "ratio_process": k_process / c_process if k_process else None,
                      "ratio_cpu": k_cpu / c_cpu if k_cpu and c_cpu else None,
                      "ratio_process_cpu": k_cpu / c_process_cpu if k_cpu else None,
                      "runs": {configs[ci][1][vi][0]: v for vi, v in ktimes[ci].items()}}
                entry["kasumi"].append(ke)
                print("%s: at relative RMSE %.4f: kasumi [%s] render %s / Cycles %s = %.3f "
                      "(speed-up %.1fx); CPU %s / %s = %.3f (%.1fx); whole process %s / %s = "
                      "%.3f (%.1fx)" % (key, target, cname, fmt_s(k_render), fmt_s(c_render),
                                        ke["ratio_render"], 1 / ke["ratio_render"],
                                        fmt_s(k_cpu), fmt_s(c_cpu), ke["ratio_cpu"],
                                        1 / ke["ratio_cpu"], fmt_s(k_process),
                                        fmt_s(c_process), ke["ratio_process"],
                                        1 / ke["ratio_process"]))
            results.append(entry)
            with open(os.path.join(args.out, "results_%s.json" % args.scenes.replace(",", "_")),
                      "w") as f:
                json.dump(results, f, indent=1)
    cycles.close()

    header = ["case", "error target (rel. RMSE)", "references agree (rel. RMSE, scale)",
              "Cycles render / CPU / process", "kasumi configuration", "kasumi render / CPU / "
              "process", "ratio kasumi/Cycles render (CPU; process)"]
    table = []
    for r in results:
        c = r["cycles"]
        for k in r["kasumi"]:
            if not k["reached"]:
                continue
            table.append([r["case"], "%.4f" % r["target_relative_rmse"],
                          "%.4f, %.3f" % (r["reference_relative_rmse_after_scale"],
                                          r["reference_scale_kasumi_over_cycles"]),
                          "%s / %s / %s" % (fmt_s(c["render_s"]), fmt_s(c["cpu_s"]),
                                            fmt_s(c["process_s"])),
                          "%s, %s%s" % (k["config"], " to ".join(k["brackets"]),
                                            (", rel. RMSE %.4f (bound)" % k["relative_rmse"])
                                            if k["bound"] else ""),
                          "%s / %s / %s" % (fmt_s(k["render_s"]),
                                                         fmt_s(k["cpu_s"]),
                                                         fmt_s(k["process_s"])),
                          "%.3f (%.3f; %.3f)" % (k["ratio_render"], k["ratio_cpu"],
                                                 k["ratio_process"])])
    print(markdown_table(header, table))
    print("load average at end: %.2f %.2f %.2f; total %.0f s"
          % (os.getloadavg() + (time.perf_counter() - t_start,)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
