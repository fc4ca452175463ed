/*---------------------------------------------------------------------------*\
Description
    Tests of the exact (CGAL intersection solid) contact-geometry engine:
    analytic overlaps of boxes, the sphere lens on icospheres, non-convex
    pairs with two regions, and the agreement of virtualMesh at level 4 with
    it (the acceptance figures: 0.5 % for convex, 1 % for non-convex).
\*---------------------------------------------------------------------------*/

#include "exactOverlap.H"
#include "sphereOverlap.H"
#include "virtualMeshOverlap.H"
#include "sphereShape.H"
#include "triangleMeshShape.H"
#include "primitiveMeshes.H"
#include "testHelpers.H"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>

using namespace immersedDEM;
using immersedDEM::test::relErr;

namespace
{

double angleDeg(const vec3& a, const vec3& b)
{
    return std::acos(std::max(-1.0, std::min(1.0, a.normalized().dot(b.normalized()))))*180/M_PI;
}

// Lowest world z of a posed mesh
double lowestZ(const shape& s, const bodyPose& p)
{
    double z = std::numeric_limits<double>::max();
    for (const vec3& x : s.surface().points) z = std::min(z, p.toWorld(x).z());
    return z;
}

// Seconds per call of f, over n calls
template<class F>
double secondsPerCall(F f, int n)
{
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < n; ++i) f();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()/n;
}

} // End anonymous namespace


TEST(exactOverlap, selectedByName)
{
    EXPECT_EQ(overlapEngine::New("exact")->type(), "exact");
}


TEST(exactOverlap, boxIntoBoxIsExact)
{
    // B's bottom face pushed 0.3 mm into A's top face, offset sideways but
    // within it: the overlap is a 4 x 3 x 0.3 mm box
    const triangleMeshShape A(primitiveMeshes::box(vec3(0.004, 0.004, 0.002)), "A");
    const triangleMeshShape B(primitiveMeshes::box(vec3(0.002, 0.0015, 0.002)), "B");
    const double depth = 0.0003;
    const vec3 offset(0.0004, -0.0003, 0);
    const bodyPose pA = A.poseFromFilePlacement(quat::Identity(), vec3::Zero());
    const bodyPose pB = B.poseFromFilePlacement
    (
        quat::Identity(), offset + vec3(0, 0, 0.002 + 0.002 - depth)
    );
    const auto g = exactOverlap().evaluate(A, pA, B, pB, {});
    ASSERT_EQ(g.regions.size(), 1u);
    const contactRegion& r = g.regions[0];
    EXPECT_LT(relErr(r.volume, 0.004*0.003*depth), 1e-9);
    EXPECT_LT((r.normal - vec3::UnitZ()).norm(), 1e-9);
    EXPECT_LT((r.point - vec3(offset.x(), offset.y(), 0.002 - depth/2)).norm(), 1e-12);
    EXPECT_LT(relErr(r.area, 0.004*0.003), 1e-9);
    EXPECT_EQ(g.queries, 0);
    EXPECT_EQ(g.leaves, 0);
}


TEST(exactOverlap, rotatedBoxesAgreeWithVirtualMesh)
{
    // B turned 0.4 rad about z and tilted 0.1 rad about x, its lowest
    // corner 0.4 mm into A's top face: a slanted, non-axis-aligned overlap
    const triangleMeshShape A(primitiveMeshes::box(vec3(0.004, 0.004, 0.002)), "A");
    const triangleMeshShape B(primitiveMeshes::box(vec3(0.002, 0.0015, 0.002)), "B");
    const quat q = bodyPose::axisAngle(vec3(0, 0, 1), 0.4)*bodyPose::axisAngle(vec3(1, 0, 0), 0.1);
    const bodyPose pA = A.poseFromFilePlacement(quat::Identity(), vec3::Zero());
    bodyPose pB = B.poseFromFilePlacement(q, vec3(0.0005, 0.0002, 0));
    pB = B.poseFromFilePlacement
    (
        q, vec3(0.0005, 0.0002, 0.002 - 0.0004 - lowestZ(B, pB))
    );

    const auto ex = exactOverlap().evaluate(A, pA, B, pB, {});
    const auto vm = virtualMeshOverlap().evaluate(A, pA, B, pB, {0.0005, 4});
    ASSERT_EQ(ex.regions.size(), 1u);
    ASSERT_EQ(vm.regions.size(), 1u);
    std::cout << "rotated boxes: exact " << ex.volume() << ", virtualMesh " << vm.volume()
        << " (rel " << relErr(vm.volume(), ex.volume()) << ")" << std::endl;
    // 0.5%: the virtual mesh's accuracy at its default resolution (the
    // contact resolution tolerance); exact is the reference here
    EXPECT_LT(relErr(vm.volume(), ex.volume()), 0.005);
    // A's surface inside B is all on its top face: the normal is +z
    EXPECT_LT((ex.regions[0].normal - vec3::UnitZ()).norm(), 1e-9);
    EXPECT_LT(angleDeg(vm.regions[0].normal, ex.regions[0].normal), 1.0);
}


TEST(exactOverlap, icospheresMatchVirtualMeshAndConvergeToTheLens)
{
    // Two spheres overlapping by 2 % of d along a skew line. An icosphere is
    // inscribed in its sphere, so its overlap is inside the lens and falls
    // short of it by the tessellation error, second order in the edge
    // length: ~7 % at level 4 (a contact disc ~6 edges across), a sixteenth
    // of it at level 6. virtualMesh must match exact on the same meshes.
    const double R = 0.005, d = 2*R;
    const vec3 c2(0.0013, 0.0021, 0.0007);
    const vec3 c1 = c2 - (d - 0.02*d)*vec3(1, 2, 3).normalized();
    const auto lens = sphereOverlap::lens(c1, R, c2, R);

    const triangleMeshShape s4(primitiveMeshes::icosphere(R, 4), "icosphere4");
    const bodyPose pA4 = s4.poseFromFilePlacement(quat::Identity(), c1);
    const bodyPose pB4 = s4.poseFromFilePlacement(quat::Identity(), c2);
    const auto ex = exactOverlap().evaluate(s4, pA4, s4, pB4, {});
    const auto vm = virtualMeshOverlap().evaluate(s4, pA4, s4, pB4, {d/20, 4});
    ASSERT_EQ(ex.regions.size(), 1u);
    ASSERT_EQ(vm.regions.size(), 1u);
    const double err4 = relErr(ex.volume(), lens.volume());
    std::cout << "icospheres level 4: lens " << lens.volume() << ", exact " << ex.volume()
        << " (rel " << err4 << "), virtualMesh " << vm.volume()
        << " (rel to exact " << relErr(vm.volume(), ex.volume()) << ")" << std::endl;
    EXPECT_LT(relErr(vm.volume(), ex.volume()), 0.005);     // as above
    EXPECT_LT(ex.volume(), lens.volume());
    // 0.5 degree, 1e-3 R: the facets of a level-4 icosphere (edges R/13)
    // tilt the exact polyhedral lens's normal and move its centroid by
    // that much against the spheres'
    EXPECT_LT(angleDeg(ex.regions[0].normal, c2 - c1), 0.5);
    EXPECT_LT((ex.regions[0].point - lens.regions[0].point).norm(), 1e-3*R);

    const triangleMeshShape s6(primitiveMeshes::icosphere(R, 6), "icosphere6");
    const auto ex6 = exactOverlap().evaluate
    (
        s6, s6.poseFromFilePlacement(quat::Identity(), c1),
        s6, s6.poseFromFilePlacement(quat::Identity(), c2),
        {}
    );
    ASSERT_EQ(ex6.regions.size(), 1u);
    const double err6 = relErr(ex6.volume(), lens.volume());
    std::cout << "icospheres level 6: exact " << ex6.volume() << " (rel " << err6
        << "), area rel " << relErr(ex6.regions[0].area, lens.regions[0].area) << std::endl;
    EXPECT_LT(err6, 0.01);      // the level-6 facets' own deficit in the lens
    EXPECT_GT(err4/err6, 10);       // second order: 16 for exact halvings
    EXPECT_LT(angleDeg(ex6.regions[0].normal, c2 - c1), 0.5);
    EXPECT_LT((ex6.regions[0].point - lens.regions[0].point).norm(), 1e-3*R);
    EXPECT_LT(relErr(ex6.regions[0].area, lens.regions[0].area), 0.01);   // as the volume's
}


TEST(exactOverlap, threadedToriGiveTwoRegions)
{
    // B is A turned 90 degrees about x: its centre circle, in the x-z plane,
    // crosses A's centre circle at x = -R and x = +R. Shifted by s along x,
    // B's circle passes through A's hole (linked) and the tubes cross at
    // x ~ -R and x ~ +R with their axes s apart: two regions 2R apart.
    // (Shifted by R they would be the classic chain link, axes R > 2r
    // apart everywhere: no contact.)
    const double R = 0.01, r = 0.003, s = 0.001;
    const triangleSoup torus = primitiveMeshes::torus(R, r, 64, 32);
    const triangleMeshShape A(torus, "A");
    const triangleMeshShape B(torus, "B");
    const bodyPose pA = A.poseFromFilePlacement(quat::Identity(), vec3::Zero());
    const bodyPose pB = B.poseFromFilePlacement
    (
        bodyPose::axisAngle(vec3(1, 0, 0), M_PI/2), vec3(s, 0, 0)
    );

    const exactOverlap exact;
    const virtualMeshOverlap virtualMesh;
    const overlapSettings settings{0.001, 4};
    contactGeometry ex, vm;
    const double tEx = secondsPerCall([&]{ ex = exact.evaluate(A, pA, B, pB, settings); }, 1);
    const double tVm = secondsPerCall([&]{ vm = virtualMesh.evaluate(A, pA, B, pB, settings); }, 1);
    ASSERT_EQ(ex.regions.size(), 2u);
    EXPECT_EQ(vm.regions.size(), ex.regions.size());
    // One crossing near each of x = -R and x = +R
    EXPECT_GT(std::abs(ex.regions[0].point.x() - ex.regions[1].point.x()), 1.5*R);
    for (const contactRegion& cr : ex.regions)
    {
        // No larger than the bicylinder of two straight tubes, 16 r^3/3
        EXPECT_GT(cr.volume, 0.5*16*r*r*r/3);
        EXPECT_LT(cr.volume, 16*r*r*r/3);
        EXPECT_TRUE(cr.normal.allFinite());
        EXPECT_NEAR(cr.normal.norm(), 1, 1e-12);
    }
    std::cout << "tori: exact " << ex.volume() << " (" << ex.regions[0].volume << " + "
        << ex.regions[1].volume << ") in " << 1e3*tEx << " ms; virtualMesh "
        << vm.volume() << " in " << vm.regions.size() << " regions (rel "
        << relErr(vm.volume(), ex.volume()) << ") in " << 1e3*tVm << " ms" << std::endl;
    // 1%: the virtual mesh on curved, non-convex tori, twice its 0.5%
    // on the boxes and spheres above
    EXPECT_LT(relErr(vm.volume(), ex.volume()), 0.01);
}


TEST(exactOverlap, lBlockAgainstBoxGivesTwoRegions)
{
    // A box turned 45 degrees about z with its face across the tips of both
    // legs of an L (x + y = 16 mm at both tips), pushed 1 mm (along x and
    // along y) past them: each tip gives a triangular prism, legs 1 mm,
    // 4 mm high (the box spans the L's height, no coplanar faces)
    const std::vector<Eigen::Vector2d> L
    {
        {0, 0}, {0.012, 0}, {0.012, 0.004}, {0.004, 0.004}, {0.004, 0.012}, {0, 0.012}
    };
    const triangleMeshShape l(primitiveMeshes::extrudedPolygon(L, 0.004), "L");
    const triangleMeshShape box(primitiveMeshes::box(vec3(0.002, 0.008, 0.004)), "box");
    const double delta = 0.001;
    const vec3 n = vec3(1, 1, 0).normalized();
    const bodyPose pL = l.poseFromFilePlacement(quat::Identity(), vec3::Zero());
    const bodyPose pBox = box.poseFromFilePlacement
    (
        bodyPose::axisAngle(vec3(0, 0, 1), M_PI/4),
        vec3(0.008 - delta/2, 0.008 - delta/2, 0.002) + 0.002*n
    );

    const auto ex = exactOverlap().evaluate(l, pL, box, pBox, {});
    const auto vm = virtualMeshOverlap().evaluate(l, pL, box, pBox, {0.0005, 4});
    ASSERT_EQ(ex.regions.size(), 2u);
    const double prism = 0.5*delta*delta*0.004;
    for (const contactRegion& cr : ex.regions)
    {
        EXPECT_LT(relErr(cr.volume, prism), 1e-9);
        EXPECT_LT(angleDeg(cr.normal, n), 1e-6);
        // Centroid of the prism at either tip
        const vec3 tip = cr.point.x() > cr.point.y() ? vec3(0.012, 0.004, 0) : vec3(0.004, 0.012, 0);
        EXPECT_LT((cr.point - (tip - vec3(delta/3, delta/3, -0.002))).norm(), 1e-12);
    }
    std::cout << "L against box: exact " << ex.volume() << ", virtualMesh " << vm.volume()
        << " in " << vm.regions.size() << " regions (rel "
        << relErr(vm.volume(), ex.volume()) << ")" << std::endl;
    EXPECT_EQ(vm.regions.size(), 2u);
    EXPECT_LT(relErr(vm.volume(), ex.volume()), 0.01);  // as the tori's: two regions, edges
}


TEST(exactOverlap, needsTwoMeshes)
{
    const sphereShape s(0.005);
    const triangleMeshShape box(primitiveMeshes::box(vec3::Constant(0.005)), "box");
    EXPECT_TRUE(test::throwsCoreError
    (
        [&]{ exactOverlap().evaluate(s, bodyPose(), box, bodyPose(), {}); },
        {"'exact'", "sphere", "virtualMesh"}
    ));
    EXPECT_TRUE(test::throwsCoreError
    (
        [&]{ exactOverlap().evaluate(box, bodyPose(), s, bodyPose(), {}); },
        {"'exact'"}
    ));
}


TEST(exactOverlap, apartOrTouchingGiveNothing)
{
    const triangleMeshShape A(primitiveMeshes::box(vec3(0.004, 0.004, 0.002)), "A");
    const triangleMeshShape B(primitiveMeshes::box(vec3(0.002, 0.0015, 0.002)), "B");
    const bodyPose pA = A.poseFromFilePlacement(quat::Identity(), vec3::Zero());
    const exactOverlap exact;
    // Boxes apart
    EXPECT_TRUE(exact.evaluate
    (
        A, pA, B, B.poseFromFilePlacement(quat::Identity(), vec3(0, 0, 0.0041)), {}
    ).regions.empty());
    // Apart although their world boxes overlap: a cube turned 45 degrees
    // about z off A's vertical edge at x = y = 4 mm, its nearest side at
    // x + y = 8.48 mm
    const triangleMeshShape C(primitiveMeshes::box(vec3::Constant(0.0015)), "C");
    const bodyPose pC = C.poseFromFilePlacement
    (
        bodyPose::axisAngle(vec3(0, 0, 1), M_PI/4), vec3(0.0053, 0.0053, 0)
    );
    ASSERT_TRUE(A.worldBox(pA).overlaps(C.worldBox(pC)));
    EXPECT_TRUE(exact.evaluate(A, pA, C, pC, {}).regions.empty());
    // Face to face, touching
    EXPECT_TRUE(exact.evaluate
    (
        A, pA, B, B.poseFromFilePlacement(quat::Identity(), vec3(0.0004, -0.0003, 0.004)), {}
    ).regions.empty());
    // Edge on face, touching (to round-off)
    const quat q = bodyPose::axisAngle(vec3(1, 0, 0), M_PI/4);
    const double zC = 0.002 - lowestZ(C, C.poseFromFilePlacement(q, vec3::Zero()));
    EXPECT_TRUE(exact.evaluate
    (
        A, pA, C, C.poseFromFilePlacement(q, vec3(0.0002, 0.0001, zC)), {}
    ).regions.empty());
}


TEST(exactOverlap, swapFlipsTheNormal)
{
    const triangleMeshShape A(primitiveMeshes::icosphere(0.005, 2), "A");
    const triangleMeshShape B(primitiveMeshes::box(vec3(0.002, 0.0015, 0.002)), "B");
    const bodyPose pA = A.poseFromFilePlacement(quat::Identity(), vec3::Zero());
    const bodyPose pB = B.poseFromFilePlacement
    (
        bodyPose::axisAngle(vec3(1, -2, 0.5), 0.7), vec3(0.003, 0.004, 0.002)
    );
    const exactOverlap exact;
    const auto ab = exact.evaluate(A, pA, B, pB, {});
    const auto ba = exact.evaluate(B, pB, A, pA, {});
    ASSERT_EQ(ab.regions.size(), 1u);
    ASSERT_EQ(ba.regions.size(), 1u);
    EXPECT_LT(relErr(ba.volume(), ab.volume()), 1e-9);
    EXPECT_LT(angleDeg(ba.regions[0].normal, -ab.regions[0].normal), 1e-6);
    EXPECT_LT((ba.regions[0].point - ab.regions[0].point).norm(), 1e-12);
    EXPECT_LT(relErr(ba.regions[0].area, ab.regions[0].area), 1e-9);
    // From the sphere towards the box
    EXPECT_GT(ab.regions[0].normal.dot(pB.position() - pA.position()), 0);
}


TEST(exactOverlap, bodyInsideTheOtherFallsBackToTheCentreLine)
{
    // No surface of the big box inside the small one: the normal is the
    // line between the centres, the volume the small box's
    const triangleMeshShape A(primitiveMeshes::box(vec3(0.004, 0.004, 0.002)), "A");
    const triangleMeshShape B(primitiveMeshes::box(vec3(0.001, 0.0005, 0.0005)), "B");
    const bodyPose pA = A.poseFromFilePlacement(quat::Identity(), vec3::Zero());
    const bodyPose pB = B.poseFromFilePlacement
    (
        bodyPose::axisAngle(vec3(0, 1, 1), 0.3), vec3(0.001, 0.0005, 0.0002)
    );
    const auto g = exactOverlap().evaluate(A, pA, B, pB, {});
    ASSERT_EQ(g.regions.size(), 1u);
    EXPECT_LT(relErr(g.volume(), 0.002*0.001*0.001), 1e-9);
    EXPECT_LT(angleDeg(g.regions[0].normal, vec3(0.001, 0.0005, 0.0002)), 1e-6);
    EXPECT_LT((g.regions[0].point - pB.position()).norm(), 1e-12);
    EXPECT_NEAR(g.regions[0].area, 0, 1e-12);

    // Concentric: no centre line either
    const auto c = exactOverlap().evaluate(A, pA, B, B.poseFromFilePlacement(quat::Identity(), vec3::Zero()), {});
    ASSERT_EQ(c.regions.size(), 1u);
    EXPECT_EQ(c.regions[0].normal, vec3::UnitX());
}
