"""The files of a small water tank case shared by the dense-suspension case
tests (makeCase.py, also for validation/studies/lubricationSpheres) and
the coupled scale benchmark (validation/benchmarks/settlingLattice/
makeLattice.py): a box of wall patches (noSlip, one patch 'walls'), or
periodic in some or all three directions, cubic cells, laminar pimpleFoam with the immersedBoundaryForce
fvOption and the immersedDEM function object."""
import os


def writer(case):
    """write(path, cls, obj, body): an OpenFOAM dictionary file of the case"""
    for s in ("0", "constant/triSurface", "system"):
        os.makedirs(os.path.join(case, s), exist_ok=True)

    def write(path, cls, obj, body):
        with open(os.path.join(case, path), "w") as f:
            f.write("FoamFile { version 2.0; format ascii; class %s; object %s; }\n\n%s"
                    % (cls, obj, body))
    return write


def writeTank(write, lo, hi, n, scale, nu, fvOptionEntries="", periodic="", g="0 0 -9.81"):
    """0/U, 0/p, g, transport and turbulence properties, fvOptions and the
    blockMeshDict of the box [lo, hi] (in units of scale m) with n cells;
    periodic: the directions ("xyz", "xy", ...; True for all three) whose
    two faces are a cyclic pair; the other faces are the wall patch
    'walls'"""
    periodic = "xyz" if periodic is True else (periodic or "")
    if any(d not in "xyz" for d in periodic):
        raise ValueError("periodic: directions among x, y, z, not %r" % periodic)
    # The box's two faces normal to each direction (hex vertex numbering)
    faces = {"x": ("(0 4 7 3)", "(1 2 6 5)"), "y": ("(0 1 5 4)", "(3 7 6 2)"),
             "z": ("(0 3 2 1)", "(4 5 6 7)")}
    wallFaces = " ".join(f for d in "xyz" if d not in periodic for f in faces[d])
    patches = ["    walls { type wall; faces ( %s ); }" % wallFaces] if wallFaces else []
    for d in "xyz":
        if d in periodic:
            # (the y pair's second face as the runs before this option had it)
            second = "(2 3 7 6)" if d == "y" else faces[d][1]
            patches += ["    %s0 { type cyclic; neighbourPatch %s1; faces (%s); }" % (d, d, faces[d][0]),
                        "    %s1 { type cyclic; neighbourPatch %s0; faces (%s); }" % (d, d, second)]
    cyclic = " ".join('%s%d { type cyclic; }' % (d, k) for d in periodic for k in (0, 1))
    wallsU = " ".join(["walls { type noSlip; }"]*bool(wallFaces) + [cyclic]*bool(cyclic))
    wallsP = " ".join(["walls { type zeroGradient; }"]*bool(wallFaces) + [cyclic]*bool(cyclic))
    write("0/U", "volVectorField", "U", "dimensions [0 1 -1 0 0 0 0];\n"
          "internalField uniform (0 0 0);\nboundaryField { %s }\n" % wallsU)
    write("0/p", "volScalarField", "p", "dimensions [0 2 -2 0 0 0 0];\n"
          "internalField uniform 0;\nboundaryField { %s }\n" % wallsP)
    write("constant/g", "uniformDimensionedVectorField", "g",
          "dimensions [0 1 -2 0 0 0 0];\nvalue (%s);\n" % g)
    write("constant/transportProperties", "dictionary", "transportProperties",
          "transportModel Newtonian;\nnu %s;\n" % nu)
    write("constant/turbulenceProperties", "dictionary", "turbulenceProperties",
          "simulationType laminar;\n")
    write("constant/fvOptions", "dictionary", "fvOptions",
          "bodies { type immersedBoundaryForce; fields (U);%s }\n" % fvOptionEntries)
    corners = [(lo[0], lo[1], lo[2]), (hi[0], lo[1], lo[2]), (hi[0], hi[1], lo[2]), (lo[0], hi[1], lo[2]),
               (lo[0], lo[1], hi[2]), (hi[0], lo[1], hi[2]), (hi[0], hi[1], hi[2]), (lo[0], hi[1], hi[2])]
    write("system/blockMeshDict", "dictionary", "blockMeshDict",
          "scale %g;\nvertices (" % scale + " ".join("(%.9g %.9g %.9g)" % c for c in corners) + ");\n"
          "blocks ( hex (0 1 2 3 4 5 6 7) (%d %d %d) simpleGrading (1 1 1) );\n" % tuple(n) +
          "boundary\n(\n" + "\n".join(patches) + "\n);\n")


def writeSolver(write):
    """fvSchemes and fvSolution (second order, PIMPLE with two correctors)"""
    write("system/fvSchemes", "dictionary", "fvSchemes", """ddtSchemes { default backward; }
gradSchemes { default Gauss linear; }
divSchemes { default none; div(phi,U) Gauss linear; div((nuEff*dev2(T(grad(U))))) Gauss linear; }
laplacianSchemes { default Gauss linear corrected; }
interpolationSchemes { default linear; }
snGradSchemes { default corrected; }
""")
    write("system/fvSolution", "dictionary", "fvSolution", """solvers
{
    p { solver GAMG; smoother GaussSeidel; tolerance 1e-7; relTol 0.01; }
    pFinal { $p; relTol 0; }
    "(U|UFinal)" { solver smoothSolver; smoother symGaussSeidel; tolerance 1e-8; relTol 0; }
}
PIMPLE { momentumPredictor yes; nOuterCorrectors 1; nCorrectors 2; nNonOrthogonalCorrectors 0; pRefCell 0; pRefValue 0; }
""")
