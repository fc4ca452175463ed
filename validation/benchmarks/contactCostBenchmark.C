/*---------------------------------------------------------------------------*\
Application
    contactCostBenchmark

Description
    Thin contacts and the cost per contact of the virtual mesh (issue 19):

    1. The sliver table: two 10 mm cubes, one sliding over the other's top
       face (footprint 8 x 6.5 mm), at depths 0 and 1e-2 .. 1e-5 of the
       size, at the default cellSize (1/20 of the volume-equivalent
       diameter) and level 4: virtualMesh against the exact engine (CGAL
       intersection solid), with the edges bevelled by the closest point's
       tangent plane (facetedEdges false, the former leaves) and with the
       meshes' triangles integrated exactly where the surface in a leaf is
       not one smooth sheet (facetedEdges true, the default).

    2. The cost per contact, both ways side by side in one run (alternating
       evaluations, the median of each): spheres (analytic), STL
       icospheres, cubes face on face, a turned cube edge-first into a
       cube, two tori. Prints the seconds per contact and the ratio
       faceted/bevelled.

    A benchmark, not a test: it checks nothing.

Usage
    contactCostBenchmark [repeats (default 21)]
\*---------------------------------------------------------------------------*/

#include "exactOverlap.H"
#include "virtualMeshOverlap.H"
#include "sphereShape.H"
#include "triangleMeshShape.H"
#include "primitiveMeshes.H"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

using namespace immersedDEM;

namespace
{

double seconds(const std::chrono::steady_clock::time_point& t0)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double median(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    return v[v.size()/2];
}

struct pairCase
{
    const char* name;
    const shape* A;
    bodyPose pA;
    const shape* B;
    bodyPose pB;
    double h;
};

} // End anonymous namespace


int main(int argc, char* argv[])
{
    const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 21;
    const virtualMeshOverlap vm;

    // 1. Slivers
    const double a = 0.005, sx = 0.002, sy = 0.0035;
    const triangleMeshShape cubeA(primitiveMeshes::box(vec3::Constant(a)), "A");
    const triangleMeshShape cubeB(primitiveMeshes::box(vec3::Constant(a)), "B");
    const double h = overlapSettings::defaultCellSize(std::cbrt(6/M_PI*cubeA.volume()));
    std::printf("Slivers: 10 mm cubes face on face, footprint 52 mm2, cellSize %.4g m, level 4\n", h);
    std::printf("%10s %13s %13s %13s %13s\n", "depth/size", "exact [m3]", "bevelled", "faceted", "");
    std::printf("%10s %13s %13s %13s\n", "", "", "(vm/ex - 1)", "(vm/ex - 1)");
    for (const double rel : {0.0, 1e-5, 1e-4, 1e-3, 1e-2})
    {
        const double d = rel*2*a;
        const bodyPose pA = cubeA.poseFromFilePlacement(quat::Identity(), vec3::Zero());
        const bodyPose pB = cubeB.poseFromFilePlacement(quat::Identity(), vec3(sx, sy, 2*a - d));
        const double ex = exactOverlap().evaluate(cubeA, pA, cubeB, pB, {}).volume();
        overlapSettings off{h, 4}, on{h, 4};
        off.facetedEdges = false;
        const double vOff = vm.evaluate(cubeA, pA, cubeB, pB, off).volume();
        const double vOn = vm.evaluate(cubeA, pA, cubeB, pB, on).volume();
        if (ex > 0)
        {
            std::printf("%10.0e %13.5e %+13.3e %+13.3e\n", rel, ex, vOff/ex - 1, vOn/ex - 1);
        }
        else
        {
            std::printf("%10.0e %13.5e %13.3e %13.3e   (volumes, m3)\n", rel, ex, vOff, vOn);
        }
    }

    // 2. Cost per contact
    const double R = 0.005;
    const sphereShape sphere(R);
    const triangleMeshShape ico(primitiveMeshes::icosphere(R, 4), "icosphere");
    const triangleMeshShape torus(primitiveMeshes::torus(0.004, 0.0015, 64, 32), "torus");
    const vec3 axis = vec3(1, 2, 3).normalized();
    const vec3 c0(0.0013, 0.0021, 0.0007);
    const double hS = overlapSettings::defaultCellSize(2*R);
    std::vector<pairCase> cases;
    cases.push_back
    ({
        "spheres 2%", &sphere, bodyPose(c0, quat::Identity()), &sphere,
        bodyPose(c0 + 0.98*2*R*axis, quat::Identity()), hS
    });
    cases.push_back
    ({
        "icospheres 2%", &ico, ico.poseFromFilePlacement(quat::Identity(), c0), &ico,
        ico.poseFromFilePlacement(quat::Identity(), c0 + 0.98*2*R*axis), hS
    });
    cases.push_back
    ({
        "cubes face on face 1e-3", &cubeA, cubeA.poseFromFilePlacement(quat::Identity(), vec3::Zero()),
        &cubeB, cubeB.poseFromFilePlacement(quat::Identity(), vec3(sx, sy, 2*a - 1e-3*2*a)), h
    });
    {
        const quat q = bodyPose::axisAngle(vec3(0, 0, 1), 0.4)*bodyPose::axisAngle(vec3(1, 0, 0), M_PI/4);
        const bodyPose p0 = cubeB.poseFromFilePlacement(q, vec3::Zero());
        double zLow = 1;
        for (const vec3& x : cubeB.surface().points) zLow = std::min(zLow, p0.toWorld(x).z());
        cases.push_back
        ({
            "cube edge into cube 0.3 mm", &cubeA, cubeA.poseFromFilePlacement(quat::Identity(), vec3::Zero()),
            &cubeB, cubeB.poseFromFilePlacement(q, vec3(0.0007, 0.0004, a - 0.0003 - zLow)), h
        });
    }
    cases.push_back
    ({
        "tori crossing", &torus, torus.poseFromFilePlacement(quat::Identity(), vec3::Zero()),
        &torus, torus.poseFromFilePlacement
        (
            bodyPose::axisAngle(vec3(1, 0, 0), M_PI/2), vec3(0.0004, 0.0001, 0.00013)
        ), overlapSettings::defaultCellSize(0.003)
    });

    std::printf("\nCost per contact (median of %d, alternating), level 4\n", repeats);
    std::printf("%-28s %12s %12s %8s %12s %12s\n",
        "pair", "bevelled [s]", "faceted [s]", "ratio", "V bevelled", "V faceted");
    for (const pairCase& pc : cases)
    {
        overlapSettings off{pc.h, 4}, on{pc.h, 4};
        off.facetedEdges = false;
        std::vector<double> tOff, tOn;
        double vOff = 0, vOn = 0;
        for (int r = 0; r < repeats; ++r)
        {
            auto t0 = std::chrono::steady_clock::now();
            vOff = vm.evaluate(*pc.A, pc.pA, *pc.B, pc.pB, off).volume();
            tOff.push_back(seconds(t0));
            t0 = std::chrono::steady_clock::now();
            vOn = vm.evaluate(*pc.A, pc.pA, *pc.B, pc.pB, on).volume();
            tOn.push_back(seconds(t0));
        }
        std::printf("%-28s %12.4e %12.4e %8.3f %12.5e %12.5e\n",
            pc.name, median(tOff), median(tOn), median(tOn)/median(tOff), vOff, vOn);
    }
    return 0;
}
