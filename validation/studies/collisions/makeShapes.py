#!/usr/bin/python3
"""The two non-convex bodies of the arbitrary-bodies collision (issue #6),
written as closed binary STL files into a folder (lengths in metres):

- bentRod.stl: a rod of round cross-section (radius a) bent along a
  circular arc (radius Rb, opening angle alpha), closed by flat end caps;
- lumpyStar.stl: a star-shaped body r(n) = R (1 + sum_k b max(0, n.d_k)^p)
  over a subdivided icosahedron, six arms along +-x, +-y, +-z tilted so no
  two arms are aligned with the collision axis.

Both are radial or swept surfaces with no self-intersection; immersedDEM
checks them again when it reads them.

    makeShapes.py <folder> [d]   d: the volume-equivalent diameter [m] (0.01)
"""
import math, os, struct, sys

import numpy as np

out = sys.argv[1]
d = float(sys.argv[2]) if len(sys.argv) > 2 else 0.01
os.makedirs(out, exist_ok=True)


def writeStl(path, points, faces):
    with open(path + ".tmp", "wb") as f:
        f.write(b"immersedDEM arbitraryBodiesCollision".ljust(80, b" "))
        f.write(struct.pack("<I", len(faces)))
        for a, b, c in faces:
            pa, pb, pc = points[a], points[b], points[c]
            n = np.cross(pb - pa, pc - pa)
            n = n / np.linalg.norm(n)
            f.write(struct.pack("<12fH", *n, *pa, *pb, *pc, 0))
    os.replace(path + ".tmp", path)


def bentRod(a, Rb, alpha, nRing=24, nArc=48):
    """Rings of nRing points around the arc x = Rb cos t, z = Rb sin t"""
    pts, faces = [], []
    ts = np.linspace(-alpha / 2, alpha / 2, nArc + 1)
    for t in ts:
        c = np.array([Rb * math.cos(t), 0.0, Rb * math.sin(t)])
        radial = np.array([math.cos(t), 0.0, math.sin(t)])
        ey = np.array([0.0, 1.0, 0.0])
        for k in range(nRing):
            phi = 2 * math.pi * k / nRing
            pts.append(c + a * (math.cos(phi) * radial + math.sin(phi) * ey))
    for i in range(nArc):
        for k in range(nRing):
            p00 = i * nRing + k; p01 = i * nRing + (k + 1) % nRing
            p10 = p00 + nRing; p11 = p01 + nRing
            faces += [(p00, p10, p11), (p00, p11, p01)]
    # End caps: a centre point each
    for end, i in ((0, 0), (1, nArc)):
        t = ts[i]
        centre = len(pts)
        pts.append(np.array([Rb * math.cos(t), 0.0, Rb * math.sin(t)]))
        for k in range(nRing):
            p0 = i * nRing + k; p1 = i * nRing + (k + 1) % nRing
            faces.append((centre, p0, p1) if end == 0 else (centre, p1, p0))
    pts = np.array(pts)
    # Centre the arc on its centroid-ish middle so the file sits near 0
    pts -= pts.mean(axis=0)
    return orient(pts, faces)


def icosphere(level):
    t = (1 + 5 ** 0.5) / 2
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
         (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    v = [np.array(p) / np.linalg.norm(p) for p in v]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
         (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
         (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(level):
        cache, nf = {}, []
        def mid(i, j):
            key = (min(i, j), max(i, j))
            if key not in cache:
                p = v[i] + v[j]
                v.append(p / np.linalg.norm(p))
                cache[key] = len(v) - 1
            return cache[key]
        for a, b, c in f:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            nf += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        f = nf
    return np.array(v), f


def lumpyStar(R, b=0.9, p=6, level=4):
    n, faces = icosphere(level)
    # Arms along the axes, turned by 20 deg about x then 35 deg about z
    ax, az = math.radians(20), math.radians(35)
    Rx = np.array([[1, 0, 0], [0, math.cos(ax), -math.sin(ax)], [0, math.sin(ax), math.cos(ax)]])
    Rz = np.array([[math.cos(az), -math.sin(az), 0], [math.sin(az), math.cos(az), 0], [0, 0, 1]])
    dirs = [Rz @ Rx @ e for e in np.vstack([np.eye(3), -np.eye(3)])]
    r = R * (1 + sum(b * np.clip(n @ dk, 0, None) ** p for dk in dirs))
    return orient(n * r[:, None], faces)


def orient(points, faces):
    """Outward orientation: positive signed volume"""
    vol = sum(np.dot(points[a], np.cross(points[b], points[c])) for a, b, c in faces) / 6
    if vol < 0:
        faces = [(a, c, b) for a, b, c in faces]
    return points, faces


# Sizes chosen so each body's volume-equivalent diameter is about d
rod = bentRod(a=0.27 * d, Rb=1.1 * d, alpha=math.radians(120))
star = lumpyStar(R=0.353 * d)
for name, (p, f) in (("bentRod", rod), ("lumpyStar", star)):
    writeStl(os.path.join(out, name + ".stl"), p, f)
    vol = sum(np.dot(p[a], np.cross(p[b], p[c])) for a, b, c in f) / 6
    print("%s.stl: %d triangles, volume %.4g m3, volume-equivalent diameter %.4g m, extent %s m"
          % (name, len(f), vol, (6 * vol / math.pi) ** (1 / 3), np.ptp(p, axis=0).round(5)))
