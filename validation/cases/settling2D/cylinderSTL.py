import math, sys
# cylinderSTL.py <file> <z0> <z1>: a cylinder of radius 5 mm along z (a
# 128-sided prism) from z0 to z1 [m], centred on the z axis
R, N = 0.005, 128
z0, z1 = float(sys.argv[2]), float(sys.argv[3])
out = open(sys.argv[1], "w")
out.write("solid cylinder\n")
def tri(a, b, c):
    out.write("facet normal 0 0 0\n outer loop\n")
    for p in (a, b, c):
        out.write("  vertex %.9e %.9e %.9e\n" % p)
    out.write(" endloop\nendfacet\n")
pts = [(R*math.cos(2*math.pi*k/N), R*math.sin(2*math.pi*k/N)) for k in range(N)]
for k in range(N):
    (x0, y0), (x1, y1) = pts[k], pts[(k+1) % N]
    tri((x0, y0, z0), (x1, y1, z0), (x1, y1, z1))
    tri((x0, y0, z0), (x1, y1, z1), (x0, y0, z1))
    tri((0, 0, z1), (x0, y0, z1), (x1, y1, z1))
    tri((0, 0, z0), (x1, y1, z0), (x0, y0, z0))
out.write("endsolid cylinder\n")
