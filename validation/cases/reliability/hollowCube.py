#!/usr/bin/env python3
"""Writes a hollow cube as an ASCII STL: a 10 mm cube (in file units, the
case scales by 0.001) with a 5 mm cubic cavity at its centre, both shells
correctly oriented (the outer facing out, the cavity's facing into the
cavity, i.e. towards its centre). Usage: hollowCube.py file.stl"""
import sys


def cube(half, inward):
    # 12 triangles, counter-clockwise seen from outside when not inward
    c = [(x, y, z) for x in (-half, half) for y in (-half, half) for z in (-half, half)]
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    tris = []
    for a, b, cc, d in quads:
        for t in ((a, b, cc), (a, cc, d)):
            tris.append(tuple(reversed(t)) if inward else t)
    return [[c[i] for i in t] for t in tris]


with open(sys.argv[1], "w") as f:
    f.write("solid hollow\n")
    for tri in cube(5, False) + cube(2.5, True):
        f.write(" facet normal 0 0 0\n  outer loop\n")
        for p in tri:
            f.write("   vertex %g %g %g\n" % p)
        f.write("  endloop\n endfacet\n")
    f.write("endsolid hollow\n")
