// The explanation of the DEM step gives the step demSolver takes, and
// names the body and partner that set it.

#include "timeStepExplanation.H"
#include "sphereShape.H"
#include "triangleMeshShape.H"
#include "halfSpaceShape.H"
#include "primitiveMeshes.H"

#include "testHelpers.H"

#include <gtest/gtest.h>

using namespace immersedDEM;
using immersedDEM::test::material;


TEST(timeStepExplanation, givesTheSolversStepAndItsCause)
{
    demSettings s;
    demSolver dem({material("soft", 1e6), material("steel", 2e11)}, s);
    rigidBody big("big", std::make_shared<sphereShape>(0.01), 1000, 0);
    big.pose = bodyPose(vec3(0, 0, 0.1), quat::Identity());
    dem.addBody(big);
    // The smallest, stiffest body sets the step, against a wall of steel
    rigidBody small("small", std::make_shared<sphereShape>(0.002), 7800, 1);
    small.pose = bodyPose(vec3(0.05, 0, 0.1), quat::Identity());
    dem.addBody(small);
    rigidBody floor("floor", std::make_shared<halfSpaceShape>(), 1, 1);
    floor.motion = motionType::fixed;
    dem.addBody(floor, true);

    const timeStepExplanation e = timeStepExplanation::of(dem);
    EXPECT_DOUBLE_EQ(e.deltaT, dem.timeStep());
    EXPECT_EQ(e.body, 1);
    EXPECT_EQ(e.material, 1);
    EXPECT_FALSE(e.speedFromBodies);
    EXPECT_DOUBLE_EQ(e.speed, s.referenceSpeed);
    EXPECT_NE(e.text(dem).find("set by body small"), std::string::npos) << e.text(dem);

    // A fast body raises the speed; a mesh body adds its flat face
    dem.bodies()[0].velocity = vec3(0, 0, -3);
    rigidBody block("block", std::make_shared<triangleMeshShape>(primitiveMeshes::box(vec3(0.001, 0.001, 0.001)), "block"), 7800, 1);
    block.pose = bodyPose(vec3(-0.05, 0, 0.1), quat::Identity());
    dem.addBody(block);
    const timeStepExplanation f = timeStepExplanation::of(dem);
    EXPECT_DOUBLE_EQ(f.deltaT, dem.timeStep());
    EXPECT_TRUE(f.speedFromBodies);
    EXPECT_DOUBLE_EQ(f.speed, 6);
    EXPECT_NE(f.text(dem).find("twice the fastest"), std::string::npos) << f.text(dem);

    // The user's step
    demSettings fixed;
    fixed.deltaT = 1e-5;
    demSolver user({material("soft", 1e6)}, fixed);
    EXPECT_TRUE(timeStepExplanation::of(user).userStep);
    EXPECT_EQ(timeStepExplanation::of(user).deltaT, 1e-5);
}
