#!/usr/bin/env python3
"""A catalyst-like pellet: a short cylinder (diameter d, height h, n sides)
as a closed ASCII STL in mm, centred at the origin, axis z.
Usage: makePellet.py out.stl [d h n]"""
import math, sys
out = sys.argv[1]
d, h, n = (float(sys.argv[2]), float(sys.argv[3]), int(sys.argv[4])) if len(sys.argv) > 4 else (3.0, 3.0, 24)
r = d/2
ring = [(r*math.cos(2*math.pi*i/n), r*math.sin(2*math.pi*i/n)) for i in range(n)]
tris = []
for i in range(n):
    (x0, y0), (x1, y1) = ring[i], ring[(i + 1) % n]
    a0, a1, b0, b1 = (x0, y0, -h/2), (x1, y1, -h/2), (x0, y0, h/2), (x1, y1, h/2)
    tris += [(a0, a1, b1), (a0, b1, b0)]            # side, outwards
    tris += [((0, 0, -h/2), a1, a0)]                # bottom, -z
    tris += [((0, 0, h/2), b0, b1)]                 # top, +z
with open(out, "w") as f:
    f.write("solid pellet\n")
    for t in tris:
        f.write(" facet normal 0 0 0\n  outer loop\n")
        for p in t:
            f.write("   vertex %.9g %.9g %.9g\n" % p)
        f.write("  endloop\n endfacet\n")
    f.write("endsolid pellet\n")
