/*---------------------------------------------------------------------------*\
Description
    Tests of the distance between convex polyhedra (convexDistance, GJK)
    against the closest pair of triangles of the two bounding-volume
    hierarchies (triangleBVH::closestPair, which it replaces for convex
    pairs in the lubrication and the pair filter): boxes and icosahedra at
    random poses and gaps from 1e-7 to 1 of their size, the closest points
    on the surfaces, parallel faces, and overlapping pairs reported as
    intersecting (against the exact convex overlap). Then the pair
    filter's bound and the lubrication's gap for two convex meshes.
\*---------------------------------------------------------------------------*/

#include "convexDistance.H"
#include "convexOverlap.H"
#include "convexPolyhedron.H"
#include "lubrication.H"
#include "pairFilter.H"
#include "triangleMeshShape.H"
#include "primitiveMeshes.H"
#include "wallMeshShape.H"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace immersedDEM;

namespace
{

quat randomRotation(std::mt19937& rng)
{
    std::normal_distribution<double> n(0, 1);
    return quat(n(rng), n(rng), n(rng), n(rng)).normalized();
}


vec3 randomDirection(std::mt19937& rng)
{
    std::normal_distribution<double> n(0, 1);
    return vec3(n(rng), n(rng), n(rng)).normalized();
}


// The BVH's closest pair of triangles, B in A's frame
triangleBVH::pairHit bvhClosest
(
    const triangleMeshShape& A, const bodyPose& pA,
    const triangleMeshShape& B, const bodyPose& pB
)
{
    const mat3 R = pA.rotation().transpose()*pB.rotation();
    const vec3 t = pA.rotation().transpose()*(pB.position() - pA.position());
    return triangleBVH::closestPair
    (
        A.distanceField().tree(), B.distanceField().tree(), R, t, 1e9
    );
}


convexClosest gjk
(
    const triangleMeshShape& A, const bodyPose& pA,
    const triangleMeshShape& B, const bodyPose& pB
)
{
    const mat3 R = pA.rotation().transpose()*pB.rotation();
    const vec3 t = pA.rotation().transpose()*(pB.position() - pA.position());
    return convexDistance(A.convex()->vertices(), B.convex()->vertices(), R, t);
}


// Place B along a random direction from A so that their gap is about g:
// moved out from overlapping along d until apart by g (bisection on the
// BVH's distance)
bodyPose placeAt
(
    const triangleMeshShape& A, const bodyPose& pA,
    const triangleMeshShape& B, const quat& qB, const vec3& d, double g
)
{
    double lo = 0, hi = 4*(A.boundingRadius() + B.boundingRadius());
    for (int i = 0; i < 200; ++i)
    {
        const double mid = 0.5*(lo + hi);
        const double dist =
            bvhClosest(A, pA, B, bodyPose(pA.position() + mid*d, qB)).distance;
        (dist < g ? lo : hi) = mid;
    }
    return bodyPose(pA.position() + hi*d, qB);
}

} // End anonymous namespace


TEST(convexDistance, agreesWithTheTrianglePairsAtAnyGap)
{
    const triangleMeshShape box(primitiveMeshes::box(vec3(0.002, 0.0015, 0.001)), "box");
    const triangleMeshShape ico(primitiveMeshes::icosphere(0.0015, 0), "icosahedron");
    ASSERT_TRUE(box.convex() && ico.convex());
    std::mt19937 rng(7);
    double worst = 0;
    int cases = 0;
    for (const triangleMeshShape* A : {&box, &ico})
    {
        for (const triangleMeshShape* B : {&box, &ico})
        {
            for (const double g : {1e-7, 1e-6, 1e-5, 1e-4, 1e-3})
            {
                for (int k = 0; k < 10; ++k)
                {
                    const bodyPose pA(vec3(0.01, -0.02, 0.003), randomRotation(rng));
                    const bodyPose pB = placeAt
                    (
                        *A, pA, *B, randomRotation(rng), randomDirection(rng), g*0.003
                    );
                    const triangleBVH::pairHit h = bvhClosest(*A, pA, *B, pB);
                    const convexClosest c = gjk(*A, pA, *B, pB);
                    ASSERT_FALSE(c.intersecting) << "gap " << h.distance;
                    const double err = std::abs(c.distance - h.distance)/h.distance;
                    worst = std::max(worst, err);
                    EXPECT_LT(err, 1e-8) << "gap " << h.distance << " gjk " << c.distance;
                    // The points: on the surfaces (in A's frame), the
                    // distance apart
                    EXPECT_NEAR((c.pointB - c.pointA).norm(), c.distance, 1e-12*0.003);
                    const vec3 bWorld = pA.toWorld(c.pointB);
                    EXPECT_NEAR(A->signedDistance(pA, pA.toWorld(c.pointA)), 0, 1e-12);
                    EXPECT_NEAR(B->signedDistance(pB, bWorld), 0, 1e-12);
                    ++cases;
                }
            }
        }
    }
    std::cout << "  " << cases << " poses, largest relative difference " << worst << std::endl;
}


TEST(convexDistance, parallelFacesAndOverlaps)
{
    const triangleMeshShape box(primitiveMeshes::box(vec3(0.001, 0.001, 0.001)), "box");
    // Face on face, 1 um apart, shifted sideways: the gap along z
    {
        const bodyPose pA(vec3::Zero(), quat::Identity());
        const bodyPose pB(vec3(0.0005, 0.0003, 0.002 + 1e-6), quat::Identity());
        const convexClosest c = gjk(box, pA, box, pB);
        ASSERT_FALSE(c.intersecting);
        EXPECT_NEAR(c.distance, 1e-6, 1e-15);
        EXPECT_NEAR(c.pointB.z() - c.pointA.z(), 1e-6, 1e-15);
    }
    // Touching exactly, and overlapping: intersecting, as the exact
    // overlap says (a region) for the overlapping ones
    std::mt19937 rng(3);
    int overlapping = 0;
    for (int k = 0; k < 200; ++k)
    {
        const bodyPose pA(vec3::Zero(), randomRotation(rng));
        const bodyPose pB(0.0026*randomDirection(rng), randomRotation(rng));
        const convexClosest c = gjk(box, pA, box, pB);
        const contactGeometry e = convexOverlap().evaluate(box, pA, box, pB, {});
        if (!e.regions.empty())
        {
            ++overlapping;
            EXPECT_TRUE(c.intersecting) << "pose " << k;
        }
        else
        {
            const double h = bvhClosest(box, pA, box, pB).distance;
            if (h > 1e-9)
            {
                EXPECT_FALSE(c.intersecting) << "pose " << k;
                EXPECT_NEAR(c.distance, h, 1e-9*h) << "pose " << k;
            }
        }
    }
    EXPECT_GT(overlapping, 20);
    EXPECT_LT(overlapping, 180);
}


TEST(convexDistance, filterAndLubricationUseIt)
{
    const triangleMeshShape box(primitiveMeshes::box(vec3(0.001, 0.001, 0.001)), "box");
    std::mt19937 rng(11);
    for (int k = 0; k < 20; ++k)
    {
        const bodyPose pA(vec3::Zero(), randomRotation(rng));
        const bodyPose pB = placeAt(box, pA, box, randomRotation(rng), randomDirection(rng), 2e-4);
        const double h = bvhClosest(box, pA, box, pB).distance;
        // The filter's lower bound: at most the distance, within 1e-8 of it
        const double g = pairFilter::gapLowerBound(box, pA, box, pB, 0, 1);
        EXPECT_LE(g, h);
        EXPECT_GT(g, h*(1 - 1e-6));
        // The lubrication's gap and normal (from A to B)
        const closestApproach a = lubrication::approach(box, pA, box, pB, 1e-3);
        ASSERT_TRUE(a.found);
        EXPECT_NEAR(a.gap, h, 1e-9*h);
        EXPECT_GT(a.normal.dot(pB.position() - pA.position()), 0);
    }
}


TEST(convexDistance, convexBodyInAWallMeshCorner)
{
    // A cube near the corner of an open box tank (1 cm faces): the least
    // corner height over the tank's near planes against the closest pair
    // of triangles; the filter's bound and the lubrication's gap use it
    const double a = 0.005;
    const triangleMeshShape cube(primitiveMeshes::box(vec3::Constant(a)), "cube");
    const wallMeshShape tank(primitiveMeshes::openBox(vec3(0, 0, 0), vec3(0.1, 0.1, 0.1), 10), "tank", 0.02);
    const bodyPose wall;
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(0, 1);
    int known = 0, near = 0;
    for (int k = 0; k < 40; ++k)
    {
        const quat q = randomRotation(rng);
        const vec3 x(0.0095 + 0.002*u(rng), 0.0095 + 0.002*u(rng), 0.0095 + 0.01*u(rng));
        const bodyPose p(x, q);
        const convexWallGap w = convexWallDistance
        (
            tank, wall, cube.convex()->vertices(), cube.boundingRadius(), p, 0.002
        );
        ASSERT_TRUE(w.known) << "pose " << k;
        ++known;
        const mat3 R = p.rotation();
        const triangleBVH::pairHit h = triangleBVH::closestPair
        (
            tank.distanceField().tree(), cube.distanceField().tree(), R, x, 1
        );
        if (w.beyondReach)
        {
            // Beyond the reach: a lower bound, the reach
            EXPECT_EQ(w.gap, 0.002);
            EXPECT_GE(h.distance, 0.002*(1 - 1e-12)) << "pose " << k;
            EXPECT_FALSE(lubrication::approach(cube, p, tank, wall, 0.002).found);
        }
        else if (w.gap > 1e-9)
        {
            EXPECT_NEAR(w.gap, h.distance, 1e-9*h.distance) << "pose " << k;
            EXPECT_NEAR((w.pointBody - w.pointWall).norm(), w.gap, 1e-12);
            const double g = pairFilter::gapLowerBound(tank, wall, cube, p, 0, 0.004);
            EXPECT_LE(g, h.distance);
            EXPECT_GT(g, h.distance - 1e-8);
            ++near;
            const closestApproach c = lubrication::approach(cube, p, tank, wall, 0.002);
            if (h.distance < 0.002)
            {
                ASSERT_TRUE(c.found);
                EXPECT_NEAR(c.gap, h.distance, 1e-9*h.distance);
                // From the cube (A) to the wall (B): out of the fluid
                EXPECT_LT(c.normal.dot(w.normal), 0);
            }
        }
        else
        {
            // Through a wall: the triangles cross (or the cube is behind)
            EXPECT_LT(h.distance, 1e-9);
        }
    }
    EXPECT_EQ(known, 40);
    EXPECT_GE(near, 8);
}
