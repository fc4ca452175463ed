/*---------------------------------------------------------------------------*\
Description
    The contact normal as the direction of the area vector (issue 19, item
    2; the gradient of the overlap volume with respect to B's translation,
    Feng, CMAME 373, 2021): an L-block across a cube, the arrangement
    mirror-symmetric in z, gives a normal in the mirror plane to 0.01
    degrees at levels 2-6 and with both bodies shifted by fractions of a
    cell; the plane fitted through the rim (the default) is printed beside
    it. The same with the roles swapped (the area vector of A's surface
    inside B: each of A's faces clipped exactly by the leaf and B's plane),
    and both area vectors against the exact volume's gradient.
\*---------------------------------------------------------------------------*/

#include "virtualMeshOverlap.H"
#include "exactOverlap.H"
#include "triangleMeshShape.H"
#include "primitiveMeshes.H"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

using namespace immersedDEM;

TEST(contactNormals, areaVectorNormalKeepsTheMirrorPlane)
{
    // An L (legs 12 mm, 4 mm wide, 4 mm high, z in [-2, 2] mm) turned -45
    // degrees about z, its outer corner 0.8 mm into the side x = 5 mm of a
    // 10 mm cube centred at the origin: mirror-symmetric in z = 0
    const std::vector<Eigen::Vector2d> L
    {
        {0, 0}, {0.012, 0}, {0.012, 0.004}, {0.004, 0.004}, {0.004, 0.012}, {0, 0.012}
    };
    const triangleMeshShape l(primitiveMeshes::extrudedPolygon(L, 0.004), "L");
    const triangleMeshShape cube(primitiveMeshes::box(vec3::Constant(0.005)), "cube");
    const double h = 0.0005;
    const double maxSine = std::sin(0.01*M_PI/180);
    const quat q = bodyPose::axisAngle(vec3(0, 0, 1), -0.25*M_PI);
    for (const double shift : {0.0, 0.11e-3, 0.37*h})
    {
        // The L's corner (file origin) at x = 5 - 0.8 mm; its height centred
        const vec3 s(0.3*shift, 0.7*shift, shift);
        const bodyPose pCube = cube.poseFromFilePlacement(quat::Identity(), s);
        const bodyPose pL = l.poseFromFilePlacement(q, s + vec3(0.0042, 0.0011, -0.002));
        vec3 exactS = vec3::Zero();
        for (int level = 2; level <= 6; ++level)
        {
            overlapSettings fitted{h, level};
            overlapSettings area{h, level};
            area.areaVectorNormal = true;
            const auto gF = virtualMeshOverlap().evaluate(cube, pCube, l, pL, fitted);
            const auto gA = virtualMeshOverlap().evaluate(cube, pCube, l, pL, area);
            ASSERT_EQ(gA.regions.size(), 1u);
            ASSERT_EQ(gF.regions.size(), 1u);
            std::cout << "shift " << shift << " level " << level << ": normal z fitted "
                << gF.regions[0].normal.z() << ", area vector " << gA.regions[0].normal.z()
                << std::endl;
            EXPECT_LT(std::abs(gA.regions[0].normal.z()), maxSine)
                << "shift " << shift << ", level " << level;
            EXPECT_NEAR(gA.regions[0].normal.norm(), 1, 1e-12);
            // With the roles swapped: the L's faces inside the cube, among
            // them its top and bottom, whose +z and -z contributions must
            // cancel. Sampled at the leaves' column centres they left the
            // plane by up to 2.6 degrees at level 2 (0.27 at level 6); the
            // faces clipped by the leaf and the cube's plane keep it
            const auto gS = virtualMeshOverlap().evaluate(l, pL, cube, pCube, area);
            ASSERT_EQ(gS.regions.size(), 1u);
            std::cout << "    swapped: area vector normal z " << gS.regions[0].normal.z()
                << std::endl;
            EXPECT_LT(std::abs(gS.regions[0].normal.z()), maxSine)
                << "swapped, shift " << shift << ", level " << level;
            // The area vector against the exact gradient of the volume
            // (central differences of the exact engine, once per shift):
            // A's faces clipped exactly where B is one plane in a leaf
            // (the L as A, the cube's face as B's plane) give it to
            // round-off; sampled at the column centres where B has edges
            // in the leaf (the cube as A), within 0.5%
            if (level == 2)
            {
                auto V = [&](const vec3& dx)
                {
                    const bodyPose p(pL.position() + dx, pL.orientation());
                    return exactOverlap().evaluate(cube, pCube, l, p, {}).volume();
                };
                const double e = 1e-7;
                for (int k = 0; k < 3; ++k)
                {
                    exactS[k] = -(V(e*vec3::Unit(k)) - V(-e*vec3::Unit(k)))/(2*e);
                }
            }
            EXPECT_LT((gS.regions[0].areaVector + exactS).norm(), 1e-6*exactS.norm())
                << "L as A, shift " << shift << ", level " << level;
            EXPECT_LT((gA.regions[0].areaVector - exactS).norm(), 5e-3*exactS.norm())
                << "cube as A, shift " << shift << ", level " << level;
            std::cout << "    exact S " << exactS.transpose() << ", cube as A "
                << gA.regions[0].areaVector.transpose() << ", L as A "
                << (-gS.regions[0].areaVector).transpose() << std::endl;
        }
    }
}
