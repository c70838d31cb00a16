#!/usr/bin/python3
"""Peer benchmark: kasumi against OpenVDB's vdb_render on the same cloud, camera, light and
medium, compared at equal error against a converged kasumi reference.

    bench/vdb_render_bench.py [--build build/release] [--res 256,512] [--image 512] [--runs 5]

What vdb_render computes (openvdb/tools/RayTracer.h, VolumeRender::operator(), OpenVDB 10):
a fixed-step march along each camera ray through the pixel centre (step `-step` voxels, nodes at
multiples of the step from the eye, index space), at each node with density d >= cutoff

    dT    = exp(-(absorb + scatter) d step)
    L    += lightColor * scatter / (scatter + absorb) * T_shadow * T_camera * (1 - dT)
    T_camera *= dT

with T_shadow a march toward the light (step `-shadowstep` voxels, rectangle rule, densities below
`cutoff` skipped, stopped when |T_shadow|^2 < cutoff) and each shadow step's optical depth
divided by (1 + t gain): `-gain` fakes multiple scattering, so we set it to 0. The camera march
stops when |T_camera|^2 < cutoff. Coefficients are per voxel length. At convergence (step -> 0,
cutoff -> 0) this is single scattering with a phase function equal to 1 per steradian:

    L = lightColor * integral sigma_s(x) T_camera(x) T_light(x) dt.

kasumi's single scattering with an isotropic phase (1/(4 pi) per sr) under a directional light
of illuminance E gives E/(4 pi) * the same integral; with E = 4 pi lux (white) the two agree
exactly, so no rescaling is needed. kasumi's coefficients are per metre: sigma = vdb coefficient
/ voxel size. Camera: same eye, look-at, up; vdb_render's -fov is horizontal, kasumi's fov_deg
vertical: equal for the square images used here. kasumi samples the pixel centre too
(film.jitter = false), so both estimate the same pixel value.

Equal error: the reference is kasumi at many samples per pixel (two independent halves, so its
own noise is measured and removed from every RMSE; bench/vdb_image_compare.cpp). vdb_render is
deterministic: its error is its bias (steps and cutoffs). kasumi's estimators are unbiased: its
error is noise, falling as 1/sqrt(spp). We find the smallest power-of-two spp whose corrected RMSE
is at or below vdb_render's, then time both (same thread count) in alternating runs and report
medians. Also printed: the time kasumi would need at exactly vdb_render's error (RMSE^2 ~ 1/spp),
kasumi's density lookups per second per core and rays per second.
"""
import argparse
import json
import math
import os
import re
import statistics

import bench_common
from bench_common import run

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# Scene (metres). make-cloud's cube spans x, z in [-500, 500], y in [0, 1000].
EYE = (0.0, 480.0, 1500.0)
TARGET = (8.0, 418.0, 0.0)
UP = (0.0, 1.0, 0.0)
FOV_DEG = 30.0
LIGHT_TOWARD = (0.55, 0.65, -0.2)  # direction toward the light (vdb_render's -light)
SIGMA_S_PER_M = 0.1  # per unit density
SIGMA_A_PER_M = 0.002


def march_with_light_cache(step_voxels):
    """The marched single-scattering configuration at a step of step_voxels voxels."""
    return ("march %d voxels + light cache" % step_voxels,
            {"integrator": "single", "estimator": "march", "step_voxels": float(step_voxels),
             "light_cache": True},
            False)


def debiased_march(step_voxels):
    """The unbiased marched single scattering at a node step of step_voxels voxels."""
    return ("debiased-march %g voxels" % step_voxels,
            {"integrator": "single", "estimator": "debiased-march",
             "step_voxels": float(step_voxels)},
            True)


# kasumi configurations timed against vdb_render (name, render.volume settings, unbiased?).
CONFIGS = [
    ("residual-ratio", {"integrator": "single", "estimator": "residual-ratio"}, True),
    ("residual-ratio + light cache",
     {"integrator": "single", "estimator": "residual-ratio", "light_cache": True}, False),
    *(march_with_light_cache(voxels) for voxels in (2, 4, 8, 6, 7)),
    # Ratio tracking for in-scattering with next-event estimation at 4 collisions per walk
    # (render.volume.nee_points, docs/volumes.md): the README's 1.74x row (--configs 7).
    ("residual-ratio, 4 next-event points",
     {"integrator": "single", "estimator": "residual-ratio", "nee_points": 4}, True),
    # Unbiased ray marching (Kettunen et al. 2021) for the shadow rays' transmittance
    # (docs/volumes.md): --configs 8,9.
    ("unbiased-march", {"integrator": "single", "estimator": "unbiased-march"}, True),
    ("unbiased-march, 4 next-event points",
     {"integrator": "single", "estimator": "unbiased-march", "nee_points": 4}, True),
    # Stochastic one-voxel trilinear lookups in the trackers (render.volume.density_filter,
    # docs/volumes.md), unbiased: --configs 10,11.
    ("residual-ratio, 4 next-event points, stochastic filter",
     {"integrator": "single", "estimator": "residual-ratio", "nee_points": 4,
      "density_filter": "stochastic"}, True),
    ("unbiased-march, 4 next-event points, stochastic filter",
     {"integrator": "single", "estimator": "unbiased-march", "nee_points": 4,
      "density_filter": "stochastic"}, True),
    # Unbiased marched single scattering (volume/debiased_march_single.h, docs/volumes.md): the
    # march's nodes, camera transmittance debiased about the trapezoid, shadows debiased about
    # the light cache's depth: --configs 12,13,14.
    *(debiased_march(voxels) for voxels in (2, 3, 4)),
    # The same at finer and coarser steps (since the correction roulettes of 2026-12-05 the
    # finer steps are the more efficient at equal error, the coarser reach vdb_render's error
    # at 1 spp soonest): --configs 15,16,17,18.
    *(debiased_march(voxels) for voxels in (1, 1.5, 5, 6)),
]


def kasumi_scene(vdb_path, voxel_m, res_px, spp, seed, volume):
    return {
        "camera": {"position": list(EYE), "look_at": list(TARGET), "up": list(UP),
                   "fov_deg": FOV_DEG},
        "film": {"width": res_px, "height": res_px, "spp": spp, "jitter": False},
        "background": [0, 0, 0],
        "lights": [{"name": "sun", "type": "directional",
                    "direction": [-c for c in LIGHT_TOWARD],
                    "illuminance_lux": 4.0 * math.pi, "color": [1, 1, 1]}],
        "media": [{"name": "cloud", "type": "vdb", "file": os.path.abspath(vdb_path),
                   "grid": "density", "sigma_a": [SIGMA_A_PER_M] * 3,
                   "sigma_s": [SIGMA_S_PER_M] * 3, "phase": {"model": "isotropic"}}],
        "render": {"seed": seed, "volume": volume},
    }


# Both write one RGBA float EXR with RLE: kasumi without AOV channels or their conversion
# (--aovs none, --compression rle), vdb_render told so (-compression rle: its default is zip,
# which until 2026-11-30 12:50 UTC it wrote while kasumi wrote RLE), so neither side pays for
# output the other does not write.
KASUMI_OUTPUT = ["--aovs", "none", "--compression", "rle"]


def render_kasumi(args, scene_path, out, spp, seed, threads):
    t, wall, cpu, stats = bench_common.render_kasumi(args.kasumi, scene_path, out, spp, seed,
                                                     threads, KASUMI_OUTPUT)
    stats["cpu_s"] = cpu
    if stats.get("density lookups") and cpu > 0:
        # Lookups per CPU second of the whole process (load and write included): a lower bound
        # on the render's own rate that the machine's load does not inflate.
        stats["lookups_per_cpu_s"] = stats["density lookups"] / cpu
    return t, wall, stats


def render_vdb(args, vdb_path, voxel_m, out, res_px, step, shadowstep, cutoff, threads, env=None):
    cmd = ["vdb_render", vdb_path, out, "-res", "%dx%d" % (res_px, res_px),
           "-translate", "%g,%g,%g" % EYE, "-lookat", "%g,%g,%g" % TARGET,
           "-up", "%g,%g,%g" % UP, "-fov", "%g" % FOV_DEG,
           "-light", "%g,%g,%g,1,1,1" % LIGHT_TOWARD,
           "-scatter", ",".join(["%g" % (SIGMA_S_PER_M * voxel_m)] * 3),
           "-absorb", ",".join(["%g" % (SIGMA_A_PER_M * voxel_m)] * 3),
           "-gain", "0", "-step", "%g" % step, "-shadowstep", "%g" % shadowstep,
           "-cutoff", "%g" % cutoff, "-cpus", str(threads), "-compression", "rle", "-v"]
    p, wall, cpu = run(cmd, env=env)
    m = re.search(r"ray-tracing.*\n.*completed in ([0-9.eE+-]+) sec", p.stdout)
    render_vdb.cpu_s = cpu  # whole process, user + system
    return (float(m.group(1)) if m else wall), wall


def compare(args, ref_a, ref_b, image):
    return bench_common.compare(args.compare, ref_a, ref_b, image)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build", "release"))
    ap.add_argument("--res", default="256,512", help="cloud resolutions (voxels per edge)")
    ap.add_argument("--image", type=int, default=512, help="image edge in pixels")
    ap.add_argument("--runs", type=int, default=5, help="timed runs per renderer (alternating)")
    ap.add_argument("--threads", type=int, default=1, help="threads for the timed runs")
    ap.add_argument("--ref-spp", type=int, default=512, help="reference spp (two halves)")
    ap.add_argument("--max-spp", type=int, default=256, help="end of each spp ladder")
    ap.add_argument("--configs", default="",
                    help="comma-separated indices into CONFIGS to run (default: all; the "
                         "reference always uses CONFIGS[0])")
    ap.add_argument("--vdb-step", default="1,3,0.005",
                    help="vdb_render step,shadowstep,cutoff (its defaults: 1,3,0.005)")
    ap.add_argument("--out", default=os.path.join(ROOT, "build", "vdb_bench"))
    ap.add_argument("--kasumi", default="",
                    help="kasumi binary to time (default: BUILD/apps/kasumi), e.g. an older build "
                         "for a before/after comparison")
    args = ap.parse_args()
    args.kasumi = args.kasumi or os.path.join(args.build, "apps", "kasumi")
    args.compare = os.path.join(args.build, "bench", "vdb_image_compare")
    os.makedirs(args.out, exist_ok=True)
    step, shadowstep, cutoff = (float(x) for x in args.vdb_step.split(","))
    load = os.getloadavg()
    print("load average at start: %.2f %.2f %.2f; %d cores" % (load + (os.cpu_count(),)))
    results = []
    for res in (int(r) for r in args.res.split(",")):
        voxel_m = 1000.0 / res
        vdb = os.path.join(args.out, "cumulus_%d.vdb" % res)
        if not os.path.exists(vdb):
            run([args.kasumi, "make-cloud", "--res", str(res), "--seed", "7", "-o", vdb])

        def scene_file(tag, volume):
            path = os.path.join(args.out, "scene_%d_%s.json" % (res, tag))
            with open(path, "w") as f:
                json.dump(kasumi_scene(vdb, voxel_m, args.image, 1, 1, volume), f, indent=1)
            return path

        configs = [(name, scene_file("c%d" % i, volume), unbiased)
                   for i, (name, volume, unbiased) in enumerate(CONFIGS)]
        ref_scene = configs[0][1]
        if args.configs:
            configs = [configs[int(i)] for i in args.configs.split(",")]
        # Reference: the unbiased configuration, two independent halves, all threads.
        half = max(args.ref_spp // 2, 1)
        refs = []
        for k, seed in enumerate((1001, 2002)):
            path = os.path.join(args.out, "ref_%d_%c.exr" % (res, "ab"[k]))
            if not os.path.exists(path):
                t, _, _ = render_kasumi(args, ref_scene, path, half, seed, 0)
                print("res %d: reference half %d (%d spp) in %.1f s" % (res, k, half, t))
            refs.append(path)

        vdb_out = os.path.join(args.out, "vdb_%d.exr" % res)
        t_vdb, _ = render_vdb(args, vdb, voxel_m, vdb_out, args.image, step, shadowstep, cutoff,
                              args.threads)
        e_vdb = compare(args, refs[0], refs[1], vdb_out)
        print("res %d: vdb_render %.2f s, RMSE %.4g (corrected %.4g, ref noise %.3g, mean %.4g)"
              % (res, t_vdb, e_vdb["rmse"], e_vdb["rmse_corrected"], e_vdb["ref_noise_rmse"],
                 e_vdb["ref_mean"]))

        # Start-up CPU of each program (process start, reading the grid, writing a 16x16 image,
        # median of 3 runs) is subtracted from every timed run's process CPU: "render CPU". A
        # light cache is built inside the render, so its build stays counted.
        tiny = ["--set", "/film/width=16", "--set", "/film/height=16"]
        startup_k = statistics.median(
            bench_common.render_kasumi(args.kasumi, ref_scene, os.path.join(args.out, "tiny_k.exr"),
                                       1, 7, args.threads, tiny + KASUMI_OUTPUT)[2]
            for _ in range(3))
        startup_v = []
        for _ in range(3):
            render_vdb(args, vdb, voxel_m, os.path.join(args.out, "tiny_v.exr"), 16, step,
                       shadowstep, cutoff, args.threads)
            startup_v.append(render_vdb.cpu_s)
        startup_v = statistics.median(startup_v)
        # vdb_render maps the file and reads a leaf's values only when a ray first needs them
        # (OpenVDB's delayed loading), so its 16x16 start-up skips most of the grid, which its
        # full render then reads. For comparison with kasumi's (which reads every leaf): its
        # start-up with delayed loading off, i.e. reading the whole grid.
        full_v = []
        for _ in range(3):
            render_vdb(args, vdb, voxel_m, os.path.join(args.out, "tiny_v.exr"), 16, step,
                       shadowstep, cutoff, args.threads,
                       env=dict(os.environ, OPENVDB_DISABLE_DELAYED_LOAD="1"))
            full_v.append(render_vdb.cpu_s)
        print("res %d: start-up CPU (16x16 image): kasumi %.3f s, vdb_render %.3f s "
              "(%.3f s reading the whole grid)" % (res, startup_k, startup_v,
                                                    statistics.median(full_v)))

        # Each configuration's spp ladder at the timed thread count: the smallest power of two
        # at or below vdb_render's error.
        chosen = []
        for ci, (name, scene, unbiased) in enumerate(configs):
            spp = 1
            while True:
                out = os.path.join(args.out, "kasumi_%d_c%d_%d.exr" % (res, ci, spp))
                t, _, stats = render_kasumi(args, scene, out, spp, 7, args.threads)
                e = compare(args, refs[0], refs[1], out)
                print("res %d: kasumi [%s] %4d spp %.3f s, RMSE corrected %.4g"
                      % (res, name, spp, t, e["rmse_corrected"]))
                if e["rmse_corrected"] <= e_vdb["rmse_corrected"] or spp >= args.max_spp:
                    break
                spp *= 2
            chosen.append((spp, e["rmse_corrected"], e["rmse_corrected"] <= e_vdb["rmse_corrected"]))

        # Alternating timed runs: vdb_render, then every configuration, repeated.
        times_vdb, walls_vdb, cpus_vdb = [], [], []
        times_k = [[] for _ in configs]
        stats_k = [[] for _ in configs]
        for _ in range(args.runs):
            t, w = render_vdb(args, vdb, voxel_m, vdb_out, args.image, step, shadowstep,
                              cutoff, args.threads)
            times_vdb.append(t)
            walls_vdb.append(w)
            cpus_vdb.append(render_vdb.cpu_s)
            for ci, (name, scene, _) in enumerate(configs):
                spp = chosen[ci][0]
                out = os.path.join(args.out, "kasumi_%d_c%d_%d.exr" % (res, ci, spp))
                t, _, s_ = render_kasumi(args, scene, out, spp, 7, args.threads)
                times_k[ci].append(t)
                stats_k[ci].append(s_)
        med_vdb = statistics.median(times_vdb)
        r = {"res": res, "image": args.image, "threads": args.threads,
             "vdb_render": {"step": step, "shadowstep": shadowstep, "cutoff": cutoff,
                            "median_s": med_vdb, "runs_s": times_vdb,
                            "median_wall_s": statistics.median(walls_vdb),
                            "median_cpu_s": statistics.median(cpus_vdb),
                            "rmse": e_vdb["rmse_corrected"]},
             "ref_mean": e_vdb["ref_mean"], "ref_noise_rmse": e_vdb["ref_noise_rmse"],
             "kasumi": []}
        for ci, (name, _, unbiased) in enumerate(configs):
            spp, rmse, reached = chosen[ci]
            med = statistics.median(times_k[ci])
            s_ = stats_k[ci][len(stats_k[ci]) // 2]
            med_cpu = statistics.median(x["cpu_s"] for x in stats_k[ci])
            med_cpu_vdb = statistics.median(cpus_vdb)
            render_cpu_k = max(med_cpu - startup_k, 1e-9)
            render_cpu_v = max(med_cpu_vdb - startup_v, 1e-9)
            entry = {"config": name, "spp": spp, "rmse": rmse, "reached_vdb_error": reached,
                     "median_s": med, "runs_s": times_k[ci],
                     "speedup_at_equal_or_lower_error": med_vdb / med if reached else None,
                     "density_lookups": s_.get("density lookups"),
                     "lookups_per_s_per_core": s_.get("lookups/s/core"),
                     "median_cpu_s": med_cpu,
                     "startup_cpu_s": startup_k, "vdb_startup_cpu_s": startup_v,
                     "render_cpu_s": render_cpu_k, "vdb_render_cpu_s": render_cpu_v,
                     "render_cpu_speedup": render_cpu_v / render_cpu_k if reached else None,
                     "lookups_per_render_cpu_s": (s_.get("density lookups") or 0) / render_cpu_k,
                     "cpu_speedup": med_cpu_vdb / med_cpu if reached and med_cpu > 0 else None,
                     "lookups_per_cpu_s": statistics.median(
                         x.get("lookups_per_cpu_s", 0.0) for x in stats_k[ci]),
                     "camera_rays_per_s": s_.get("camera rays/s"),
                     "all_rays_per_s": s_.get("all rays/s")}
            if unbiased and rmse > 0:
                # RMSE^2 ~ 1/spp for an unbiased estimator: time at exactly vdb_render's error.
                entry["seconds_at_vdb_rmse"] = med * (rmse / e_vdb["rmse_corrected"]) ** 2
                entry["speedup_at_equal_error"] = med_vdb / entry["seconds_at_vdb_rmse"]
                entry["cpu_speedup_at_equal_error"] = (
                    med_cpu_vdb / (med_cpu * (rmse / e_vdb["rmse_corrected"]) ** 2))
                entry["render_cpu_speedup_at_equal_error"] = (
                    render_cpu_v / (render_cpu_k * (rmse / e_vdb["rmse_corrected"]) ** 2))
            r["kasumi"].append(entry)
            print("res %d: median vdb_render %.3f s (RMSE %.4g) vs kasumi [%s] %.3f s at %d spp "
                  "(RMSE %.4g%s): %s; CPU %.3f s vs %.3f s: %s; %.3g lookups/s/core (wall), "
                  "%.3g lookups per CPU s, %.3g camera rays/s, %.3g rays/s" %
                  (res, med_vdb, e_vdb["rmse_corrected"], name, med, spp, rmse,
                   "" if reached else ", vdb_render's error NOT reached",
                   ("%.1fx" % (med_vdb / med)) if reached else "n/a",
                   med_cpu_vdb, med_cpu,
                   ("%.1fx" % (med_cpu_vdb / med_cpu)) if reached and med_cpu > 0 else "n/a",
                   s_.get("lookups/s/core", 0), entry["lookups_per_cpu_s"],
                   s_.get("camera rays/s", 0), s_.get("all rays/s", 0)))
            print("res %d:   render CPU (start-up removed) vdb_render %.3f s vs kasumi [%s] %.3f s:"
                  " %s; %.3g lookups per render CPU s (%.0f ns per lookup all-in)"
                  % (res, render_cpu_v, name, render_cpu_k,
                     ("%.1fx" % (render_cpu_v / render_cpu_k)) if reached else "n/a",
                     entry["lookups_per_render_cpu_s"],
                     1e9 / entry["lookups_per_render_cpu_s"] if entry["lookups_per_render_cpu_s"]
                     else 0))
        results.append(r)
    load = os.getloadavg()
    print("load average at end: %.2f %.2f %.2f" % load)
    print(json.dumps(results, indent=1))


if __name__ == "__main__":
    main()
