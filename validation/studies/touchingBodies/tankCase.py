"""The files of a small water tank case shared by the dense-suspension case
tests (makeCase.py, also for validation/studies/lubricationSpheres) and
the coupled scale benchmark (validation/benchmarks/settlingLattice/
makeLattice.py): a box of wall patches (noSlip, one patch 'walls'; or
periodic in all three directions), cubic cells, laminar pimpleFoam with the immersedBoundaryForce
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


def writeTank(write, lo, hi, n, scale, nu, fvOptionEntries="", periodic=False, g="0 0 -9.81"):
    """0/U, 0/p, g, transport and turbulence properties, fvOptions and the
    blockMeshDict of the box [lo, hi] (in units of scale m) with n cells;
    periodic: cyclic patches in all three directions instead of walls"""
    wallsU, wallsP = ('".*" { type cyclic; }', '".*" { type cyclic; }') if periodic \
        else ("walls { type noSlip; }", "walls { type zeroGradient; }")
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
          (periodicBoundary if periodic else
           "boundary ( walls { type wall; faces ( (0 4 7 3) (1 2 6 5) (0 1 5 4) (3 7 6 2)"
           " (0 3 2 1) (4 5 6 7) ); } );\n"))


# The box's faces as three cyclic pairs
periodicBoundary = """boundary
(
    x0 { type cyclic; neighbourPatch x1; faces ((0 4 7 3)); }
    x1 { type cyclic; neighbourPatch x0; faces ((1 2 6 5)); }
    y0 { type cyclic; neighbourPatch y1; faces ((0 1 5 4)); }
    y1 { type cyclic; neighbourPatch y0; faces ((2 3 7 6)); }
    z0 { type cyclic; neighbourPatch z1; faces ((0 3 2 1)); }
    z1 { type cyclic; neighbourPatch z0; faces ((4 5 6 7)); }
);
"""


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
