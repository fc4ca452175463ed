#!/usr/bin/env python3
"""Summarise the body's motion in a plane-Couette case of makeCouette.py.

    checkCouette.py <caseDir> [-body cylinder]

Reads <caseDir>/postProcessing/bodies/0/bodies.dat (through
src/python/immersedDEMData.py, columns by name) and the case's parameters
from <caseDir>/couetteParameters (written by makeCouette.py; the
makeCouette.py defaults if it is missing). Prints the largest lateral
velocity |vy|, the largest displacements |x - x0| and |y - y0| over D, the
final angular velocity omega_z against the expected one, the largest body
speed over Uw, then a one-line summary

    couette: maxSpeed/Uw X, maxDisp/D Y, omega/omegaExpected Z

and exits 0. No pass/fail thresholds. Exits 1 with a message if bodies.dat
is missing, unreadable, has no row of the body, or holds a NaN (or an
infinite value).

The expected spin: the top wall (y = +H/2) moves at +Uw, the bottom one at
-Uw, so u = Uw 2y/H, the shear rate is G = du/dy = 2 Uw/H and the fluid's
vorticity omega_f,z = dv/dx - du/dy = -G (clockwise seen from +z). A
torque-free circular cylinder in a linear shear flow (Stokes flow; at the
default particle Reynolds number G D^2/nu = 0.04 the inertial correction is
negligible) turns at half the vorticity, and so does a torque-free sphere
(-shape sphere; exact in unbounded Stokes flow):

    omegaExpected = -G/2 = -Uw/H        (-0.5 rad/s at the defaults)

The confinement (D/H = 0.1) lowers it slightly. For -shape ellipse the
ratio is still taken against -G/2; Jeffery's (1922) rate for an ellipse of
semi-axes a, b whose major axis is at angle phi from x,
omega = -G (a^2 sin^2 phi + b^2 cos^2 phi)/(a^2 + b^2) (period mean
-G ab/(a^2 + b^2)), is printed beside it, phi from the time integral of
omega_z from phi = 0 at rest at t = 0.
"""
import argparse, math, os, sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "..", "..", "src", "python"))
from immersedDEMData import readTable  # noqa: E402

# makeCouette.py's defaults
DEFAULTS = {"shape": "circle", "D": 0.002, "a": 0.001, "b": 0.001, "H": 0.02, "Uw": 0.01,
            "x0": 0.0, "y0": 0.0}


def parameters(case):
    path = os.path.join(case, "couetteParameters")
    p = dict(DEFAULTS)
    if not os.path.exists(path):
        print("checkCouette.py: no %s: taking makeCouette.py's defaults %s"
              % (path, " ".join("%s %s" % kv for kv in sorted(DEFAULTS.items()))), file=sys.stderr)
        return p
    for line in open(path):
        f = line.split()
        if len(f) == 2 and not f[0].startswith("#"):
            p[f[0]] = f[1] if f[0] == "shape" else float(f[1])
    return p


def fail(message):
    print("checkCouette.py: " + message)
    sys.exit(1)


def main():
    ap = argparse.ArgumentParser(description="plane-Couette body motion summary")
    ap.add_argument("case")
    ap.add_argument("-body", default=None, help="body name (default: the first in the table)")
    a = ap.parse_args()
    path = os.path.join(a.case, "postProcessing", "bodies", "0", "bodies.dat")
    if not os.path.isfile(path):
        fail("%s is missing: has the case run (blockMesh, pimpleFoam)?" % path)
    try:
        table = readTable(path)
    except ValueError as e:
        # no header, or a value that is not a number
        fail("%s cannot be read: %s" % (path, e))
    if not len(table):
        fail("%s has no complete row" % path)
    body = a.body or table.bodies()[0]
    t = table.where(body=body)
    if not len(t):
        fail("%s has no row of body '%s' (bodies: %s)" % (path, body, " ".join(table.bodies())))
    for row in table.rows:
        for c, v in zip(table.columns, row):
            if isinstance(v, float) and not math.isfinite(v):
                fail("%s holds %s in column %s at time %s: the run blew up"
                     % (path, v, c, row[table.index("time")]))

    p = parameters(a.case)
    D, H, Uw = p["D"], p["H"], p["Uw"]
    shear = 2*Uw/H
    omegaExpected = -shear/2          # = -Uw/H: half the vorticity -du/dy

    time = t["time"]
    vx, vy, vz = t["vx"], t["vy"], t["vz"]
    x, y, z = t["x"], t["y"], t["z"]
    wz = t["wz"]
    maxVy = max(abs(v) for v in vy)
    maxDx = max(abs(xi - p["x0"]) for xi in x)/D
    maxDy = max(abs(yi - p["y0"]) for yi in y)/D
    maxDz = max(abs(zi - p.get("z0", zi)) for zi in z)/D if p["shape"] == "sphere" else 0.0
    speed = [math.sqrt(u*u + v*v + w*w) for u, v, w in zip(vx, vy, vz)]
    iMax = max(range(len(speed)), key=lambda i: speed[i])
    ratio = wz[-1]/omegaExpected

    print("case %s: body %s (%s), D %g m, H %g m, Uw %g m/s, shear rate 2 Uw/H = %g 1/s; "
          "%d rows, t %g to %g s" % (a.case, body, p["shape"], D, H, Uw, shear, len(t), time[0], time[-1]))
    print("largest |vy|: %.4g m/s (%.4g Uw)" % (maxVy, maxVy/Uw))
    print("largest |x - x0|/D: %.4g, largest |y - y0|/D: %.4g, largest |z - z0|/D: %.4g (x0 %g, y0 %g m)"
          % (maxDx, maxDy, maxDz, p["x0"], p["y0"]))
    print("final omega_z: %.6g rad/s at t %g s; expected -shear/2 = -Uw/H = %.6g rad/s "
          "(clockwise: the fluid's vorticity is -du/dy = %.6g 1/s); ratio %.4f"
          % (wz[-1], time[-1], omegaExpected, -shear, ratio))
    if p["shape"] == "ellipse":
        A, B = p["a"], p["b"]
        # the orientation from the integral of omega_z (at rest, phi = 0, at t = 0)
        phi, tPrev, wPrev = 0.0, 0.0, 0.0
        for ti, wi in zip(time, wz):
            phi += 0.5*(wi + wPrev)*(ti - tPrev)
            tPrev, wPrev = ti, wi
        jeffery = -shear*(A*A*math.sin(phi)**2 + B*B*math.cos(phi)**2)/(A*A + B*B)
        mean = -shear*A*B/(A*A + B*B)
        print("ellipse (a %g, b %g m): major axis at %.4g deg from x at the end; Jeffery's rate there "
              "%.6g rad/s (final omega_z over it %.4f), its period mean %.6g rad/s"
              % (A, B, math.degrees(phi), jeffery, wz[-1]/jeffery, mean))
    print("largest body speed: %.4g m/s (%.4g Uw) at t %g s" % (speed[iMax], speed[iMax]/Uw, time[iMax]))
    print("couette: maxSpeed/Uw %.4g, maxDisp/D %.4g, omega/omegaExpected %.4g"
          % (speed[iMax]/Uw, max(maxDx, maxDy, maxDz), ratio))
    sys.exit(0)


if __name__ == "__main__":
    main()
