"""immersedDEMOverlap: JSON output against the analytic lens, swap flips the
normal, and bad input exits non-zero with a message. Exit 1 on any failure."""
import json
import math
import subprocess
import sys

exe = sys.argv[1]
failures = []
passed = 0


def check(what, ok):
    global passed
    if ok:
        passed += 1
        print("PASS:", what)
    else:
        failures.append(what)
        print("FAIL:", what)


def run(*args):
    return subprocess.run([exe, *args], capture_output=True, text=True)


R, s = 0.005, 0.0099
pose = [str(v) for v in (s, 0, 0, 0, 0, 1, 0)]
vm = run("-A", "sphere:%g" % R, "-B", "sphere:%g" % R, "-poseB", *pose, "-repeat", "3")
check("virtualMesh exits 0", vm.returncode == 0)
out = json.loads(vm.stdout)
exact = math.pi * (4 * R + s) * (2 * R - s) ** 2 / 12
check("keys", all(k in out for k in ("method", "level", "h", "regions", "volume", "queries", "seconds")))
check("one region", len(out["regions"]) == 1)
# 0.5%: the default contact resolution's tolerance; the normal to 0.26
# degrees (cos = 0.99999), the octree's on an axial lens
check("volume within 0.5%% of the lens (%.4g vs %.4g)" % (out["volume"], exact),
      abs(out["volume"] / exact - 1) < 0.005)
check("normal along +x", out["regions"][0]["normal"][0] > 0.99999)
check("default h = d/20 and level 4", abs(out["h"] - 2 * R / 20) < 1e-15 and out["level"] == 4)

sw = json.loads(run("-A", "sphere:%g" % R, "-poseA", *pose, "-B", "sphere:%g" % R).stdout)
check("swapping A and B flips the normal", sw["regions"][0]["normal"][0] < -0.99999)

an = json.loads(run("-A", "sphere:%g" % R, "-B", "sphere:%g" % R, "-poseB", *pose,
                    "-method", "sphere").stdout)
check("sphere method is the closed form", abs(an["volume"] / exact - 1) < 1e-12)

for args, text in (
    (("-A", "sphere:0.005", "-B", "missing.stl"), "missing.stl"),
    (("-A", "sphere:0.005", "-B", "sphere:0.005", "-method", "octree"), "Unknown overlap method"),
    (("-A", "sphere:-1", "-B", "sphere:0.005"), "radius"),
    (("-A", "sphere:0.005"), "both -A and -B"),
    (("-A", "sphere:0.005", "-B", "sphere:0.005", "-level", "x"), "not a number"),
):
    r = run(*args)
    check("bad input %s -> exit 1 naming '%s'" % (" ".join(args), text),
          r.returncode == 1 and text in r.stderr)

print("%d passed, %d failed" % (passed, len(failures)))
sys.exit(1 if failures else 0)
