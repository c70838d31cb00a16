#!/usr/bin/python3
"""Validate a phase function against its own sampler and plot both.

    PYTHONPATH=build/release/python examples/validate_phase.py \
        '{"model": "hg", "g": 0.9}' -o hg.png

Runs the checks of `kasumi phase validate` (printed with their p-values), draws samples through
kasumi.phase.sample, and plots the sampled density per steradian against the pdf over the
scattering angle θ (log axes resolve forward peaks), with the ratio and its 2σ band below.
"""
import argparse
import json

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import kasumi  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("model", help='scene-file phase object, e.g. \'{"model": "hg", "g": 0.9}\'')
    parser.add_argument("-o", "--output", default="phase_validation.png", help="PNG to write")
    parser.add_argument("--samples", type=int, default=4_000_000)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()

    try:
        p = kasumi.phase.make(json.loads(args.model), source="command line")
    except kasumi.SceneError as e:
        parser.error(str(e))
    report = kasumi.phase.validate(p, samples=args.samples, seed=args.seed)
    print(report["decision_rule"])
    for c in report["checks"]:
        extra = f"  p = {c['p_value']:.3g}" if c["p_value"] is not None else ""
        print(f"{c['name']:16s} {'pass' if c['passed'] else 'FAIL'}  {c['detail']}{extra}")

    rng = np.random.default_rng(args.seed)
    mu, _ = p.sample(rng.random(args.samples), rng.random(args.samples))
    theta = np.arccos(np.clip(mu, -1, 1))
    # Bins in θ: logarithmic from 1e-5 rad, so narrow forward peaks get bins of their own.
    edges = np.concatenate([[0.0], np.geomspace(1e-5, np.pi, 160)])
    counts = np.histogram(theta, edges)[0]
    solid_angle = 2 * np.pi * (np.cos(edges[:-1]) - np.cos(edges[1:]))
    sampled = counts / (args.samples * solid_angle)
    sigma = np.sqrt(np.maximum(counts, 1)) / (args.samples * solid_angle)
    fine = np.geomspace(1e-5, np.pi, 2000)
    centre = np.sqrt(edges[1:] * np.maximum(edges[:-1], 0.25 * edges[1]))
    # The pdf averaged over each bin (per steradian), to compare with the histogram.
    expected = np.array([np.mean(p.pdf(np.cos(np.linspace(a, b, 64)))) for a, b in
                         zip(edges[:-1], edges[1:])])

    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 7), sharex=True,
                                      gridspec_kw={"height_ratios": [3, 1]})
    top.loglog(np.degrees(fine), p.pdf(np.cos(fine)), "k-", lw=1, label="pdf (eval)")
    keep = counts >= 5  # bins with fewer counts: selection-biased upward, left out
    top.loglog(np.degrees(centre[keep]), sampled[keep], "o", ms=3, color="tab:orange",
               label=f"sampled histogram ({args.samples:.0e} samples)")
    top.set_ylabel("p(θ) per steradian")
    chi = report["checks"][-1]
    top.set_title(f"{json.dumps(json.loads(args.model))}\nchi-square p = {chi['p_value']:.3g} "
                  f"(fails below {chi['alpha']:.2g}): {'pass' if report['passed'] else 'FAIL'}")
    top.legend()
    ok = keep & (counts >= 20)
    ratio = sampled[ok] / expected[ok]
    bottom.semilogx(np.degrees(centre[ok]), ratio, "o", ms=3, color="tab:orange")
    bottom.fill_between(np.degrees(centre[ok]), 1 - 2 * sigma[ok] / expected[ok],
                        1 + 2 * sigma[ok] / expected[ok], color="0.85", label="±2σ")
    bottom.axhline(1.0, color="k", lw=1)
    bottom.set_ylabel("sampled / pdf")
    bottom.set_xlabel("scattering angle θ (degrees)")
    bottom.legend()
    fig.tight_layout()
    fig.savefig(args.output, dpi=110)
    print(f"wrote {args.output}")
    return 0 if report["passed"] else 5


if __name__ == "__main__":
    raise SystemExit(main())
