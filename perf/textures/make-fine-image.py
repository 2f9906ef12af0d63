#!/usr/bin/env python3
"""Writes a 512x512 image (PFM, linear floats) of detail finer than the pixels
that show it in perf/textures/filtering.pbrt: one-texel checks in two
colours under coarser stripes, so filtering changes what the image shows.
python3 make-fine-image.py OUT.pfm"""
import struct, sys

N = 512
with open(sys.argv[1], "wb") as f:
    f.write(b"PF\n%d %d\n-1.0\n" % (N, N))
    for y in range(N):
        for x in range(N):
            fine = (x + y) & 1
            stripe = (x // 32) & 1
            r = 0.9 if fine else 0.05
            g = 0.7 if stripe else 0.2
            b = 0.1 + 0.8 * fine * stripe
            f.write(struct.pack("<3f", r, g, b))
