"""Correlations for packed, fluidised and settling beds, and the pressure
taps of the bed templates (caseTemplates/packedBed, fluidisedBed).

Every function takes SI units. Sources:
- Ergun (1952), Chem. Eng. Prog. 48, 89: the pressure gradient of a
  packed bed, dp/L = 150 mu u (1-eps)^2/(eps^3 d^2) + 1.75 rho u^2 (1-eps)/(eps^3 d),
  and with Mehta & Hawley's (1969) wall factor M = 1 + 2 d/(3 D (1-eps))
  on the specific surface.
- Eisfeld & Schnitzlein (2001), Chem. Eng. Sci. 56, 4321: Ergun's form
  refitted with the wall on measured drops of spheres and cylinders
  (their range: D/d from 1.6, Re 0.01-17,635, porosity 0.33-0.88),
  psi = dp/L d/(rho u^2) = K1 A^2/Re (1-eps)^2/eps^3 + A/B (1-eps)/eps^3,
  Re = rho u d/mu, A = 1 + 2/(3 (D/d)(1-eps)), B = (k1 (d/D)^2 + k2)^2;
  spheres K1 154, k1 1.15, k2 0.87; all shapes together 155, 1.42, 0.83
  (constants as transcribed from the paper in the open-source correlation
  collection nikitin-pro/whr-optimization-framework, models_pressure_drop.py).
- Benyahia & O'Neill (2005), Part. Sci. Technol. 23, 169: the mean porosity
  of a packed tube against D/d, spheres eps = 0.390 + 1.740/(D/d + 1.140)^2
  (mean error 1.5%, D/d 1.5-50), solid cylinders eps = 0.373 + 1.703/
  (D/d_pe + 0.611)^2 (d_pe the volume-equivalent diameter; 1.6%, 1.7-26.3)
  (as given in the fluids library, CalebBell/fluids, packed_bed.py).
- Wen & Yu (1966), AIChE Symp. Ser. 62, 100: Re_mf = sqrt(33.7^2 + 0.0408 Ar) - 33.7.
- Haider & Levenspiel (1989), Powder Technol. 58, 63: the drag of
  spheres and non-spherical bodies against Re and sphericity.
- Richardson & Zaki (1954), Trans. Inst. Chem. Eng. 32, 35: u/u_i = eps^n,
  log10 u_i = log10 u_t - d/D, n = 4.65 + 19.5 d/D (Re_t < 0.2),
  (4.35 + 17.5 d/D) Re_t^-0.03 (0.2-1), (4.45 + 18 d/D) Re_t^-0.1 (1-200),
  4.45 Re_t^-0.1 (200-500), 2.39 (above).
- Garside & Al-Dibouni (1977), Ind. Eng. Chem. Process Des. Dev. 16, 206:
  (5.1 - n)/(n - 2.7) = 0.1 Re_t^0.9 (unbounded suspensions).
"""
import glob
import math
import os


def bisect(f, lo, hi, steps=200):
    """The root of an increasing f between lo and hi."""
    for _ in range(steps):
        mid = 0.5*(lo + hi)
        lo, hi = (mid, hi) if f(mid) < 0 else (lo, mid)
    return 0.5*(lo + hi)


def ergun(mu, rho, u, eps, d, D=None):
    """Ergun's pressure gradient [Pa/m]; with the column's hydraulic
    diameter D, Mehta & Hawley's wall factor on the specific surface."""
    M = 1 + 2*d/(3*D*(1 - eps)) if D else 1.0
    return (150*mu*u*(1 - eps)**2*M**2/(eps**3*d**2)
            + 1.75*rho*u*u*(1 - eps)*M/(eps**3*d))


def eisfeldSchnitzlein(mu, rho, u, eps, d, D, shape="sphere"):
    """Eisfeld & Schnitzlein's (2001) wall-corrected pressure gradient
    [Pa/m]; shape "sphere" or "any" (their fit over spheres and cylinders
    together), d the particle's (Sauter) diameter, D the tube's."""
    K1, k1, k2 = {"sphere": (154.0, 1.15, 0.87), "any": (155.0, 1.42, 0.83)}[shape]
    A = 1 + 2/(3*(D/d)*(1 - eps))
    B = (k1*(d/D)**2 + k2)**2
    Re = rho*u*d/mu
    psi = K1*A*A/Re*(1 - eps)**2/eps**3 + A/B*(1 - eps)/eps**3
    return psi*rho*u*u/d


def benyahiaONeillPorosity(DOverD, shape="sphere"):
    """Benyahia & O'Neill's (2005) mean porosity of a bed in a tube of D/d
    (spheres), or D/d_pe (solid cylinders, shape "cylinder")."""
    if shape == "sphere":
        return 0.390 + 1.740/(DOverD + 1.140)**2
    return 0.373 + 1.703/(DOverD + 0.611)**2


def buoyantWeightGradient(rho, rhoP, g, eps):
    """The bed's buoyant weight per volume of bed [Pa/m]."""
    return (1 - eps)*(rhoP - rho)*g


def ergunMinimumFluidisation(mu, rho, rhoP, g, eps, d, D=None):
    """The superficial velocity at which Ergun's gradient carries the bed's
    buoyant weight."""
    w = buoyantWeightGradient(rho, rhoP, g, eps)
    return bisect(lambda u: ergun(mu, rho, u, eps, d, D) - w, 0.0, 100.0)


def archimedes(mu, rho, rhoP, g, d):
    return rho*(rhoP - rho)*g*d**3/mu**2


def wenYuMinimumFluidisation(mu, rho, rhoP, g, d):
    ar = archimedes(mu, rho, rhoP, g, d)
    return (math.sqrt(33.7**2 + 0.0408*ar) - 33.7)*mu/(rho*d)


def surfaceVolumeArea(path, scale=1.0):
    """Volume and area of a closed ASCII STL (divergence theorem), its
    coordinates times scale. Raises ValueError if it is not a triangle
    surface, OSError if it cannot be read."""
    with open(path) as f:
        pts = [tuple(float(x) for x in l.split()[1:4]) for l in f if l.strip().startswith("vertex")]
    if len(pts) % 3 or not pts:
        raise ValueError("%s is not an ASCII triangle surface" % path)
    V = A = 0.0
    for i in range(0, len(pts), 3):
        a, b, c = pts[i:i + 3]
        ab = [b[k] - a[k] for k in range(3)]
        ac = [c[k] - a[k] for k in range(3)]
        n = (ab[1]*ac[2] - ab[2]*ac[1], ab[2]*ac[0] - ab[0]*ac[2], ab[0]*ac[1] - ab[1]*ac[0])
        A += 0.5*math.sqrt(sum(x*x for x in n))
        V += sum(a[k]*n[k] for k in range(3))/6.0
    return abs(V)*scale**3, A*scale**2


def terminalVelocity(V, A, rhoP, rhoF, nu, g):
    """A body's terminal velocity in an unbounded fluid from Haider &
    Levenspiel's (1989) drag C_D(Re, phi) (Powder Technol. 58, 63), Re on
    the volume-equivalent diameter d, phi = pi d^2/A the sphericity (1 for
    a sphere): (rho_p - rho_f) g V = C_D rho_f U^2 pi d^2/8. Returns
    (U, d, phi)."""
    d = (6*V/math.pi)**(1.0/3)
    phi = min(1.0, math.pi*d*d/A)
    a = math.exp(2.3288 - 6.4581*phi + 2.4486*phi**2)
    b = 0.0964 + 0.5565*phi
    c = math.exp(4.905 - 13.8944*phi + 18.4222*phi**2 - 10.2599*phi**3)
    e = math.exp(1.4681 + 12.2584*phi - 20.7322*phi**2 + 15.8855*phi**3)

    def excess(U):
        Re = U*d/nu
        cd = 24/Re*(1 + a*Re**b) + c/(1 + e/Re)
        return cd*rhoF*U*U*math.pi*d*d/8 - (rhoP - rhoF)*g*V
    return bisect(excess, 1e-12, 100.0), d, phi


def schillerNaumannTerminalVelocity(nu, densityRatio, g, d):
    """A sphere's terminal velocity in an unbounded fluid by Schiller &
    Naumann's standard drag, C_D = 24/Re (1 + 0.15 Re^0.687) (Re < 800)."""
    def excess(U):
        re = U*d/nu
        return 3*math.pi*nu*d*U*(1 + 0.15*re**0.687) - (densityRatio - 1)*g*math.pi/6*d**3
    return bisect(excess, 1e-12, 100.0)


def richardsonZaki(ret, dOverD):
    """Richardson & Zaki's exponent n and the wall factor u_i/u_t."""
    if ret < 0.2:
        n = 4.65 + 19.5*dOverD
    elif ret < 1:
        n = (4.35 + 17.5*dOverD)*ret**-0.03
    elif ret < 200:
        n = (4.45 + 18*dOverD)*ret**-0.1
    elif ret < 500:
        n = 4.45*ret**-0.1
    else:
        n = 2.39
    return n, 10**(-dOverD)


def garsideAlDibouni(ret):
    """Garside & Al-Dibouni's exponent n at the terminal Reynolds number."""
    c = 0.1*ret**0.9
    return (5.1 + 2.7*c)/(1 + c)


def readTaps(case, offset=0.25e-3):
    """{z [m]: (times, p)} of a bed template's pressure taps: the planes
    postProcessing/p_z<mm>/ (at <mm> + 0.25 mm) and the inlet pInlet (z 0),
    from every run's surfaceFieldValue.dat (later runs win where they
    overlap; offset: the planes' height above <mm>). p is the kinematic
    pressure [m2/s2]."""
    taps = {}
    for d in glob.glob(os.path.join(case, "postProcessing", "p_z*")) \
            + glob.glob(os.path.join(case, "postProcessing", "pInlet")):
        name = os.path.basename(d)
        z = 0.0 if name == "pInlet" else int(name[3:])*1e-3 + offset
        rows = []
        for f in sorted(glob.glob(os.path.join(d, "*", "surfaceFieldValue*.dat")),
                        key=lambda f: float(os.path.basename(os.path.dirname(f)))):
            new = []
            for line in open(f):
                w = line.split()
                if w and not line.startswith("#"):
                    new.append((float(w[0]), float(w[1])))
            if new:
                rows = [r for r in rows if r[0] < new[0][0]] + new
        if rows:
            taps[z] = ([r[0] for r in rows], [r[1] for r in rows])
    return taps


def squareDuctFriction(mu, u, D):
    """The laminar pressure gradient of a square duct of side D [Pa/m]
    (f Re = 56.9 on the hydraulic diameter D: dp/L = 56.9 mu u/(2 D^2))."""
    return 56.9*mu*u/(2*D**2)
