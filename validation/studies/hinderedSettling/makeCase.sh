#!/bin/bash
# makeCase.sh <dir> <phi> <L> [-n N] [-endTime T] [-seed S]
# A triply periodic box of L diameters (caseTemplates/periodicSphereArray,
# N cells per diameter, default 8) holding spheres of diameter 1 m and
# density ratio 2 at volume fraction phi (0: one sphere at the centre), in
# a fluid of nu 0.0875 m2/s with g 1 m/s2 along -z: a terminal Reynolds
# number of about 5 for the isolated sphere. Stock pimpleFoam (backward,
# two outer correctors, maxCo 0.5); the fvOption's default drive holds
# the mean velocity at zero (the frame of a closed container).
set -eu
here="$(cd "$(dirname "$0")" && pwd -P)"
project="$(cd "$here/../../.." && pwd -P)"
dir="$1"; phi="$2"; L="$3"; shift 3
n=8; endTime=60; seed=1
while [ $# -gt 0 ]
do
    case "$1" in
        -n) n="$2"; shift 2 ;;
        -endTime) endTime="$2"; shift 2 ;;
        -seed) seed="$2"; shift 2 ;;
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
if python3 -c "import sys; sys.exit(0 if float('$phi') > 0 else 1)"
then
    number=$(python3 -c "import math; print(int(round($phi*$L**3/(math.pi/6))))")
    # (the box grown by a radius: centres anywhere in it, none kept from
    # a layer a radius deep at the periodic boundaries)
    Lr=$(python3 -c "print($L + 0.5)")
    bodies="templates
{
    ball { shape sphere; radius 0.5; material glass; density 2; }
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
    bodies="bodies { s_0 { shape sphere; radius 0.5; material glass; density 2; position ($c $c $c); } }"
fi
cat > constant/immersedDEMProperties <<DICT
FoamFile { version 2.0; format ascii; class dictionary; object immersedDEMProperties; }
materials { glass { youngsModulus 1e7; poissonsRatio 0.25; restitution 0.9; friction 0.1; } }
$bodies
DICT
printf 'phi %s\nL %s\ncellsPerDiameter %s\nseed %s\n' "$phi" "$L" "$n" "$seed" > caseParameters
