#!/usr/bin/env python3
# Writes scenes/smoke.pbrt: a rising plume of smoke on a 24 x 32 x 24
# uniformgrid (a smooth procedural density), inside an "interface" box,
# in a room lit by a window light and a dim sky.
# Usage: python3 perf/media/make-smoke.py > scenes/smoke.pbrt
import math

nx, ny, nz = 24, 32, 24
vals = []
for k in range(nz):
    for j in range(ny):
        for i in range(nx):
            x, y, z = (i + 0.5) / nx - 0.5, (j + 0.5) / ny, (k + 0.5) / nz - 0.5
            cx = 0.08 * math.sin(6.0 * y)
            cz = 0.06 * math.cos(5.0 * y)
            radius = 0.08 + 0.3 * y
            r = math.hypot(x - cx, z - cz) / radius
            core = max(0.0, 1.0 - r * r) ** 1.5
            swirl = 0.65 + 0.35 * math.sin(17 * x + 9 * y + 5 * z) * math.cos(13 * z - 7 * y + 4 * x)
            fade = min(1.0, y * 8.0) * (1.0 - y) ** 0.7
            vals.append(round(max(0.0, core * swirl * fade) * 3.0, 3))

def box(lo, hi):
    P = [(x, y, z) for z in (lo[2], hi[2]) for y in (lo[1], hi[1]) for x in (lo[0], hi[0])]
    c = [(lo[a] + hi[a]) / 2 for a in range(3)]
    faces = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    idx = []
    for f in faces:
        a, b, d = P[f[0]], P[f[1]], P[f[2]]
        u = [b[t] - a[t] for t in range(3)]
        v = [d[t] - a[t] for t in range(3)]
        n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
        mid = [(a[t] + d[t]) / 2 - c[t] for t in range(3)]
        if sum(n[t] * mid[t] for t in range(3)) < 0:
            f = (f[0], f[3], f[2], f[1])
        idx += [f[0], f[1], f[2], f[0], f[2], f[3]]
    return P, idx

P, idx = box((-0.6, 0.01, -0.6), (0.6, 1.6, 0.6))  # clear of the floor: no coplanar faces
print('''# A plume of smoke rising from the floor: a generated 24 x 32 x 24
# uniformgrid (perf/media/make-smoke.py) inside an "interface" box, in a room
# lit by a low window light and a dim sky. Absorbing, forward-scattering
# smoke (docs/media.md).
Film "rgb"
    "integer xresolution" [ 360 ]
    "integer yresolution" [ 480 ]
    "string filename" [ "smoke.exr" ]
Sampler "zsobol"
    "integer pixelsamples" [ 64 ]
Integrator "volpath"
    "integer maxdepth" [ 12 ]
PixelFilter "gaussian"
LookAt 0.3 1.0 -3.6  0 0.8 0  0 1 0
Camera "perspective"
    "float fov" [ 36 ]

WorldBegin

LightSource "infinite"
    "rgb L" [ 0.08 0.1 0.14 ]

# The window: a warm panel low on the right.
AttributeBegin
    AreaLightSource "diffuse"
        "rgb L" [ 14 11 8 ]
    Shape "trianglemesh"
        "point3 P" [ 2.2 0.3 -0.8  2.2 0.3 0.8  2.2 1.4 0.8  2.2 1.4 -0.8 ]
        "integer indices" [ 0 1 2 0 2 3 ]
AttributeEnd

Material "diffuse"
    "rgb reflectance" [ 0.45 0.42 0.38 ]
Shape "trianglemesh"
    "point3 P" [ -5 0 -5  -5 0 5  5 0 5  5 0 -5 ]
    "integer indices" [ 0 1 2 0 2 3 ]
Material "diffuse"
    "rgb reflectance" [ 0.3 0.32 0.36 ]
Shape "trianglemesh"
    "point3 P" [ -5 0 2  5 0 2  5 4 2  -5 4 2 ]
    "integer indices" [ 0 1 2 0 2 3 ]

AttributeBegin
    Translate 0 0 0
    MakeNamedMedium "smoke"
        "string type" [ "uniformgrid" ]
        "rgb sigma_a" [ 0.8 0.8 0.8 ]
        "rgb sigma_s" [ 8 8 8 ]
        "float g" [ 0.5 ]
        "point3 p0" [ -0.6 0 -0.6 ]
        "point3 p1" [ 0.6 1.6 0.6 ]
        "integer nx" [ %d ] "integer ny" [ %d ] "integer nz" [ %d ]
        "float density" [ %s ]
    MediumInterface "smoke" ""
    Material "interface"
    Shape "trianglemesh"
        "point3 P" [ %s ]
        "integer indices" [ %s ]
AttributeEnd''' % (nx, ny, nz, " ".join("%g" % v for v in vals), " ".join("%g %g %g" % p for p in P),
                   " ".join(map(str, idx))))
