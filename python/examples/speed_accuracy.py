#!/usr/bin/env python3
"""The speed/accuracy trade of a scene: render it with each integrator,
sample count and maximum depth, measure each image's error against a
reference and its time, and plot error against time.

    PYTHONPATH=build/python python3 python/examples/speed_accuracy.py \
        scenes/cornell-box.pbrt --out study

writes study/error-vs-time.png, study/report.html (one self-contained page:
the plot, a table, every image), and study/results.json.

The reference is a render with the first integrator at the largest depth
and --reference-spp samples, or an image given with --reference (for
example one of pbrt-v4's). Relative MSE is Rousselle et al.'s (2011), as
`lantern compare` reports it; a point below and to the left of another
gives less error in less time. A smaller maxdepth is faster and biased:
the plot shows where that bias starts to dominate the noise.
"""
import argparse
import base64
import html
import io
import json
import os
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import lantern  # noqa: E402


def tonemapped_png(image, exposure=1.0):
    """An sRGB-encoded 8-bit PNG of a linear image, as bytes."""
    x = np.clip(image * exposure, 0.0, 1.0)
    x = np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)
    buf = io.BytesIO()
    plt.imsave(buf, x, format="png")
    return buf.getvalue()


def data_uri(png):
    return "data:image/png;base64," + base64.b64encode(png).decode("ascii")


def study(args):
    scene = lantern.load_scene(args.scene)
    common = dict(resolution=tuple(args.resolution), seed=args.seed)
    depths = args.maxdepth or [scene.settings["maxdepth"]]
    if args.reference:
        reference = lantern.read_image(args.reference)
        ref_note = f"the image {args.reference}"
    else:
        ref = lantern.render(scene, integrator=args.integrators[0], spp=args.reference_spp, maxdepth=max(depths),
                             seed=args.seed + 1, resolution=tuple(args.resolution))
        reference = ref.image
        ref_note = (f"{args.integrators[0]}, {args.reference_spp} spp, maxdepth {max(depths)} "
                    f"({ref.seconds:.2f} s)")
    rows = []
    for integrator in args.integrators:
        for depth in depths:
            for spp in args.spp:
                r = lantern.render(scene, integrator=integrator, spp=spp, maxdepth=depth, **common)
                m = lantern.compare(r.image, reference)
                rows.append(dict(integrator=integrator, maxdepth=depth, spp=spp, seconds=r.seconds,
                                 relmse=m["relmse"], mse=m["mse"], psnr=m["psnr"],
                                 samples_per_second=r.samples / r.seconds if r.seconds > 0 else 0.0,
                                 png=tonemapped_png(r.image, args.exposure)))
                print(f"{integrator:5s} maxdepth {depth:2d} {spp:5d} spp: {r.seconds:7.3f} s, "
                      f"relMSE {m['relmse']:.4g}", file=sys.stderr)
    return scene, reference, ref_note, rows


def plot(rows, path):
    fig, ax = plt.subplots(figsize=(7, 4.5), dpi=110)
    series = sorted({(r["integrator"], r["maxdepth"]) for r in rows})
    for integrator, depth in series:
        pts = sorted((r["seconds"], r["relmse"], r["spp"]) for r in rows
                     if r["integrator"] == integrator and r["maxdepth"] == depth)
        ax.loglog([p[0] for p in pts], [p[1] for p in pts], marker="o", label=f"{integrator}, maxdepth {depth}")
        for t, e, spp in pts:
            ax.annotate(str(spp), (t, e), textcoords="offset points", xytext=(4, 4), fontsize=7)
    ax.set_xlabel("render time (s)")
    ax.set_ylabel("relative MSE against the reference")
    ax.set_title("Error against time (labels: samples per pixel)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def report(args, scene, reference, ref_note, rows, plot_png, path):
    table = "\n".join(
        f"<tr><td>{html.escape(r['integrator'])}</td><td>{r['maxdepth']}</td><td>{r['spp']}</td>"
        f"<td>{r['seconds']:.3f}</td><td>{r['samples_per_second'] / 1e6:.2f}</td><td>{r['relmse']:.4g}</td>"
        f"<td>{r['psnr']:.2f}</td><td><img src=\"{data_uri(r['png'])}\" width=\"96\"></td></tr>" for r in rows)
    page = f"""<!DOCTYPE html>
<html><head><meta charset="utf-8"><title>Speed and accuracy: {html.escape(os.path.basename(args.scene))}</title>
<style>body{{font-family:sans-serif;margin:2em}}table{{border-collapse:collapse}}
td,th{{border:1px solid #ccc;padding:3px 8px;text-align:right}}</style></head><body>
<h1>Speed and accuracy: {html.escape(args.scene)}</h1>
<p>{html.escape(lantern.version())}; {args.resolution[0]}x{args.resolution[1]} pixels, seed {args.seed};
reference: {html.escape(ref_note)}.</p>
<p><img src="{data_uri(plot_png)}" alt="error against time"></p>
<p>Reference:<br><img src="{data_uri(tonemapped_png(reference, args.exposure))}" width="192"></p>
<table><tr><th>integrator</th><th>maxdepth</th><th>spp</th><th>seconds</th><th>Msamples/s</th>
<th>relMSE</th><th>PSNR (dB)</th><th>image</th></tr>
{table}
</table></body></html>
"""
    pathlib.Path(path).write_text(page)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("scene")
    p.add_argument("--out", default="study", help="folder for the plot, the report and the results")
    p.add_argument("--integrators", nargs="+", default=["path", "bdpt", "vcm"])
    p.add_argument("--spp", nargs="+", type=int, default=[4, 16, 64])
    p.add_argument("--maxdepth", nargs="+", type=int, help="default: the scene's")
    p.add_argument("--resolution", nargs=2, type=int, default=[160, 160])
    p.add_argument("--reference", help="a reference image (default: render one)")
    p.add_argument("--reference-spp", type=int, default=1024)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--exposure", type=float, default=1.0, help="for the report's pictures")
    args = p.parse_args(argv)
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    scene, reference, ref_note, rows = study(args)
    plot(rows, out / "error-vs-time.png")
    report(args, scene, reference, ref_note, rows, (out / "error-vs-time.png").read_bytes(), out / "report.html")
    (out / "results.json").write_text(json.dumps(
        {"scene": args.scene, "reference": ref_note, "version": lantern.version(),
         "results": [{k: v for k, v in r.items() if k != "png"} for r in rows]}, indent=2))
    print(f"wrote {out / 'error-vs-time.png'}, {out / 'report.html'}, {out / 'results.json'}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
