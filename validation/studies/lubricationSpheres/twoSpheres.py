#!/usr/bin/env python3
"""The exact Stokes drag of two equal spheres approaching each other along
their line of centres, each at speed U (relative speed 2U): by symmetry
the plane between them carries no normal velocity and no shear stress, so
each sphere moves as a sphere approaching a free plane surface, whose
exact bispherical solution is Brenner's (Chem. Eng. Sci. 16, 242, 1961,
the free-surface case):

  F = 6 pi mu a U lambda,
  lambda = 4/3 sinh(alpha) sum_{n>=1} n(n+1)/((2n-1)(2n+3))
           [ (4 cosh^2((n+1/2) alpha) + (2n+1)^2 sinh^2(alpha))
             / (2 sinh((2n+1) alpha) - (2n+1) sinh(2 alpha)) - 1 ],

alpha = arccosh(z/a), z = a + h/2 the centre's distance from the mid-plane
(h the gap between the spheres). It is X11A - X12A of Jeffrey & Onishi
(J. Fluid Mech. 139, 261, 1984) for equal spheres. Checked here against
both ends, which come from other derivations:
  - far apart (s = r/a, r = 2z): 1 + 3/(2s) + 9/(4s^2) + O(s^-3), the
    method of reflections (the Stokeslet of the other sphere, 3a/(2r) U,
    then its reflection);
  - near contact: a/(2h), the lubrication limit 6 pi mu (a/2)^2 (2U)/h.
Run alone it prints these checks and a table, and exits 1 when a check
fails.
"""
import math
import sys


def approach(gap, a):
    """lambda at gap h = gap between two equal spheres of radius a"""
    alpha = math.acosh(1 + 0.5*gap/a)
    s = 0.0
    for n in range(1, 1000000):
        k = 2*n + 1
        num = 4*math.cosh((n + 0.5)*alpha)**2 + k*k*math.sinh(alpha)**2
        den = 2*math.sinh(k*alpha) - k*math.sinh(2*alpha)
        term = n*(n + 1)/((2*n - 1)*(2*n + 3))*(num/den - 1)
        s += term
        if abs(term) < 1e-13*abs(s) and n > 5:
            break
    return 4.0/3.0*math.sinh(alpha)*s


def selfCheck():
    ok = True
    # The remainder after the first three terms must fall as s^-3: from
    # s = 20 to 40 by about 8 (a wrong first or second term would leave a
    # remainder falling as s^-1 or s^-2: by 2 or 4)
    rest = []
    for s in (20.0, 40.0):
        lam = approach((s - 2), 1.0)
        far = 1 + 1.5/s + 2.25/s**2
        rest.append(lam - far)
        print("r/a %5.1f: lambda %.7f, 1 + 3/(2s) + 9/(4s^2) %.7f" % (s, lam, far))
    good = 6 < rest[0]/rest[1] < 10
    ok = ok and good
    print("the remainder falls by %.2f from r/a 20 to 40 (s^-3: 8) %s" % (rest[0]/rest[1], "ok" if good else "WRONG"))
    for h in (1e-3, 1e-4):
        lam = approach(h, 1.0)
        near = 1/(2*h)
        # the next term is O(ln(1/h)): a relative 1% at h = 1e-3
        good = abs(lam/near - 1) < 0.01
        ok = ok and good
        print("h/a %7.4f: lambda %.3f, a/(2h) %.3f %s" % (h, lam, near, "ok" if good else "WRONG"))
    return ok


if __name__ == "__main__":
    ok = selfCheck()
    for g in (1.0, 0.5, 0.2, 0.1, 0.05):
        print("h/d %5.2f  lambda %8.4f" % (g, approach(2*g, 1.0)))
    sys.exit(0 if ok else 1)
