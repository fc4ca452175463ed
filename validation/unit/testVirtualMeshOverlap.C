// The virtual mesh (virtualMeshOverlap) against analytic lenses and exact
// volumes (its octree: two spheres otherwise take the lens itself):
// accuracy, cost growth, pose invariance, regions, errors.

#include "overlapEngine.H"
#include "sphereOverlap.H"
#include "virtualMeshOverlap.H"
#include "sphereShape.H"
#include "halfSpaceShape.H"
#include "triangleMeshShape.H"
#include "wallMeshShape.H"
#include "primitiveMeshes.H"
#include "coreError.H"
#include "testHelpers.H"

#include <gtest/gtest.h>

#include <cmath>

using namespace immersedDEM;

namespace
{

const double R = 0.005, d = 0.01, h = d/20;

double angleDeg(const vec3& a, const vec3& b)
{
    return std::acos(std::max(-1.0, std::min(1.0, a.normalized().dot(b.normalized()))))*180/M_PI;
}

// Two spheres overlapping by a fraction of the diameter along a skew line
struct spherePair
{
    vec3 c2, c1;    // c1 is made from c2
    explicit spherePair(double frac)
    :
        c2(0.0013, 0.0021, 0.0007),
        c1(c2 - (d - frac*d)*vec3(1, 2, 3).normalized())
    {}
};

// A mesh whose search is always the full one (shape's closestNear: the
// closest point wherever it is), as the octree searched before it
// searched a child cell's mesh only within the cell's ball
struct fullSearchMesh : triangleMeshShape
{
    using triangleMeshShape::triangleMeshShape;
    bool closestNear
    (
        const vec3& p, double radius, double distanceBound, surfacePoint& sp
    ) const override
    {
        return shape::closestNear(p, radius, distanceBound, sp);
    }
};

} // End anonymous namespace


class virtualMeshSphereSphere : public ::testing::TestWithParam<double> {};

TEST_P(virtualMeshSphereSphere, level4MatchesAnalyticLens)
{
    const spherePair p(GetParam());
    const sphereShape s(R);
    const auto g = virtualMeshOverlap().evaluate
    (
        s, bodyPose(p.c1, quat::Identity()), s, bodyPose(p.c2, quat::Identity()), test::octree(h, 4)
    );
    const auto ref = sphereOverlap::lens(p.c1, R, p.c2, R);
    ASSERT_EQ(g.regions.size(), 1u);
    EXPECT_NEAR(g.volume()/ref.volume(), 1, 0.005);
    EXPECT_LT(angleDeg(g.regions[0].normal, ref.regions[0].normal), 0.5);
    EXPECT_LT((g.regions[0].point - ref.regions[0].point).norm(), h/16);
    EXPECT_NEAR(g.regions[0].area/ref.regions[0].area, 1, 0.1);
}

INSTANTIATE_TEST_SUITE_P
(
    overlapFractions, virtualMeshSphereSphere,
    ::testing::Values(0.005, 0.01, 0.02, 0.035, 0.05)
);


TEST(virtualMesh, spheresAndPlanesTakeTheAnalyticAnswer)
{
    // Two spheres of different sizes, and a sphere against a plane (either
    // order): the lens and the cap themselves, without a query; a lens
    // refined by the octree costs thousands (a suspension in a periodic
    // box, where the DEM's sphere sweep is off, took 2 ms per contact)
    const sphereShape s(R), small(0.6*R);
    // centres 0.1 of the smaller diameter closer than touching
    const vec3 c1(0.0013, 0.0021, 0.0007);
    const vec3 c2 = c1 + (1.6*R - 0.12*R)*vec3(1, 2, 3).normalized();
    const bodyPose p1(c1, quat::Identity()), p2(c2, quat::Identity());
    const virtualMeshOverlap vm;
    const overlapSettings fine{h/4, 6};
    const auto g = vm.evaluate(s, p1, small, p2, fine);
    const auto lens = sphereOverlap::lens(c1, R, c2, 0.6*R);
    ASSERT_EQ(g.regions.size(), 1u);
    ASSERT_EQ(lens.regions.size(), 1u);
    EXPECT_EQ(g.queries, 0);
    // the same arithmetic: equal to rounding
    EXPECT_NEAR(g.volume()/lens.volume(), 1, 1e-14);
    EXPECT_LT((g.regions[0].point - lens.regions[0].point).norm(), 1e-15);
    EXPECT_LT((g.regions[0].normal - lens.regions[0].normal).norm(), 1e-15);
    // The octree on the same pair: close (within its 0.5% at level 4), and
    // not free
    const auto o = vm.evaluate(s, p1, small, p2, test::octree(h, 4));
    EXPECT_NEAR(o.volume()/lens.volume(), 1, 0.005);
    EXPECT_GT(o.queries, 100);

    // A plane through the origin with normal (1, 2, 3)/|.|, the sphere
    // 0.3 R into it
    const vec3 n = vec3(1, 2, 3).normalized();
    const halfSpaceShape plane;
    const bodyPose pP = halfSpaceShape::poseOf(vec3::Zero(), n);
    const vec3 c = 0.7*R*n;
    const auto cap = sphereOverlap::cap(vec3::Zero(), n, c, R);
    ASSERT_EQ(cap.regions.size(), 1u);
    const auto gw = vm.evaluate(plane, pP, s, bodyPose(c, quat::Identity()), fine);
    const auto gs = vm.evaluate(s, bodyPose(c, quat::Identity()), plane, pP, fine);
    ASSERT_EQ(gw.regions.size(), 1u);
    ASSERT_EQ(gs.regions.size(), 1u);
    EXPECT_NEAR(gw.volume()/cap.volume(), 1, 1e-14);
    EXPECT_NEAR(gs.volume()/cap.volume(), 1, 1e-14);
    EXPECT_LT((gw.regions[0].normal - n).norm(), 1e-12);     // from A, the plane, to B
    EXPECT_LT((gs.regions[0].normal + n).norm(), 1e-12);
    EXPECT_EQ(gw.queries + gs.queries, 0);
}


TEST(virtualMesh, sphereInATanksCornerTakesOneCapPerWall)
{
    // An open box tank 100 mm wide of 10 mm squares (a blockMesh patch),
    // a sphere of radius 5 mm in its corner: the floor and two sides
    // within its reach, so no flat wall; a new user's spheres there cost
    // 97% of the run on the octree at d/320. Where the caps behind the
    // planes are apart, their sum is the overlap with the wall's solid,
    // exactly and without a query
    const wallMeshShape tank(primitiveMeshes::openBox(vec3(0, 0, 0), vec3(0.1, 0.1, 0.1), 10), "tank", 0.02);
    const bodyPose wall;
    const sphereShape s(R);
    const overlapSettings exact{0.0005, 4};
    // The octree on the same pairs, finer: leaves of h/32 = 16 um on caps
    // 0.4-0.8 mm deep
    const overlapSettings octree = test::octree(0.0005, 5);

    struct corner
    {
        vec3 centre;
        size_t caps;
    };
    // Three walls crossed (0.4, 0.6 and 0.8 mm in), two (a side and the
    // floor, away from the corner), and one (the floor near the sides,
    // which do not reach the sphere: the flat wall's cap)
    for
    (
        const corner& k :
        {
            corner{vec3(R - 0.0004, R - 0.0006, R - 0.0008), 3},
            corner{vec3(0.05, R - 0.0006, R - 0.0008), 2},
            corner{vec3(R + 0.0002, R + 0.0003, R - 0.0008), 1}
        }
    )
    {
        const bodyPose pS(k.centre, quat::Identity());
        // The caps by hand: each wall plane through the origin, normal
        // into the tank
        double capsVolume = 0;
        for (int i = 0; i < 3; ++i)
        {
            if (k.centre[i] < R)
            {
                capsVolume += sphereOverlap::cap(vec3::Zero(), vec3::Unit(i), k.centre, R).volume();
            }
        }
        // (Against the floor alone the flat wall's cap answers whatever
        // the settings: no octree to compare with)
        const contactGeometry o = k.caps > 1
            ? virtualMeshOverlap().evaluate(tank, wall, s, pS, octree)
            : sphereOverlap::cap(vec3::Zero(), vec3::UnitZ(), k.centre, R);
        if (k.caps > 1) EXPECT_GT(o.queries, 1000);
        for (const bool wallFirst : {true, false})
        {
            const contactGeometry g = wallFirst
                ? virtualMeshOverlap().evaluate(tank, wall, s, pS, exact)
                : virtualMeshOverlap().evaluate(s, pS, tank, wall, exact);
            ASSERT_EQ(g.regions.size(), k.caps);
            EXPECT_EQ(g.queries, 0);
            // The same arithmetic as the caps by hand: equal to rounding
            EXPECT_NEAR(g.volume()/capsVolume, 1, 1e-12);
            // The octree's volume: within 1%, its accuracy at this level
            // (the sphere-sphere lens at level 4 is within 0.5%, above)
            EXPECT_NEAR(o.volume()/capsVolume, 1, 0.01);
            // Each region along its wall's normal, from the first body
            // into the second: into the tank for the wall first
            for (const contactRegion& r : g.regions)
            {
                EXPECT_GT(r.normal.cwiseAbs().maxCoeff(), 1 - 1e-12);
                EXPECT_GT((wallFirst ? 1 : -1)*r.normal.sum(), 0);
            }
        }
    }

    // Off the floor, pressed 2.5 mm into both sides of a vertical edge:
    // the region behind both sides is 2.5 sqrt(2) = 3.5 mm from the
    // centre, inside the sphere, so the two caps share a part (4.8% of
    // their sum by Monte Carlo, above the octree's 1%) and their sum is
    // not the overlap: the octree's, with queries
    const bodyPose pressed(vec3(R - 0.0025, R - 0.0025, 0.05), quat::Identity());
    const contactGeometry g = virtualMeshOverlap().evaluate(tank, wall, s, pressed, exact);
    EXPECT_GT(g.queries, 0);
    const double twoCaps = 2*sphereOverlap::cap(vec3::Zero(), vec3::UnitX(), pressed.position(), R).volume();
    // 0.952 of the sum, give or take the octree's 1%: below 0.98 of it
    EXPECT_LT(g.volume(), 0.98*twoCaps);
    EXPECT_GT(g.volume(), 0.92*twoCaps);
    // Far from every wall: no region, no query
    const contactGeometry none = virtualMeshOverlap().evaluate
    (
        tank, wall, s, bodyPose(vec3(0.05, 0.05, 0.05), quat::Identity()), exact
    );
    EXPECT_TRUE(none.regions.empty());
    EXPECT_EQ(none.queries, 0);
}


TEST(virtualMesh, costGrowsLikeASurface)
{
    const spherePair p(0.02);
    const sphereShape s(R);
    long previous = 0;
    for (int L = 0; L <= 5; ++L)
    {
        const auto g = virtualMeshOverlap().evaluate
        (
            s, bodyPose(p.c1, quat::Identity()), s, bodyPose(p.c2, quat::Identity()), test::octree(h, L)
        );
        if (L >= 2)
        {
            EXPECT_LT(double(g.queries)/previous, 4.5) << "level " << L;
        }
        previous = g.queries;
    }
}


TEST(virtualMesh, rigidMotionOfThePairAndSwap)
{
    // A box pressed into a rotated box: move and rotate the pair as a whole
    const triangleMeshShape A(primitiveMeshes::box(vec3(0.004, 0.003, 0.002)), "A");
    const triangleMeshShape B(primitiveMeshes::box(vec3(0.002, 0.002, 0.002)), "B");
    // Poses place the shapes as given (their principal frames may be permuted)
    const bodyPose pA = A.poseFromFilePlacement(quat::Identity(), vec3::Zero());
    const bodyPose pB = B.poseFromFilePlacement
    (
        bodyPose::axisAngle(vec3(0, 0, 1), 0.4), vec3(0.0005, 0.0002, 0.0037)
    );
    const virtualMeshOverlap vm;
    const auto g0 = vm.evaluate(A, pA, B, pB, {h, 4});
    ASSERT_EQ(g0.regions.size(), 1u);
    const bodyPose M(vec3(0.0123, -0.0071, 0.0033), bodyPose::axisAngle(vec3(1, -2, 0.5), 1.1));
    const auto g1 = vm.evaluate(A, M*pA, B, M*pB, {h, 4});
    ASSERT_EQ(g1.regions.size(), 1u);
    EXPECT_NEAR(g1.volume()/g0.volume(), 1, 0.005);
    EXPECT_LT(angleDeg(g1.regions[0].normal, M.vectorToWorld(g0.regions[0].normal)), 1.0);
    EXPECT_LT((g1.regions[0].point - M.toWorld(g0.regions[0].point)).norm(), h/8);

    const auto gs = vm.evaluate(B, pB, A, pA, {h, 4});
    ASSERT_EQ(gs.regions.size(), 1u);
    EXPECT_NEAR(gs.volume()/g0.volume(), 1, 1e-12);
    EXPECT_LT(angleDeg(gs.regions[0].normal, -g0.regions[0].normal), 1e-6);
    // B's bottom face (rotated, within A's top face) 0.3 mm into A: the
    // overlap is a prism of that depth and the normal +z from A to B
    EXPECT_NEAR(g0.volume()/(0.004*0.004*0.0003), 1, 0.005);
    EXPECT_LT(angleDeg(g0.regions[0].normal, vec3::UnitZ()), 0.5);
}


TEST(virtualMesh, boxIntoBoxExactVolume)
{
    // B's bottom 0.3 mm pushed into A's top face; the overlap is a box
    const triangleMeshShape A(primitiveMeshes::box(vec3(0.004, 0.004, 0.002)), "A");
    const triangleMeshShape B(primitiveMeshes::box(vec3(0.002, 0.0015, 0.002)), "B");
    const double depth = 0.0003;
    const bodyPose pA = A.poseFromFilePlacement(quat::Identity(), vec3::Zero());
    const bodyPose pB = B.poseFromFilePlacement
    (
        quat::Identity(), vec3(0.0004, -0.0003, 0.002 + 0.002 - depth)
    );
    const auto g = virtualMeshOverlap().evaluate(A, pA, B, pB, {h, 4});
    ASSERT_EQ(g.regions.size(), 1u);
    EXPECT_NEAR(g.volume()/(0.004*0.003*depth), 1, 0.005);
    EXPECT_LT(angleDeg(g.regions[0].normal, vec3::UnitZ()), 0.5);
    EXPECT_NEAR(g.regions[0].point.z(), 0.002 - depth/2, h/16);
    EXPECT_NEAR(g.regions[0].area/(0.004*0.003), 1, 0.1);
}


TEST(virtualMesh, twoProngsGiveTwoRegions)
{
    // A U-shaped block whose two prongs dip into a slab: two separate boxes
    const std::vector<Eigen::Vector2d> U
    {
        {0, 0}, {0.012, 0}, {0.012, 0.008}, {0.009, 0.008}, {0.009, 0.003},
        {0.003, 0.003}, {0.003, 0.008}, {0, 0.008}
    };
    const triangleMeshShape u(primitiveMeshes::extrudedPolygon(U, 0.004), "U");
    const triangleMeshShape slab(primitiveMeshes::box(vec3(0.01, 0.002, 0.01)), "slab");
    // Put the U (file frame) with prong tips at y = 0.008 into the slab
    // whose bottom face is at y = 0.0075: each prong overlaps 3 x 0.5 x 4 mm
    const bodyPose pU = u.poseFromFilePlacement(quat::Identity(), vec3::Zero());
    const bodyPose pS = slab.poseFromFilePlacement
    (
        quat::Identity(), vec3(0.006, 0.0075 + 0.002, 0.002)
    );
    const auto g = virtualMeshOverlap().evaluate(u, pU, slab, pS, {h, 4});
    ASSERT_EQ(g.regions.size(), 2u);
    for (const contactRegion& r : g.regions)
    {
        EXPECT_NEAR(r.volume/(0.003*0.0005*0.004), 1, 0.01);
        EXPECT_LT(angleDeg(r.normal, vec3::UnitY()), 0.5);
    }
}


TEST(virtualMesh, apartGivesNothingAndBadSettingsThrow)
{
    const sphereShape s(R);
    const virtualMeshOverlap vm;
    const auto g = vm.evaluate(s, bodyPose(), s, bodyPose(vec3(0.0101, 0, 0), quat::Identity()), test::octree(h, 4));
    EXPECT_TRUE(g.regions.empty());
    EXPECT_EQ(g.volume(), 0);
    EXPECT_THROW(vm.evaluate(s, bodyPose(), s, bodyPose(), {0, 4}), coreError);
    EXPECT_THROW(vm.evaluate(s, bodyPose(), s, bodyPose(), {h, -1}), coreError);
}


TEST(virtualMesh, normalIsStableUnderSmallPoseChanges)
{
    // Two non-convex bodies (tori) crossing; tiny moves of B must not flip
    // or jump the normal, and it is never NaN
    const triangleMeshShape A(primitiveMeshes::torus(0.004, 0.0015, 48, 24), "A");
    const triangleMeshShape B(primitiveMeshes::torus(0.004, 0.0015, 48, 24), "B");
    const bodyPose pA = A.poseFromFilePlacement(quat::Identity(), vec3::Zero());
    const virtualMeshOverlap vm;
    vec3 previous = vec3::Zero();
    for (int k = 0; k < 20; ++k)
    {
        const double eps = 1e-6*k;
        const bodyPose pB = B.poseFromFilePlacement
        (
            bodyPose::axisAngle(vec3(1, 0, 0), M_PI/2 + eps),
            vec3(0.0004 + eps, 0.0001, 0)
        );
        const auto g = vm.evaluate(A, pA, B, pB, {h, 3});
        ASSERT_FALSE(g.regions.empty());
        const vec3 n = g.regions[0].normal;
        ASSERT_TRUE(n.allFinite());
        EXPECT_NEAR(n.norm(), 1, 1e-12);
        if (k > 0)
        {
            EXPECT_GT(n.dot(previous), std::cos(2*M_PI/180)) << "step " << k;
        }
        previous = n;
    }
}


TEST(virtualMesh, searchWithinTheCellIsTheFullSearch)
{
    // The octree searches a child cell's mesh only within the cell's ball
    // and puts a cell no surface enters on its parent's side: the regions
    // (volume, point, normal, area, area vector and moment) and the work
    // must be those of the full search, bit for bit. Two crossing tori
    // (curved, non-convex, two regions) and a box's corner into a torus,
    // near the origin and 2.6 m from it (the lattice's round-off there)
    const triangleSoup torus = primitiveMeshes::torus(0.004, 0.0015, 48, 24);
    const triangleSoup box = primitiveMeshes::box(vec3(0.003, 0.002, 0.0025));
    const triangleMeshShape torusA(torus, "torusA"), torusB(torus, "torusB");
    const fullSearchMesh fullA(torus, "torusA"), fullB(torus, "torusB");
    const triangleMeshShape boxS(box, "box");
    const fullSearchMesh fullBox(box, "box");
    // (as overlapConvergenceBenchmark's: B's tube crosses A's twice, 0.4
    // mm deep; the box's corner into A's tube)
    const bodyPose pA = torusA.poseFromFilePlacement(quat::Identity(), vec3::Zero());
    const bodyPose pB = torusB.poseFromFilePlacement
    (
        bodyPose::axisAngle(vec3(1, 0, 0), M_PI/2), vec3(2*0.0015 - 0.0004, 0, 0)
    );
    const bodyPose pC = boxS.poseFromFilePlacement
    (
        bodyPose::axisAngle(vec3(1, -1, 0.3), 0.7), vec3(0.0048, 0.0046, 0.0031)
    );
    const virtualMeshOverlap vm;
    int compared = 0;
    for (const vec3& far : {vec3(0, 0, 0), vec3(0.7, -1.3, 2.1)})
    {
        const bodyPose M(far, bodyPose::axisAngle(vec3(0.2, 1, -0.4), 0.3));
        for (int pair = 0; pair < 2; ++pair)
        {
            const shape& A = torusA;
            const shape& fA = fullA;
            const shape& B = pair == 0 ? static_cast<const shape&>(torusB) : boxS;
            const shape& fB = pair == 0 ? static_cast<const shape&>(fullB) : fullBox;
            const bodyPose& PB = pair == 0 ? pB : pC;
            for (const int L : {2, 4})
            {
                const overlapSettings o{h, L};
                const contactGeometry g = vm.evaluate(A, M*pA, B, M*PB, o);
                const contactGeometry f = vm.evaluate(fA, M*pA, fB, M*PB, o);
                ASSERT_EQ(g.regions.size(), f.regions.size());
                ASSERT_GE(g.regions.size(), pair == 0 ? 2u : 1u);
                EXPECT_EQ(g.queries, f.queries);
                EXPECT_EQ(g.leaves, f.leaves);
                for (size_t k = 0; k < g.regions.size(); ++k)
                {
                    const contactRegion& a = g.regions[k];
                    const contactRegion& b = f.regions[k];
                    EXPECT_GT(a.volume, 0);
                    EXPECT_EQ(a.volume, b.volume);
                    EXPECT_EQ(a.point, b.point);
                    EXPECT_EQ(a.normal, b.normal);
                    EXPECT_EQ(a.area, b.area);
                    EXPECT_EQ(a.areaVector, b.areaVector);
                    EXPECT_EQ(a.areaMoment, b.areaMoment);
                    ++compared;
                }
            }
        }
    }
    EXPECT_GE(compared, 12);
}
