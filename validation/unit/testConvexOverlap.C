/*---------------------------------------------------------------------------*\
Description
    Tests of the exact convex contact (convexOverlap) and its dispatch from
    the default engine: convexity detection, agreement with the CGAL exact
    engine for cubes and icosahedra at random poses, cubes on a plane in
    both orders, face-on-face slivers down to 1e-5 of the size, exactly
    touching faces, a body wholly inside another, S and M against central
    differences of the volume, and non-convex meshes left to the octree.
\*---------------------------------------------------------------------------*/

#include "convexOverlap.H"
#include "convexPolyhedron.H"
#include "exactOverlap.H"
#include "halfSpaceShape.H"
#include "wallMeshShape.H"
#include "virtualMeshOverlap.H"
#include "triangleMeshShape.H"
#include "primitiveMeshes.H"
#include "testHelpers.H"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>

using namespace immersedDEM;

namespace
{

quat randomRotation(std::mt19937& rng)
{
    std::normal_distribution<double> n(0, 1);
    quat q(n(rng), n(rng), n(rng), n(rng));
    return q.normalized();
}


// A big box standing for the half-space z <= 0 of the exact engine
std::unique_ptr<triangleMeshShape> slab()
{
    triangleSoup s = primitiveMeshes::box(vec3(0.1, 0.1, 0.05));
    primitiveMeshes::transform(s, mat3::Identity(), vec3(0, 0, -0.05));
    return std::make_unique<triangleMeshShape>(s, "slab");
}


// The exact engine's region against the convex one's
void expectSameAsExact
(
    const shape& A, const bodyPose& pA, const shape& B, const bodyPose& pB,
    double tol, const std::string& what
)
{
    // tol: the caller's; two exact methods agree to round-off
    const contactGeometry e = exactOverlap().evaluate(A, pA, B, pB, {});
    overlapSettings s;
    s.areaVectorNormal = true;
    const contactGeometry c = convexOverlap().evaluate(A, pA, B, pB, s);
    ASSERT_EQ(c.regions.size(), e.regions.size()) << what;
    if (e.regions.empty()) return;
    const contactRegion& re = e.regions[0];
    const contactRegion& rc = c.regions[0];
    const double l = std::cbrt(re.volume);
    EXPECT_NEAR(rc.volume, re.volume, tol*re.volume) << what;
    EXPECT_LT((rc.point - re.point).norm(), tol*l) << what;
    EXPECT_LT((rc.areaVector - re.area*re.normal).norm(), tol*re.area) << what;
    EXPECT_NEAR(rc.area, re.area, tol*re.area) << what;
    EXPECT_LT((rc.normal - re.normal).norm(), tol) << what;
}

} // End anonymous namespace


TEST(convexOverlap, selectedByName)
{
    EXPECT_EQ(overlapEngine::New("convex")->type(), "convex");
}


TEST(convexOverlap, convexityIsDetected)
{
    const triangleMeshShape cube(primitiveMeshes::box(vec3(0.005, 0.004, 0.003)), "cube");
    ASSERT_NE(cube.convex(), nullptr);
    EXPECT_EQ(cube.convex()->faces().size(), 6u);
    for (const auto& f : cube.convex()->faces()) EXPECT_EQ(f.corners.size(), 4u);

    const triangleMeshShape ico(primitiveMeshes::icosphere(0.005, 0), "ico");
    ASSERT_NE(ico.convex(), nullptr);
    EXPECT_EQ(ico.convex()->faces().size(), 20u);
    const triangleMeshShape ball(primitiveMeshes::icosphere(0.005, 2), "ball");
    ASSERT_NE(ball.convex(), nullptr);
    EXPECT_EQ(ball.convex()->faces().size(), 320u);

    // A hexagonal prism: its side rectangles and its two hexagons
    std::vector<Eigen::Vector2d> hexagon;
    for (int k = 0; k < 6; ++k)
    {
        hexagon.emplace_back(0.004*std::cos(k*M_PI/3), 0.004*std::sin(k*M_PI/3));
    }
    const triangleMeshShape prism(primitiveMeshes::extrudedPolygon(hexagon, 0.003), "prism");
    ASSERT_NE(prism.convex(), nullptr);
    EXPECT_EQ(prism.convex()->faces().size(), 8u);

    // Not convex: an L prism, a torus; and not taken by the convex path
    const std::vector<Eigen::Vector2d> L{{0, 0}, {0.004, 0}, {0.004, 0.001}, {0.001, 0.001}, {0.001, 0.003}, {0, 0.003}};
    const triangleMeshShape l(primitiveMeshes::extrudedPolygon(L, 0.002), "L");
    EXPECT_EQ(l.convex(), nullptr);
    const triangleMeshShape torus(primitiveMeshes::torus(0.004, 0.001, 24, 12), "torus");
    EXPECT_EQ(torus.convex(), nullptr);
    const halfSpaceShape plane;
    EXPECT_TRUE(convexOverlap::handles(cube, ico));
    EXPECT_TRUE(convexOverlap::handles(plane, cube));
    EXPECT_TRUE(convexOverlap::handles(cube, plane));
    EXPECT_FALSE(convexOverlap::handles(l, cube));
    EXPECT_FALSE(convexOverlap::handles(cube, torus));
    EXPECT_FALSE(convexOverlap::handles(plane, l));
    EXPECT_TRUE(test::throwsCoreError
    (
        [&]{ convexOverlap().evaluate(l, bodyPose(), cube, bodyPose(), {}); },
        {"convex", "virtualMesh"}
    ));
}


TEST(convexOverlap, cubesAndIcosahedraAtRandomPosesMatchExact)
{
    const triangleMeshShape cube(primitiveMeshes::box(vec3::Constant(0.005)), "cube");
    const triangleMeshShape brick(primitiveMeshes::box(vec3(0.006, 0.003, 0.002)), "brick");
    const triangleMeshShape ico(primitiveMeshes::icosphere(0.005, 0), "ico");
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    const std::pair<const shape*, const shape*> pairs[] =
        {{&cube, &cube}, {&cube, &brick}, {&ico, &ico}, {&ico, &brick}};
    int contacts = 0;
    for (const auto& AB : pairs)
    {
        for (int k = 0; k < 12; ++k)
        {
            const bodyPose pA(vec3(0.1, -0.2, 0.3), randomRotation(rng));
            const vec3 d = vec3(u(rng), u(rng), u(rng)).normalized()*0.0085;
            const bodyPose pB(pA.position() + d, randomRotation(rng));
            const contactGeometry e = exactOverlap().evaluate(*AB.first, pA, *AB.second, pB, {});
            contacts += int(e.regions.size());
            expectSameAsExact(*AB.first, pA, *AB.second, pB, 1e-8, "pose " + std::to_string(k));
        }
    }
    std::cout << contacts << " of 48 poses in contact" << std::endl;
    EXPECT_GT(contacts, 30);    // enough of the 48 random poses test something
}


TEST(convexOverlap, theOrderOfThePairTurnsSAndMOnly)
{
    const triangleMeshShape ico(primitiveMeshes::icosphere(0.005, 0), "ico");
    const triangleMeshShape brick(primitiveMeshes::box(vec3(0.006, 0.003, 0.002)), "brick");
    const bodyPose pA(vec3::Zero(), bodyPose::axisAngle(vec3(1, 2, 3), 0.4));
    const bodyPose pB(vec3(0.003, 0.004, 0.005), bodyPose::axisAngle(vec3(-1, 0, 2), 1.1));
    const contactGeometry ab = convexOverlap().evaluate(ico, pA, brick, pB, {});
    const contactGeometry ba = convexOverlap().evaluate(brick, pB, ico, pA, {});
    ASSERT_EQ(ab.regions.size(), 1u);
    ASSERT_EQ(ba.regions.size(), 1u);
    const contactRegion& x = ab.regions[0];
    const contactRegion& y = ba.regions[0];
    EXPECT_NEAR(x.volume, y.volume, 1e-12*x.volume);
    EXPECT_LT((x.point - y.point).norm(), 1e-12);
    // A's surface inside B and B's inside A close the overlap: S_A = -S_B
    EXPECT_LT((x.areaVector + y.areaVector).norm(), 1e-9*x.area);
    EXPECT_LT((x.areaMoment + y.areaMoment).norm(), 1e-9*x.area*std::sqrt(x.area));
    EXPECT_LT((x.normal + y.normal).norm(), 1e-9);
}


TEST(convexOverlap, cubeOnAPlaneInBothOrders)
{
    const triangleMeshShape cube(primitiveMeshes::box(vec3::Constant(0.005)), "cube");
    const std::unique_ptr<triangleMeshShape> slabShape = slab();
    const triangleMeshShape& floor = *slabShape;
    const halfSpaceShape plane;
    const bodyPose wall;        // z <= 0
    const bodyPose slabPose = floor.poseFromFilePlacement(quat::Identity(), vec3::Zero());
    std::mt19937 rng(3);
    for (int k = 0; k < 8; ++k)
    {
        const quat q = randomRotation(rng);
        // The lowest corner 1 mm below the plane
        double low = 1;
        for (const vec3& x : cube.surface().points) low = std::min(low, (q*x).z());
        const bodyPose p(vec3(0.001, 0.002, -low - 0.001), q);
        const contactGeometry e = exactOverlap().evaluate(floor, slabPose, cube, p, {});
        ASSERT_EQ(e.regions.size(), 1u);
        overlapSettings s{0.0005, 4};
        s.areaVectorNormal = true;
        const contactGeometry pb = convexOverlap().evaluate(plane, wall, cube, p, s);
        const contactGeometry bp = convexOverlap().evaluate(cube, p, plane, wall, s);
        ASSERT_EQ(pb.regions.size(), 1u);
        ASSERT_EQ(bp.regions.size(), 1u);
        const contactRegion& re = e.regions[0];
        for (const contactRegion* r : {&pb.regions[0], &bp.regions[0]})
        {
            EXPECT_NEAR(r->volume, re.volume, 1e-8*re.volume);
            EXPECT_LT((r->point - re.point).norm(), 1e-10);
            EXPECT_NEAR(r->area, re.area, 1e-8*re.area);
        }
        // Plane first: S is the plane's normal times the cut's area
        EXPECT_LT((pb.regions[0].areaVector - re.area*vec3::UnitZ()).norm(), 1e-8*re.area);
        EXPECT_LT((bp.regions[0].areaVector + re.area*vec3::UnitZ()).norm(), 1e-8*re.area);
        EXPECT_LT((pb.regions[0].normal - vec3::UnitZ()).norm(), 1e-12);
        // The fitted plane through the rim (the cut's outline) is the plane
        const contactGeometry fitted = convexOverlap().evaluate(cube, p, plane, wall, {});
        EXPECT_LT((fitted.regions[0].normal + vec3::UnitZ()).norm(), 1e-9);
        // The default engine takes the convex path
        const contactGeometry v = virtualMeshOverlap().evaluate(cube, p, plane, wall, s);
        ASSERT_EQ(v.regions.size(), 1u);
        EXPECT_EQ(v.regions[0].volume, bp.regions[0].volume);
        EXPECT_EQ(v.leaves, 0);
    }
}


TEST(convexOverlap, slivers)
{
    // Two 10 mm cubes face on face, B shifted sideways by 3 and 2 mm and
    // pressed in by depth d; the bodies turned together (the faces on no
    // lattice plane): the overlap is a box wx x wy x d, and S (in A's
    // frame) is A's top face there and its two side strips of depth d
    const double a = 0.005, wx = 2*a - 0.003, wy = 2*a - 0.002;
    const triangleMeshShape cube(primitiveMeshes::box(vec3::Constant(a)), "cube");
    const quat q = bodyPose::axisAngle(vec3(1, 2, 3), 0.7);
    const vec3 t(0.02, 0.01, 0.03);
    const bodyPose pA = cube.poseFromFilePlacement(q, t);
    std::cout << "depth/size  exact  convex  virtualMesh(default)  octree  (over the exact box's)" << std::endl;
    std::cout.precision(8);
    for (const double rel : {1e-2, 1e-3, 1e-4, 1e-5})
    {
        const double d = rel*2*a;
        const bodyPose pB = cube.poseFromFilePlacement(q, t + q*vec3(0.003, 0.002, 2*a - d));
        const double V = d*wx*wy;
        const double ve = exactOverlap().evaluate(cube, pA, cube, pB, {}).volume();
        const contactGeometry c = convexOverlap().evaluate(cube, pA, cube, pB, {});
        const contactGeometry v = virtualMeshOverlap().evaluate(cube, pA, cube, pB, {0.0005, 4});
        overlapSettings octree{0.0005, 4};
        octree.convexExact = false;
        const double vo = virtualMeshOverlap().evaluate(cube, pA, cube, pB, octree).volume();
        std::cout << rel << "  " << ve/V << "  " << c.volume()/V << "  " << v.volume()/V
            << "  " << vo/V << std::endl;
        ASSERT_EQ(c.regions.size(), 1u);
        EXPECT_NEAR(c.volume(), ve, 0.01*ve);   // see the exact method's own rounding below
        EXPECT_NEAR(c.volume(), V, 1e-6*V);     // the clipped polyhedron is the box: round-off
        EXPECT_EQ(v.volume(), c.volume());
        const contactRegion& r = c.regions[0];
        const vec3 S = q*vec3(wy*d, wx*d, wx*wy);
        EXPECT_LT((r.areaVector - S).norm(), 1e-9*S.norm());
        EXPECT_NEAR(r.area, S.norm(), 1e-9*S.norm());
        // The plane fitted through the rim: within the sliver's slope of
        // the face normal
        EXPECT_LT((r.normal - q*vec3::UnitZ()).norm(), 2*rel);
        EXPECT_GT(r.normal.dot(q*vec3::UnitZ()), 0);
        const vec3 p = t + q*vec3(0.0015, 0.001, a - 0.5*d);
        EXPECT_LT((r.point - p).norm(), 1e-9*a);
    }
}


TEST(convexOverlap, touchingFacesGiveNoRegion)
{
    const double a = 0.005;
    const triangleMeshShape cube(primitiveMeshes::box(vec3::Constant(a)), "cube");
    const halfSpaceShape plane;
    std::mt19937 rng(11);
    for (int k = 0; k < 6; ++k)
    {
        const quat q = k == 0 ? quat::Identity() : randomRotation(rng);
        const vec3 t(0.02, 0.01, 0.03);
        const bodyPose pA = cube.poseFromFilePlacement(q, t);
        const bodyPose pB = cube.poseFromFilePlacement(q, t + q*vec3(0.003, -0.004, 2*a));
        EXPECT_TRUE(convexOverlap().evaluate(cube, pA, cube, pB, {}).regions.empty()) << k;
        EXPECT_TRUE(virtualMeshOverlap().evaluate(cube, pA, cube, pB, {0.0005, 4}).regions.empty()) << k;
        // Edge on edge, and corner on corner
        const bodyPose pE = cube.poseFromFilePlacement(q, t + q*vec3(2*a, 0.001, 2*a));
        EXPECT_TRUE(convexOverlap().evaluate(cube, pA, cube, pE, {}).regions.empty()) << k;
        const bodyPose pC = cube.poseFromFilePlacement(q, t + q*vec3(2*a, 2*a, 2*a));
        EXPECT_TRUE(convexOverlap().evaluate(cube, pA, cube, pC, {}).regions.empty()) << k;
    }
    // A cube resting on a plane, its face on it
    const bodyPose wall;
    const bodyPose onIt = cube.poseFromFilePlacement(quat::Identity(), vec3(0.3, 0.1, a));
    EXPECT_TRUE(convexOverlap().evaluate(plane, wall, cube, onIt, {}).regions.empty());
    EXPECT_TRUE(convexOverlap().evaluate(cube, onIt, plane, wall, {}).regions.empty());
    // ... and 1e-9 of its size into it: a region
    const bodyPose into = cube.poseFromFilePlacement(quat::Identity(), vec3(0.3, 0.1, a - 1e-11));
    const contactGeometry g = convexOverlap().evaluate(plane, wall, cube, into, {});
    ASSERT_EQ(g.regions.size(), 1u);
    EXPECT_NEAR(g.volume(), 1e-11*4*a*a, 1e-6*1e-11*4*a*a);
}


TEST(convexOverlap, oneBodyInsideTheOther)
{
    const triangleMeshShape big(primitiveMeshes::box(vec3::Constant(0.005)), "big");
    const triangleMeshShape ico(primitiveMeshes::icosphere(0.002, 0), "ico");
    const bodyPose pA(vec3(0, 0, 0), bodyPose::axisAngle(vec3(1, 1, 0), 0.3));
    const bodyPose pB(vec3(0.001, 0.0005, 0), bodyPose::axisAngle(vec3(0, 1, 1), 0.8));
    for (const bool bigFirst : {true, false})
    {
        const contactGeometry g = bigFirst
            ? convexOverlap().evaluate(big, pA, ico, pB, {})
            : convexOverlap().evaluate(ico, pB, big, pA, {});
        ASSERT_EQ(g.regions.size(), 1u);
        const contactRegion& r = g.regions[0];
        EXPECT_NEAR(r.volume, ico.volume(), 1e-12*ico.volume());
        EXPECT_LT((r.point - pB.position()).norm(), 1e-12);
        // S and M: the integrals over A's closed surface (ico first) or
        // over nothing (big first), zero to round-off (1e-12 of the
        // icosahedron's area 4e-5 m2, and of that times its size)
        EXPECT_LT(r.area, 1e-12*4e-5);
        EXPECT_LT(r.areaVector.norm(), 1e-12*4e-5);
        EXPECT_LT(r.areaMoment.norm(), 1e-12*4e-5*0.002);
        // The normal: the centre line from A to B
        const vec3 line = (bigFirst ? 1 : -1)*(pB.position() - pA.position()).normalized();
        EXPECT_LT((r.normal - line).norm(), 1e-12);
    }
}


TEST(convexOverlap, areaVectorAndMomentAreTheVolumeGradient)
{
    // Icosahedron and brick at a general pose: S = -dV/dx_B, M = -dV/dtheta_B
    // about the contact point, V of the convex engine itself
    const triangleMeshShape ico(primitiveMeshes::icosphere(0.005, 0), "ico");
    const triangleMeshShape brick(primitiveMeshes::box(vec3(0.006, 0.003, 0.002)), "brick");
    const bodyPose pA(vec3::Zero(), bodyPose::axisAngle(vec3(1, 2, 3), 0.4));
    const bodyPose p0(vec3(0.003, 0.004, 0.004), bodyPose::axisAngle(vec3(-1, 0, 2), 1.1));
    const contactGeometry g = convexOverlap().evaluate(ico, pA, brick, p0, {});
    ASSERT_EQ(g.regions.size(), 1u);
    const contactRegion& r = g.regions[0];
    auto volumeAt = [&](const vec3& dx, const vec3& dtheta)
    {
        const double a = dtheta.norm();
        const quat dq = a > 0 ? bodyPose::axisAngle(dtheta/a, a) : quat::Identity();
        const vec3 c = r.point + dq*(p0.position() - r.point) + dx;
        return convexOverlap().evaluate(ico, pA, brick, bodyPose(c, dq*p0.orientation()), {}).volume();
    };
    const double e = 1e-7, t = 1e-5;
    const double S = r.areaVector.norm();
    for (int k = 0; k < 3; ++k)
    {
        const vec3 u = vec3::Unit(k);
        const double dVdx = (volumeAt(e*u, vec3::Zero()) - volumeAt(-e*u, vec3::Zero()))/(2*e);
        const double dVdt = (volumeAt(vec3::Zero(), t*u) - volumeAt(vec3::Zero(), -t*u))/(2*t);
        std::cout << "axis " << k << ": -dV/dx " << -dVdx << " S " << r.areaVector[k]
            << "; -dV/dtheta " << -dVdt << " M " << r.areaMoment[k] << std::endl;
        // 1e-4: the central differences' error (steps 1e-7 m, 1e-5 rad,
        // second order) and their round-off
        EXPECT_NEAR(r.areaVector[k], -dVdx, 1e-4*S) << "axis " << k;
        EXPECT_NEAR(r.areaMoment[k], -dVdt, 1e-4*S*std::sqrt(S)) << "axis " << k;
    }
}


TEST(convexOverlap, nonConvexPairsStayOnTheOctree)
{
    // An L prism not decomposed into convex pieces (maxConvexPieces 0)
    const std::vector<Eigen::Vector2d> L{{0, 0}, {0.004, 0}, {0.004, 0.001}, {0.001, 0.001}, {0.001, 0.003}, {0, 0.003}};
    const triangleMeshShape l(primitiveMeshes::extrudedPolygon(L, 0.002), "L", true, 0);
    const triangleMeshShape cube(primitiveMeshes::box(vec3::Constant(0.002)), "cube");
    const bodyPose pA = l.poseFromFilePlacement(quat::Identity(), vec3::Zero());
    const bodyPose pB = cube.poseFromFilePlacement(quat::Identity(), vec3(0.0035, 0.0005, 0.001));
    const contactGeometry g = virtualMeshOverlap().evaluate(l, pA, cube, pB, {0.0002, 4});
    ASSERT_FALSE(g.regions.empty());
    EXPECT_GT(g.leaves, 0);
    const double ve = exactOverlap().evaluate(l, pA, cube, pB, {}).volume();
    EXPECT_NEAR(g.volume(), ve, 0.01*ve);   // the octree's accuracy on a non-convex body
}


TEST(convexOverlap, cubeOnAFlatPartOfAWallMesh)
{
    // An open box 100 mm wide (10 x 10 squares per side): a cube on its
    // floor, far from the sides, meets the floor's plane exactly; in the
    // corner the wall is not flat within the cube's reach: the octree
    const double a = 0.005;
    const triangleMeshShape cube(primitiveMeshes::box(vec3::Constant(a)), "cube");
    const wallMeshShape tank(primitiveMeshes::openBox(vec3(0, 0, 0), vec3(0.1, 0.1, 0.1), 10), "tank", 0.02);
    const halfSpaceShape plane;
    const bodyPose wall;
    const quat q = bodyPose::axisAngle(vec3(0, 0, 1), 0.3);
    const bodyPose p = cube.poseFromFilePlacement(q, vec3(0.051, 0.047, a - 2e-5));
    const overlapSettings s{0.0005, 4};
    const contactGeometry onPlane = convexOverlap().evaluate(cube, p, plane, wall, s);
    for (const bool cubeFirst : {true, false})
    {
        const contactGeometry g = cubeFirst
            ? virtualMeshOverlap().evaluate(cube, p, tank, wall, s)
            : virtualMeshOverlap().evaluate(tank, wall, cube, p, s);
        ASSERT_EQ(g.regions.size(), 1u);
        EXPECT_EQ(g.leaves, 0);
        EXPECT_NEAR(g.volume(), onPlane.volume(), 1e-12*onPlane.volume());
        EXPECT_NEAR(g.volume(), 2e-5*4*a*a, 1e-9*2e-5*4*a*a);
        const vec3 S = (cubeFirst ? 1 : -1)*onPlane.regions[0].areaVector;
        EXPECT_LT((g.regions[0].areaVector - S).norm(), 1e-9*S.norm());
    }
    // Near the corner, the side walls within the cube's reach but only
    // the floor crossed: the floor's plane, exactly
    const bodyPose nearCorner = cube.poseFromFilePlacement(q, vec3(1.3*a, 1.3*a, a - 2e-5));
    for (const bool cubeFirst : {true, false})
    {
        const contactGeometry g = cubeFirst
            ? virtualMeshOverlap().evaluate(cube, nearCorner, tank, wall, s)
            : virtualMeshOverlap().evaluate(tank, wall, cube, nearCorner, s);
        ASSERT_EQ(g.regions.size(), 1u);
        EXPECT_EQ(g.leaves, 0);
        EXPECT_NEAR(g.volume(), 2e-5*4*a*a, 1e-9*2e-5*4*a*a);
        EXPECT_LT((g.regions[0].normal - (cubeFirst ? -1 : 1)*vec3::UnitZ()).norm(), 1e-9);
    }
    // ... and lifted off the floor: no region, no octree either
    const bodyPose lifted = cube.poseFromFilePlacement(q, vec3(1.3*a, 1.3*a, a + 1e-5));
    const contactGeometry none = virtualMeshOverlap().evaluate(cube, lifted, tank, wall, s);
    EXPECT_TRUE(none.regions.empty());
    EXPECT_EQ(none.leaves, 0);
    // In the corner, the floor and both sides crossed, the parts behind
    // the floor and behind a side sharing the cube's bottom corners: the
    // cube less its part in front of the three planes (the octant x, y,
    // z > 0, here a big box, clipped exactly), one region; against the
    // octree within its accuracy
    const bodyPose corner = cube.poseFromFilePlacement(q, vec3(a + 0.001, a + 0.001, a - 2e-5));
    const triangleMeshShape octant(primitiveMeshes::box(vec3::Constant(0.05)), "octant");
    const bodyPose pOctant(vec3::Constant(0.05), quat::Identity());
    const contactGeometry front = convexOverlap().evaluate(cube, corner, octant, pOctant, s);
    ASSERT_EQ(front.regions.size(), 1u);
    const double inWall = cube.volume() - front.volume();
    const vec3 Sin = -front.regions[0].areaVector;
    overlapSettings octree = s;
    octree.convexExact = false;
    const contactGeometry o = virtualMeshOverlap().evaluate(cube, corner, tank, wall, octree);
    for (const bool cubeFirst : {true, false})
    {
        const contactGeometry c = cubeFirst
            ? virtualMeshOverlap().evaluate(cube, corner, tank, wall, s)
            : virtualMeshOverlap().evaluate(tank, wall, cube, corner, s);
        ASSERT_EQ(c.regions.size(), 1u);
        EXPECT_EQ(c.leaves, 0);
        EXPECT_NEAR(c.volume(), inWall, 1e-9*inWall);
        EXPECT_LT((c.regions[0].areaVector - (cubeFirst ? 1 : -1)*Sin).norm(), 1e-9*Sin.norm());
        EXPECT_NEAR(c.volume(), o.volume(), 0.01*inWall);   // the octree's 1%
        // Pointing from the first body into the second: down into the
        // corner for the cube first
        const vec3 into(-1, -1, -1);
        EXPECT_GT((cubeFirst ? 1 : -1)*c.regions[0].normal.dot(into), 0);
    }

    // In the corner off the floor, both sides crossed apart from each
    // other (a pellet in a square tube's corner): one exact region per
    // side, their sum the octree's volume within its accuracy
    const bodyPose sides = cube.poseFromFilePlacement(q, vec3(a + 0.00123, a + 0.00121, 0.03));
    for (const bool cubeFirst : {true, false})
    {
        const contactGeometry g = cubeFirst
            ? virtualMeshOverlap().evaluate(cube, sides, tank, wall, s)
            : virtualMeshOverlap().evaluate(tank, wall, cube, sides, s);
        ASSERT_EQ(g.regions.size(), 2u);
        EXPECT_EQ(g.leaves, 0);
        double planes = 0;
        for (const vec3& n : {vec3(1, 0, 0), vec3(0, 1, 0)})
        {
            const bodyPose pP = halfSpaceShape::poseOf(vec3::Zero(), n);
            planes += convexOverlap().evaluate(cube, sides, plane, pP, s).volume();
        }
        EXPECT_NEAR(g.volume(), planes, 1e-12*planes);
        EXPECT_GT(planes, 0);
        overlapSettings octree = s;
        octree.convexExact = false;
        const contactGeometry o = virtualMeshOverlap().evaluate(cube, sides, tank, wall, octree);
        EXPECT_GT(o.leaves, 0);
        EXPECT_NEAR(o.volume(), planes, 0.01*planes);       // the octree's 1%
        // Normals: each region's along its wall's
        for (const contactRegion& r : g.regions)
        {
            const double along = std::max(std::abs(r.normal.x()), std::abs(r.normal.y()));
            EXPECT_GT(along, 1 - 1e-9);
        }
    }
    // Far from every wall, inside the tank's box: no region and no octree
    const bodyPose middle = cube.poseFromFilePlacement(q, vec3(0.05, 0.05, 0.05));
    const contactGeometry free = virtualMeshOverlap().evaluate(tank, wall, cube, middle, s);
    EXPECT_TRUE(free.regions.empty());
    EXPECT_EQ(free.leaves, 0);
}


TEST(convexOverlap, cubeAgainstTheInsideOfAFacetedTube)
{
    // A closed 24-sided prism (radius 60 mm) turned inside out: a tube
    // whose fluid is inside (a locally convex fluid region). A cube tilted
    // against one facet near its edge with the next: exact, against the
    // octree at a fine resolution; the same prism as a pillar, the cube
    // near the outer edge of two facets (fluid outside, not convex
    // there): the octree
    const double a = 0.005;
    const triangleMeshShape cube(primitiveMeshes::box(vec3::Constant(a)), "cube");
    std::vector<Eigen::Vector2d> ring;
    for (int k = 0; k < 24; ++k) ring.emplace_back(0.06*std::cos(2*M_PI*k/24), 0.06*std::sin(2*M_PI*k/24));
    triangleSoup tube = primitiveMeshes::extrudedPolygon(ring, 0.04);
    triangleSoup pillar = tube;
    for (triFace& f : tube.faces) std::swap(f[1], f[2]);
    const wallMeshShape inside(tube, "tube", 0.01);
    const wallMeshShape outside(pillar, "pillar", 0.01);
    const bodyPose wall;

    // Facet 0 spans the angles 0..15 degrees; its inner distance 60 cos(7.5)
    // mm; the cube, off its middle by 1 mm, reaches its neighbours' planes
    // (within its bounding radius) but crosses facet 0's only
    const double rf = 0.06*std::cos(M_PI/24);
    const vec3 nf(std::cos(M_PI/24), std::sin(M_PI/24), 0);
    const quat q = bodyPose::axisAngle(vec3(0, 0, 1), M_PI/24 + 0.05)*bodyPose::axisAngle(vec3(0, 1, 0), 0.03);
    bodyPose p = cube.poseFromFilePlacement(q, vec3::Zero());
    double out = -1;
    for (const vec3& x : cube.convex()->vertices()) out = std::max(out, nf.dot(p.toWorld(x) - p.position()));
    const vec3 c = (rf - out + 3e-5)*nf + vec3(0, 0, 0.02) + 0.001*vec3(-nf.y(), nf.x(), 0);
    p = bodyPose(c, p.orientation());

    const overlapSettings s{0.0005, 4};
    const contactGeometry g = virtualMeshOverlap().evaluate(inside, wall, cube, p, s);
    ASSERT_EQ(g.regions.size(), 1u);
    EXPECT_EQ(g.leaves, 0);
    overlapSettings fine{0.00025, 5};
    fine.convexExact = false;
    const contactGeometry o = virtualMeshOverlap().evaluate(inside, wall, cube, p, fine);
    std::cout << "tube: exact " << g.volume() << ", octree " << o.volume() << std::endl;
    ASSERT_EQ(o.regions.size(), 1u);
    // the octree's 1% at level 5; 0.02 (about a degree) its normal's
    EXPECT_NEAR(g.volume(), o.volume(), 0.01*g.volume());
    EXPECT_LT((g.regions[0].normal - o.regions[0].normal).norm(), 0.02);
    // The wall's S points from the wall into the cube, towards the axis
    EXPECT_LT(g.regions[0].areaVector.dot(nf), 0);

    const bodyPose q2 = cube.poseFromFilePlacement
    (
        bodyPose::axisAngle(vec3(0, 0, 1), M_PI/24), (rf + a - 3e-5)*nf + vec3(0, 0, 0.02) + 0.006*vec3(-nf.y(), nf.x(), 0)
    );
    const contactGeometry pg = virtualMeshOverlap().evaluate(outside, wall, cube, q2, s);
    ASSERT_FALSE(pg.regions.empty());
    EXPECT_GT(pg.leaves, 0);
}


TEST(convexOverlap, slabThroughABlockKeepsItsAreaMoment)
{
    // A plate 0.2 mm thick, wider than the block, through a sheared block
    // (a parallelepiped whose sides lean 0.5 along x): A's faces inside B
    // are the plate's two faces, of equal area (the block's sections at
    // two heights are translates) and opposite, so S = 0 (a translation
    // leaves the volume unchanged) but their centroids are apart, so a
    // rotation does not: M against the central difference of the volume
    // (tolerance 1e-6 of |M|: the difference's own error at a step of
    // 1e-7 rad)
    const triangleMeshShape plate(primitiveMeshes::box(vec3(0.01, 0.01, 0.0001)), "plate");
    triangleSoup sheared = primitiveMeshes::box(vec3(0.002, 0.003, 0.0025));
    mat3 shear = mat3::Identity();
    shear(0, 2) = 0.5;
    primitiveMeshes::transform(sheared, shear, vec3::Zero());
    const triangleMeshShape block(sheared, "sheared block");
    const quat tilt = bodyPose::axisAngle(vec3(1, 0.3, 0), 0.4);
    const bodyPose pA = plate.poseFromFilePlacement(tilt, tilt*vec3(0.0002, 0.0001, 0.0003));
    const bodyPose pB = block.poseFromFilePlacement(tilt, vec3::Zero());
    const contactGeometry g = convexOverlap().evaluate(plate, pA, block, pB, {});
    ASSERT_EQ(g.regions.size(), 1u);
    const contactRegion& r = g.regions[0];
    // |S| below 1e-9 of a face's area (V over the thickness): it vanishes
    EXPECT_LT(r.areaVector.norm(), 1e-9*r.volume/0.0002);
    ASSERT_GT(r.areaMoment.norm(), 1e-3*r.volume);
    vec3 fd;
    const double h = 1e-7;
    for (int i = 0; i < 3; ++i)
    {
        auto turned = [&](double a)
        {
            const quat q(Eigen::AngleAxisd(a, vec3::Unit(i)));
            const bodyPose p(r.point + q*(pB.position() - r.point), q*pB.orientation());
            return convexOverlap().evaluate(plate, pA, block, p, {}).volume();
        };
        fd[i] = (turned(h) - turned(-h))/(2*h);
    }
    EXPECT_LT((fd + r.areaMoment).norm(), 1e-6*r.areaMoment.norm());   // the differences' error
}
