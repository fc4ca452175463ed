#!/bin/bash
# makeCase.sh <dir> <phi> <L> [-n N] [-endTime T] [-seed S] [-shape sphere|cube]
# A triply periodic box of L diameters (caseTemplates/periodicSphereArray,
# N cells per diameter, default 8) holding spheres of diameter 1 m and
# density ratio 2 at volume fraction phi (0: one sphere at the centre), in
# a fluid of nu 0.0875 m2/s with g 1 m/s2 along -z: a terminal Reynolds
# number of about 5 for the isolated sphere. Stock pimpleFoam (backward,
# two outer correctors, maxCo 0.5); the fvOption's default drive holds
# the mean velocity at zero (the frame of a closed container).
# -shape cube: cubes of the sphere's volume (side (pi/6)^(1/3) m, random
# orientations; the single cube face down), the same number at the same phi.
set -eu
here="$(cd "$(dirname "$0")" && pwd -P)"
project="$(cd "$here/../../.." && pwd -P)"
dir="$1"; phi="$2"; L="$3"; shift 3
n=8; endTime=60; seed=1; shape=sphere
while [ $# -gt 0 ]
do
    case "$1" in
        -n) n="$2"; shift 2 ;;
        -endTime) endTime="$2"; shift 2 ;;
        -seed) seed="$2"; shift 2 ;;
        -shape) shape="$2"; shift 2 ;;
        *) echo "Unknown option $1" 1>&2; exit 1 ;;
    esac
done
rm -rf "$dir"
mkdir -p "$(dirname "$dir")"
cp -r "$project/caseTemplates/periodicSphereArray" "$dir"
cd "$dir"
./Allclean > /dev/null 2>&1 || true
cells=$(python3 -c "print(int(round($L*$n)))")
# (sed, not foamDictionary: rewriting the file, foamDictionary would
# expand the vertices' $L and the blocks' $N with the old values)
sed -i -e "s/^L .*/L       $L;/" -e "s/^N .*/N       $cells;/" system/blockMeshDict
foamDictionary -entry drive -remove constant/fvOptions > /dev/null
foamDictionary -entry nu -set 0.0875 constant/transportProperties > /dev/null
foamDictionary -entry ddtSchemes.default -set backward system/fvSchemes > /dev/null
foamDictionary -entry PIMPLE.nOuterCorrectors -set 2 system/fvSolution > /dev/null
foamDictionary -entry endTime -set "$endTime" system/controlDict > /dev/null
foamDictionary -entry writeInterval -set 10 system/controlDict > /dev/null
foamDictionary -entry adjustTimeStep -set yes system/controlDict > /dev/null
foamDictionary -entry maxCo -set 0.5 system/controlDict > /dev/null
foamDictionary -entry maxDeltaT -set 0.1 system/controlDict > /dev/null
foamDictionary -entry deltaT -set 0.01 system/controlDict > /dev/null
foamDictionary -entry functions.sphere.rhoInf -set 1 system/controlDict > /dev/null
cat > constant/g <<'DICT'
FoamFile { version 2.0; format ascii; class uniformDimensionedVectorField; object g; }
dimensions [0 1 -2 0 0 0 0];
value (0 0 -1);
DICT
case "$shape" in
    sphere) body="shape sphere; radius 0.5;" ;;
    cube)
        # the cube of the unit sphere's volume, centred on the origin, as
        # an ASCII STL (12 triangles, outward normals)
        mkdir -p constant/triSurface
        python3 - > constant/triSurface/cube.stl <<'PY'
import math
h = 0.5*(math.pi/6)**(1.0/3)
print("solid cube")
for axis in range(3):
    for sign in (-1, 1):
        u, v = (axis + 1) % 3, (axis + 2) % 3
        if sign < 0:
            u, v = v, u
        def p(a, b):
            x = [0.0, 0.0, 0.0]
            x[axis] = sign*h; x[u] = a*h; x[v] = b*h
            return x
        for tri in ((p(-1, -1), p(1, -1), p(1, 1)), (p(-1, -1), p(1, 1), p(-1, 1))):
            n = [0.0, 0.0, 0.0]; n[axis] = sign
            print(" facet normal %g %g %g\n  outer loop" % tuple(n))
            for x in tri:
                print("   vertex %.12g %.12g %.12g" % tuple(x))
            print("  endloop\n endfacet")
print("endsolid cube")
PY
        body="shape triangleMesh; file \"cube.stl\"; orientation random;" ;;
    *) echo "Unknown shape $shape (sphere or cube)" 1>&2; exit 1 ;;
esac
if python3 -c "import sys; sys.exit(0 if float('$phi') > 0 else 1)"
then
    number=$(python3 -c "import math; print(int(round($phi*$L**3/(math.pi/6))))")
    # (the box grown by a radius: centres anywhere in it, none kept from
    # a layer a radius deep at the periodic boundaries)
    Lr=$(python3 -c "print($L + 0.5)")
    bodies="templates
{
    ball { $body material glass; density 2; }
}
insertion
{
    s
    {
        template    ball;
        region      { type box; min (-0.5 -0.5 -0.5); max ($Lr $Lr $Lr); }
        number      $number;
        seed        $seed;
    }
}"
else
    c=$(python3 -c "print(0.5*$L)")
    body="${body/ orientation random;/}"
    bodies="bodies { s_0 { $body material glass; density 2; position ($c $c $c); } }"
fi
cat > constant/immersedDEMProperties <<DICT
FoamFile { version 2.0; format ascii; class dictionary; object immersedDEMProperties; }
materials { glass { youngsModulus 1e7; poissonsRatio 0.25; restitution 0.9; friction 0.1; } }
$bodies
DICT
printf 'phi %s\nL %s\ncellsPerDiameter %s\nseed %s\nshape %s\n' "$phi" "$L" "$n" "$seed" "$shape" > caseParameters
