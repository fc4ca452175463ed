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

    3. Convex pairs: the octree (convexExact off) against the exact convex
       path (convexOverlap, the default for them), side by side
       (alternating; the convex path timed over 100 calls per sample):
       two 20-face icosahedra 0.1 mm deep (B turned, 0.1 mm closer
       along a general direction than at first touch) (at h = d/10 level 3 and at the
       defaults), two 10 mm cubes face on face 0.01 mm deep, a 10 mm cube
       0.01 mm deep in a plane, and on the floor of an open box (a wall
       mesh) 2.8 and 3.6 mm from two sides; the volume errors against the exact engine
       (the plane as a slab mesh).

    4. A wall's rim on the domain's boundary (a channel's walls at its
       outlet): the open box's top rim as an outlet, a 10 mm cube sliding
       0.01 mm deep on a side wall while it crosses the rim (its top 7 mm
       past it), and a sphere the same. The wall as read before (the rim
       is rim: the octree measures it) against the wall continued across
       the rim (immersedDEMPatchSurface marks such edges: exact planes),
       side by side; volumes against the exact overlap with the side's
       half-space (the cube against a slab mesh, CGAL).

    Sections 1 and 2 measure the octree itself (convexExact off: their
    cubes and icospheres are convex).

    A benchmark, not a test: it checks nothing.

Usage
    contactCostBenchmark [repeats (default 21)]
\*---------------------------------------------------------------------------*/

#include "convexOverlap.H"
#include "exactOverlap.H"
#include "halfSpaceShape.H"
#include "wallMeshShape.H"
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
        off.convexExact = on.convexExact = false;
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
        off.convexExact = on.convexExact = false;
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

    // 3. The exact convex path against the octree, side by side
    {
        std::printf("\nConvex pairs: the octree (convexExact no) against the exact convex path"
            " (the default), median of %d alternating runs; volume errors against exact (CGAL)\n", repeats);
        std::printf("%-34s %12s %12s %9s %12s %12s %12s\n",
            "pair", "octree [us]", "convex [us]", "ratio", "V exact", "octree err", "convex err");
        const triangleMeshShape icoA(primitiveMeshes::icosphere(0.005, 0), "icosahedron");
        const double dIco = std::cbrt(6/M_PI*icoA.volume());
        // B turned, pressed 0.1 mm into A along a general direction (the
        // bodies' extents along it overlapping by 0.1 mm)
        const vec3 u = vec3(0.3, -0.5, 0.8).normalized();
        const quat qB = bodyPose::axisAngle(vec3(1, -2, 0.5), 0.9);
        const bodyPose pIA = icoA.poseFromFilePlacement(quat::Identity(), vec3::Zero());
        bodyPose pIB = icoA.poseFromFilePlacement(qB, vec3::Zero());
        {
            // The centre distance at first touch, by bisection on the
            // exact volume, then 0.1 mm closer
            double lo = 0, hi = 0.02;
            for (int k = 0; k < 60; ++k)
            {
                const double mid = 0.5*(lo + hi);
                pIB.setPosition(mid*u);
                (convexOverlap().evaluate(icoA, pIA, icoA, pIB, {}).volume() > 0 ? lo : hi) = mid;
            }
            pIB.setPosition((hi - 1e-4)*u);
        }

        // A 10 mm cube resting face down 0.01 mm deep in a plane, and the
        // same in a slab mesh for the exact engine
        const halfSpaceShape plane;
        triangleSoup slabSoup = primitiveMeshes::box(vec3(0.1, 0.1, 0.05));
        primitiveMeshes::transform(slabSoup, mat3::Identity(), vec3(0, 0, -0.05));
        const triangleMeshShape slab(slabSoup, "slab");
        const bodyPose onPlane = cubeB.poseFromFilePlacement(quat::Identity(), vec3(0.0013, 0.0021, a - 1e-5));
        // The floor of an open box (100 mm, 10 x 10 squares per side) as
        // a wall mesh: the same cube on it near a corner (the sides within
        // its reach, not crossed)
        const wallMeshShape tank
        (
            primitiveMeshes::openBox(vec3(-0.0065, -0.0065, 0), vec3(0.0935, 0.0935, 0.1), 10), "tank", 0.02
        );

        struct convexCase
        {
            const char* name;
            const shape* A; bodyPose pA; const shape* B; bodyPose pB;
            overlapSettings s;
            double exact;
        };
        const overlapSettings defaults{h, 4};
        const bodyPose cubeFace = cubeB.poseFromFilePlacement(quat::Identity(), vec3(sx, sy, 2*a - 1e-3*2*a));
        const bodyPose origin = cubeA.poseFromFilePlacement(quat::Identity(), vec3::Zero());
        std::vector<convexCase> cc
        {
            {"icosahedra 0.1 mm, d/10 level 3", &icoA, pIA, &icoA, pIB, {dIco/10, 3}, 0},
            {"icosahedra 0.1 mm, defaults", &icoA, pIA, &icoA, pIB, {overlapSettings::defaultCellSize(dIco), 4}, 0},
            {"cubes face on face 0.01 mm", &cubeA, origin, &cubeB, cubeFace, defaults, 0},
            {"cube on a plane 0.01 mm", &plane, bodyPose(), &cubeB, onPlane, defaults, 0},
            {"cube on a wall mesh, by a corner", &tank, bodyPose(), &cubeB, onPlane, defaults, 0}
        };
        cc[0].exact = cc[1].exact = exactOverlap().evaluate(icoA, pIA, icoA, pIB, {}).volume();
        cc[2].exact = exactOverlap().evaluate(cubeA, origin, cubeB, cubeFace, {}).volume();
        cc[3].exact = cc[4].exact = exactOverlap().evaluate
        (
            slab, slab.poseFromFilePlacement(quat::Identity(), vec3::Zero()), cubeB, onPlane, {}
        ).volume();
        for (const convexCase& c : cc)
        {
            overlapSettings octree = c.s;
            octree.convexExact = false;
            std::vector<double> tO, tC;
            double vO = 0, vC = 0;
            const int inner = 100;
            for (int r = 0; r < repeats; ++r)
            {
                auto t0 = std::chrono::steady_clock::now();
                vO = vm.evaluate(*c.A, c.pA, *c.B, c.pB, octree).volume();
                tO.push_back(seconds(t0));
                t0 = std::chrono::steady_clock::now();
                for (int k = 0; k < inner; ++k)
                {
                    vC = vm.evaluate(*c.A, c.pA, *c.B, c.pB, c.s).volume();
                }
                tC.push_back(seconds(t0)/inner);
            }
            std::printf("%-34s %12.1f %12.2f %9.0f %12.5e %+12.2e %+12.2e\n",
                c.name, 1e6*median(tO), 1e6*median(tC), median(tO)/median(tC), c.exact,
                vO/c.exact - 1, vC/c.exact - 1);
        }
    }

    // 4. Crossing a wall's rim on the domain's boundary
    {
        std::printf("\nA wall's rim at an outlet: the rim as rim (octree) against the wall continued"
            " across it (exact planes), median of %d alternating runs\n", repeats);
        std::printf("%-34s %12s %12s %9s %12s %12s %12s\n",
            "pair", "rim [us]", "continued", "ratio", "V exact", "rim err", "cont. err");
        const vec3 lo(-0.0065, -0.0065, 0), hi(0.0935, 0.0935, 0.1);
        const triangleSoup box = primitiveMeshes::openBox(lo, hi, 10);
        std::vector<wallMeshShape::edge> top;
        for (const triFace& f : box.faces)
        {
            for (int k = 0; k < 3; ++k)
            {
                const int p = f[k], q = f[(k + 1)%3];
                if (box.points[p].z() == hi.z() && box.points[q].z() == hi.z()) top.push_back({p, q});
            }
        }
        const wallMeshShape rim(box, "rim", 0.02);
        const wallMeshShape continued(box, "continued", 0.02, top);
        // On the side x = lo, 0.01 mm deep, its top 7 mm past the outlet
        const bodyPose cubePose =
            cubeB.poseFromFilePlacement(quat::Identity(), vec3(lo.x() + a - 1e-5, 0.04, hi.z() - 0.3*a));
        const sphereShape ball(a);
        const bodyPose ballPose(vec3(lo.x() + a - 1e-5, 0.04, hi.z() - 0.3*a), quat::Identity());
        // The side's half-space as a slab mesh, for the exact engine
        triangleSoup slabSoup = primitiveMeshes::box(vec3(0.05, 0.1, 0.1));
        primitiveMeshes::transform(slabSoup, mat3::Identity(), vec3(lo.x() - 0.05, 0.04, 0.1));
        const triangleMeshShape slab(slabSoup, "slab");
        const bodyPose slabPose = slab.poseFromFilePlacement(quat::Identity(), vec3::Zero());
        const double exactCube = exactOverlap().evaluate(slab, slabPose, cubeB, cubePose, {}).volume();
        const double t = 1e-5, exactBall = M_PI*t*t*(3*a - t)/3;     // the cap
        struct rimCase { const char* name; const shape* B; bodyPose pB; double exact; };
        for (const rimCase& c : std::vector<rimCase>
        {
            {"cube on a side, across the outlet", &cubeB, cubePose, exactCube},
            {"sphere on a side, across the outlet", &ball, ballPose, exactBall}
        })
        {
            const overlapSettings defaults{h, 4};
            std::vector<double> tR, tC;
            double vR = 0, vC = 0;
            const int inner = 100;
            for (int r = 0; r < repeats; ++r)
            {
                auto t0 = std::chrono::steady_clock::now();
                vR = vm.evaluate(rim, bodyPose(), *c.B, c.pB, defaults).volume();
                tR.push_back(seconds(t0));
                t0 = std::chrono::steady_clock::now();
                for (int k = 0; k < inner; ++k)
                {
                    vC = vm.evaluate(continued, bodyPose(), *c.B, c.pB, defaults).volume();
                }
                tC.push_back(seconds(t0)/inner);
            }
            std::printf("%-34s %12.1f %12.2f %9.0f %12.5e %+12.2e %+12.2e\n",
                c.name, 1e6*median(tR), 1e6*median(tC), median(tR)/median(tC), c.exact,
                vR/c.exact - 1, vC/c.exact - 1);
        }
    }
    return 0;
}
