# pbrt-v4's quadrics and curves as polygon meshes in their object space,
# for scene_to_cycles.py: (vertices, faces), each face wound
# counter-clockwise seen from the side pbrt's normal points to (outwards
# for spheres and cylinders, +z for disks). No Blender here.
import math


def _phi_steps(phimax_deg, seg):
    """Angles of the vertices around z: a closed ring for a full turn."""
    phimax = math.radians(min(max(phimax_deg, 0.0), 360.0))
    closed = phimax >= 2 * math.pi - 1e-6
    count = seg if closed else seg + 1
    return [phimax * k / seg for k in range(count)], closed


def _band(rings, closed):
    """Quads between consecutive rings of equal length, (a, b, c, d) with
    b after a around z and d above a on the next ring."""
    faces = []
    n = len(rings[0])
    for j in range(len(rings) - 1):
        for k in range(n if closed else n - 1):
            k1 = (k + 1) % n
            a, b = rings[j][k], rings[j][k1]
            c, d = rings[j + 1][k1], rings[j + 1][k]
            faces.append((a, b, c, d))
    return faces


def _rings(phis, ring_params, point):
    """Rings of vertices point(t, phi), one per t in ring_params, and
    their indices."""
    verts, ring_ids = [], []
    for t in ring_params:
        ring_ids.append(list(range(len(verts), len(verts) + len(phis))))
        verts.extend(point(t, ph) for ph in phis)
    return verts, ring_ids


def sphere(radius, zmin=None, zmax=None, phimax=360.0, seg=64, rings=32):
    zmin = -radius if zmin is None else max(-radius, min(zmin, radius))
    zmax = radius if zmax is None else max(-radius, min(zmax, radius))
    th0, th1 = math.acos(zmax / radius), math.acos(zmin / radius)
    phis, closed = _phi_steps(phimax, seg)
    # from the bottom (theta1) up, so that each band's quads face out
    thetas = [th1 + (th0 - th1) * j / rings for j in range(rings + 1)]
    verts, ring_ids = _rings(phis, thetas, lambda th, ph: (radius * math.sin(th) * math.cos(ph),
                                                           radius * math.sin(th) * math.sin(ph), radius * math.cos(th)))
    return verts, _band(ring_ids, closed)


def cylinder(radius, zmin=-1.0, zmax=1.0, phimax=360.0, seg=64):
    phis, closed = _phi_steps(phimax, seg)
    verts, ring_ids = _rings(phis, (zmin, zmax), lambda z, ph: (radius * math.cos(ph), radius * math.sin(ph), z))
    return verts, _band(ring_ids, closed)


def disk(radius, innerradius=0.0, height=0.0, phimax=360.0, seg=64):
    phis, closed = _phi_steps(phimax, seg)
    verts, ring_ids = _rings(phis, (innerradius, radius), lambda r, ph: (r * math.cos(ph), r * math.sin(ph), height))
    # rings from the inside out: a band's quads face -z, so they are
    # reversed (triangles at the centre when innerradius is 0)
    faces = []
    for a, b, c, d in _band(ring_ids, closed):
        faces.append((d, c, b, a) if innerradius > 0 else (d, c, a))
    return verts, faces


def _bezier(p, u):
    s = 1 - u
    return [s * s * s * p[0][k] + 3 * s * s * u * p[1][k] + 3 * s * u * u * p[2][k] + u * u * u * p[3][k] for k in range(3)]


def curve_tube(points, width0, width1, steps=8, sides=6):
    """A cubic Bezier curve of four control points as a tube of its width
    (pbrt-v4's "flat" and "cylinder" curves alike: a round fibre)."""
    centres = [_bezier(points, i / steps) for i in range(steps + 1)]
    verts, ring_ids = [], []
    prev_n = None
    for i, c in enumerate(centres):
        a, b = centres[max(i - 1, 0)], centres[min(i + 1, steps)]
        t = [b[k] - a[k] for k in range(3)]
        tl = math.sqrt(sum(x * x for x in t)) or 1.0
        t = [x / tl for x in t]
        # a normal carried along the curve (projected, so it stays smooth)
        ref = prev_n or ([1.0, 0.0, 0.0] if abs(t[0]) < 0.9 else [0.0, 1.0, 0.0])
        d = sum(ref[k] * t[k] for k in range(3))
        n = [ref[k] - d * t[k] for k in range(3)]
        nl = math.sqrt(sum(x * x for x in n)) or 1.0
        n = [x / nl for x in n]
        bn = [t[1] * n[2] - t[2] * n[1], t[2] * n[0] - t[0] * n[2], t[0] * n[1] - t[1] * n[0]]
        prev_n = n
        r = 0.5 * (width0 + (width1 - width0) * i / steps)
        ids = []
        for s in range(sides):
            ph = 2 * math.pi * s / sides
            ids.append(len(verts))
            verts.append(tuple(c[k] + r * (math.cos(ph) * n[k] + math.sin(ph) * bn[k]) for k in range(3)))
        ring_ids.append(ids)
    # rings advance along t, each counter-clockwise around it (n, then
    # t x n): _band's quads face outwards, as a cylinder's
    return verts, _band(ring_ids, True)
