#!/usr/bin/env python3
"""Writes a 64x64 tangent-space normal map (PFM, linear floats) of a grid of
round bumps, for perf/textures/bumps.pbrt: python3 make-normal-map.py OUT.pfm"""
import math, struct, sys

W = H = 64
rows = []
for y in range(H):
    row = []
    for x in range(W):
        # 4x4 bumps per tile: a height field h = cos^2 over each cell.
        u, v = (x + 0.5) / W * 4, (y + 0.5) / H * 4
        fu, fv = u - math.floor(u) - 0.5, v - math.floor(v) - 0.5
        r = math.hypot(fu, fv)
        if r < 0.4:
            k = math.pi / 0.8 * math.sin(math.pi * r / 0.4) / max(r, 1e-6) * 0.3
            n = (k * fu, -k * fv, 1.0)  # image rows run down while v runs up
        else:
            n = (0.0, 0.0, 1.0)
        l = math.sqrt(sum(c * c for c in n))
        row.append(tuple(0.5 * (c / l + 1) for c in n))
    rows.append(row)
with open(sys.argv[1], "wb") as f:
    f.write(b"PF\n%d %d\n-1.0\n" % (W, H))
    for row in reversed(rows):  # PFM stores the bottom row first
        for px in row:
            f.write(struct.pack("<3f", *px))
