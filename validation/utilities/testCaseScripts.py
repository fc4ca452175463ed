"""immersedDEMCase and the templates' check scripts read the physical
constants from the case they check: the reader against the templates'
dictionaries, plotPile against a settlingPile case whose constants are
changed (its terminal velocities must follow) and whose bodies.dat has a
body outside the tank at one written time only (it must be found). Exit 1
on any failure."""
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

here = os.path.dirname(os.path.abspath(__file__))
project = os.path.abspath(os.path.join(here, "..", ".."))
# The scripts run as in a user's shell that sourced src/etc/bashrc, which
# sets IMMERSEDDEM_DIR (they find the project's Python modules from it)
runEnv = dict(os.environ, IMMERSEDDEM_DIR=project)
pyDir = os.path.join(project, "src", "python")
sys.path.insert(0, pyDir)
from immersedDEMCase import caseConstants, readDictionary, dictionaryError  # noqa: E402

fails = []


def check(what, ok, detail=""):
    print(("PASS: " if ok else "FAIL: ") + what + (" (" + detail + ")" if detail else ""))
    if not ok:
        fails.append(what)


# The reader on the templates' own dictionaries
pile = os.path.join(project, "caseTemplates", "settlingPile")
c = caseConstants(pile)
check("settlingPile: rhoInf, nu, g and the tank from its dictionaries",
      (c.rhoFluid, c.nu, c.g, c.meshBounds())
      == (1000.0, 1e-6, (0.0, 0.0, -9.81), ((-0.02, -0.02, 0.0), (0.02, 0.02, 0.08))))
check("settlingPile: densities of named bodies ($cubeA merged) and inserted ones",
      [c.density(n) for n in ("cubeA", "cubeB", "discA", "cubes_3", "blocks_0")] == [2500.0]*5
      and c.bodyEntry("cubeB")["position"] == ["0.005", "-0.008", "0.005"])
try:
    c.density("spheres_1")
    check("a body no entry makes is an error naming it", False)
except dictionaryError as e:
    check("a body no entry makes is an error naming it", "spheres_1" in str(e))
bed = caseConstants(os.path.join(project, "caseTemplates", "packedBed"))
check("packedBed: #include and $ in the controlDict and blockMeshDict",
      bed.rhoFluid == 1000.0 and bed.meshBounds()[1][2] > 0,
      "%s" % (bed.meshBounds(),))
work = tempfile.mkdtemp(prefix="immersedDEMCase-")
d = os.path.join(work, "d")
with open(d, "w") as f:
    f.write("a { x 1; y (1 2 3); } // note\n/* block */ b { $a; x 2; }\nnu [0 2 -1 0 0 0 0] 1e-5;\n")
t = readDictionary(d)
check("comments, $ merge and override, dimensioned scalar",
      t["b"] == {"x": "2", "y": ["1", "2", "3"]} and t["nu"][-1] == "1e-5")

# plotPile on a case with other constants: fluid 1200 kg/m3, nu 2e-6,
# g 5 m/s2, the cubes' template 3000 kg/m3
case = os.path.join(work, "pile")
shutil.copytree(pile, case)


def edit(rel, pattern, repl):
    p = os.path.join(case, rel)
    s = open(p).read()
    s2 = re.sub(pattern, repl, s, count=1)
    assert s2 != s, (rel, pattern)
    open(p, "w").write(s2)


edit("system/controlDict", r"rhoInf\s+1000;", "rhoInf 1200;")
edit("constant/transportProperties", r"nu\s+1e-06;", "nu 2e-06;")
edit("constant/g", r"\(0 0 -9\.81\)", "(0 0 -5)")
edit("constant/immersedDEMProperties", r"(cube\s*\{[^}]*?density\s+)2500", r"\g<1>3000")
os.makedirs(os.path.join(case, "constant", "triSurface"), exist_ok=True)
prism = os.path.join(pyDir, "immersedDEMPrism")
for stl, a in (("cube.stl", ["14.1421356", "10", "4"]), ("disc.stl", ["10", "5", "24"])):
    subprocess.run(env=runEnv, args=[sys.executable, prism, os.path.join(case, "constant", "triSurface", stl)] + a,
                   check=True, capture_output=True)
# -help prints the usage and writes nothing (it once wrote an STL named -help)
r = subprocess.run(env=runEnv, args=[sys.executable, prism, "-help"], cwd=case, capture_output=True, text=True)
check("immersedDEMPrism -help prints its usage and writes no file",
      r.returncode == 0 and "Usage: immersedDEMPrism out.stl" in r.stdout
      and not os.path.exists(os.path.join(case, "-help")))
shutil.copy(os.path.join(project, "caseTemplates", "quickStart", "constant", "triSurface", "block.stl"),
            os.path.join(case, "constant", "triSurface"))
out = os.path.join(case, "postProcessing", "pile", "0")
os.makedirs(out)
# cubes_0 leaves the tank's top (z 0.085 > 0.08) at t = 0.02 only; every
# body is at rest at the end (settled) and slower than its terminal velocity
with open(os.path.join(out, "bodies.dat"), "w") as f:
    f.write("# time body x y z vx vy vz\n")
    for i in range(5):
        t = 0.01*i
        v = 0.05 if i < 4 else 0.0
        f.write("%g cubes_0 0 0 %g 0 0 %g\n" % (t, 0.085 if i == 2 else 0.04, v))
        f.write("%g discs_0 0.01 0 0.03 0 0 %g\n" % (t, v))
r = subprocess.run(env=runEnv, args=[sys.executable, os.path.join(case, "plotPile"), "-case", case, "-noplot"],
                   capture_output=True, text=True)
print(r.stdout + r.stderr)
check("plotPile prints the case's constants",
      "fluid 1200 kg/m3, nu 2e-06 m2/s, g 5 m/s2" in r.stdout and "to (0.02 0.02 0.08)" in r.stdout)
check("plotPile finds a body outside the tank at one written time, inside at the end",
      r.returncode == 1 and "bodies outside the tank: cubes_0 (at 1 written times from t = 0.02 s)" in r.stdout
      and "discs_0" not in r.stdout.split("bodies outside the tank:")[-1])


def terminalOf(text, body):
    for line in text.splitlines():
        w = line.split()
        if w and w[0] == body:
            return float(w[3])
    return float("nan")


# The same run with the template's constants: the terminal velocities must
# differ, and the cube's ratio to the disc's follow the densities
ref = os.path.join(work, "pileRef")
shutil.copytree(pile, ref)
shutil.copytree(os.path.join(case, "constant", "triSurface"), os.path.join(ref, "constant", "triSurface"))
shutil.copytree(os.path.join(case, "postProcessing"), os.path.join(ref, "postProcessing"))
r0 = subprocess.run(env=runEnv, args=[sys.executable, os.path.join(ref, "plotPile"), "-case", ref, "-noplot"],
                    capture_output=True, text=True)
u, u0 = terminalOf(r.stdout, "cubes_0"), terminalOf(r0.stdout, "cubes_0")
ud, ud0 = terminalOf(r.stdout, "discs_0"), terminalOf(r0.stdout, "discs_0")
check("terminal velocities follow the case's constants (cube, disc: changed case against the template)",
      all(math.isfinite(x) for x in (u, u0, ud, ud0)) and abs(u/u0 - 1) > 0.05 and abs(ud/ud0 - 1) > 0.05
      and "fluid 1000 kg/m3, nu 1e-06 m2/s, g 9.81 m/s2" in r0.stdout,
      "cube %.4g against %.4g m/s, disc %.4g against %.4g m/s" % (u, u0, ud, ud0))

shutil.rmtree(work, ignore_errors=True)
print("%d failed" % len(fails))
sys.exit(1 if fails else 0)
