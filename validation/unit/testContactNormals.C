/*---------------------------------------------------------------------------*\
Description
    The contact normal as the direction of the area vector (issue 19, item
    2; the gradient of the overlap volume with respect to B's translation,
    Feng, CMAME 373, 2021): an L-block across a cube, the arrangement
    mirror-symmetric in z, gives a normal in the mirror plane to 0.01
    degrees at levels 2-6 and with both bodies shifted by fractions of a
    cell; the plane fitted through the rim (the default) is printed beside
    it. With the roles swapped the area vector is not yet symmetric to
    that accuracy (printed).
\*---------------------------------------------------------------------------*/

#include "virtualMeshOverlap.H"
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
            // With the roles swapped (the L's faces inside the cube, among
            // them its top and bottom, whose +z and -z contributions must
            // cancel) the area vector still leaves the plane by up to 2.6
            // degrees at level 2 (0.27 at level 6): printed, not yet
            // asserted (issue 19, what remains)
            const auto gS = virtualMeshOverlap().evaluate(l, pL, cube, pCube, area);
            ASSERT_EQ(gS.regions.size(), 1u);
            std::cout << "    swapped: area vector normal z " << gS.regions[0].normal.z()
                << std::endl;
        }
    }
}
