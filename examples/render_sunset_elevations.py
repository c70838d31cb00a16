#!/usr/bin/python3
"""Render the sunset at five sun elevations and plot the mean sky luminance against elevation.

    PYTHONPATH=build/release/python examples/render_sunset_elevations.py -o sunset_sky.png

Loads data/scenes/sunset.json once, sets /sun/elevation_deg for each render (as
`kasumi render --set /sun/elevation_deg=E` would), and averages the luminance
Y = 0.2126 R + 0.7152 G + 0.0722 B (cd/m², Rec.709) over the sky: the pixels whose camera ray
met no surface (depth 0). Writes the plot and, with --frames, each render's preview PNG.
"""
import argparse
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import kasumi  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[1]
REC709_Y = np.array([0.2126, 0.7152, 0.0722], dtype=np.float32)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scene", default=str(ROOT / "data" / "scenes" / "sunset.json"))
    parser.add_argument("-o", "--output", default="sunset_sky.png", help="plot PNG to write")
    parser.add_argument("--elevations", default="0,2,5,10,20", help="sun elevations, degrees")
    parser.add_argument("--res", default="320x180", help="film WxH (the scene's is 1280x720)")
    parser.add_argument("--frames", metavar="DIR", help="also write each render's preview PNG")
    args = parser.parse_args()

    elevations = [float(e) for e in args.elevations.split(",")]
    width, height = (int(v) for v in args.res.split("x"))
    scene = kasumi.Scene.load(args.scene)
    scene.set("/film/width", width)
    scene.set("/film/height", height)

    sky_luminance = []
    for elevation in elevations:
        scene.set("/sun/elevation_deg", elevation)
        result = scene.render()
        sky = result.depth[..., 0] == 0.0
        y = result.beauty @ REC709_Y  # (H, W) luminance, cd/m²
        sky_luminance.append(float(y[sky].mean()))
        print(f"sun at {elevation:5.1f} deg: mean sky luminance {sky_luminance[-1]:10.1f} cd/m² "
              f"over {int(sky.sum())} pixels ({result.seconds:.2f} s)")
        if args.frames:
            pathlib.Path(args.frames).mkdir(parents=True, exist_ok=True)
            result.write_png(str(pathlib.Path(args.frames) / f"sunset_{elevation:g}deg.png"))

    fig, ax = plt.subplots(figsize=(6, 4), dpi=120)
    ax.plot(elevations, sky_luminance, "o-")
    ax.set_yscale("log")
    ax.set_xlabel("sun elevation (degrees)")
    ax.set_ylabel("mean sky luminance (cd/m²)")
    ax.set_title(pathlib.Path(args.scene).name)
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(args.output)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
