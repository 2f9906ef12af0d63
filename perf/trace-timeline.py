#!/usr/bin/env python3
"""Draws a window of a Lantern trace (--trace) as a PNG: one row per track,
waves as grey bars, stages coloured inside them, ray queries in red below
(the darker, the more rays). Perfetto shows the same; this makes a picture
for documents and pages without a browser.

    perf/trace-timeline.py t.json out.png [--from MS] [--to MS] [--width PX]

Needs oiiotool (OpenImageIO) for the PNG and its labels, and the DejaVu
font (Debian's fonts-dejavu-core).
"""
import argparse
import json
import os
import subprocess
import tempfile

STAGE_COLOURS = {
    "generate": (70, 110, 200), "surface": (70, 170, 90), "connect": (235, 140, 40),
    "scatter": (150, 90, 190), "accumulate": (225, 200, 60), "shade": (70, 170, 170),
}
FONT = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"
ROW, LABEL, AXIS = 44, 210, 30


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("trace")
    ap.add_argument("png")
    ap.add_argument("--from", dest="t0", type=float, default=None, help="window start, ms")
    ap.add_argument("--to", dest="t1", type=float, default=None, help="window end, ms")
    ap.add_argument("--width", type=int, default=1600)
    a = ap.parse_args()

    events = json.load(open(a.trace))["traceEvents"]
    names = {e["tid"]: e["args"]["name"] for e in events if e["ph"] == "M" and e["name"] == "thread_name"}
    spans = [e for e in events if e["ph"] == "X"]
    t0 = a.t0 * 1e3 if a.t0 is not None else min(e["ts"] for e in spans)
    t1 = a.t1 * 1e3 if a.t1 is not None else max(e["ts"] + e["dur"] for e in spans)
    tracks = sorted({e["tid"] for e in spans})
    w, h = a.width, AXIS + ROW * len(tracks) + 10
    px = bytearray([255, 255, 255] * w * h)

    def rect(x0, x1, y0, y1, colour):
        for y in range(max(y0, 0), min(y1, h)):
            row = y * w
            for x in range(max(int(x0), LABEL), min(int(x1) + 1, w)):
                px[3 * (row + x):3 * (row + x) + 3] = bytes(colour)

    def xof(t):
        return LABEL + (t - t0) / (t1 - t0) * (w - LABEL - 10)

    max_rays = max([e["args"].get("rays", 0) for e in spans if e.get("cat") == "rays"] or [1])
    for i, tid in enumerate(tracks):
        top = AXIS + ROW * i
        rect(LABEL, w, top + ROW - 1, top + ROW, (220, 220, 220))
        for e in spans:
            if e["tid"] != tid or e["ts"] + e["dur"] < t0 or e["ts"] > t1:
                continue
            x0, x1 = xof(e["ts"]), xof(e["ts"] + e["dur"])
            cat = e.get("cat")
            if cat in ("wave", "load", "render", "output", "pipeline"):
                rect(x0, x1, top + 4, top + 14, (150, 150, 150) if cat != "pipeline" else (90, 90, 90))
            elif cat == "stage":
                rect(x0, x1, top + 16, top + 28, STAGE_COLOURS.get(e["name"], (0, 0, 0)))
            elif cat == "rays":
                k = e["args"].get("rays", 0) / max_rays
                rect(x0, x1, top + 30, top + 40, (255, int(200 * (1 - k)), int(200 * (1 - k))))

    with tempfile.TemporaryDirectory() as d:
        ppm = os.path.join(d, "t.ppm")
        with open(ppm, "wb") as f:
            f.write(b"P6 %d %d 255\n" % (w, h) + bytes(px))
        cmd = ["oiiotool", ppm]
        text = lambda x, y, s, size=13: [f"--text:x={int(x)}:y={int(y)}:size={size}:color=0,0,0:font={FONT}", s]
        for i, tid in enumerate(tracks):
            cmd += text(6, AXIS + ROW * i + 26, names.get(tid, str(tid)))
        for k in range(6):
            t = t0 + (t1 - t0) * k / 5
            cmd += text(min(xof(t), w - 70), 18, "%.1f ms" % (t * 1e-3), 12)
        cmd += ["-o", a.png]
        subprocess.run(cmd, check=True)


if __name__ == "__main__":
    main()
