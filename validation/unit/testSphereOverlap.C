// The analytic sphere engine and the engine selector.

#include "overlapEngine.H"
#include "sphereOverlap.H"
#include "sphereShape.H"
#include "triangleMeshShape.H"
#include "primitiveMeshes.H"
#include "coreError.H"

#include <gtest/gtest.h>

#include <cmath>

using namespace immersedDEM;

namespace
{

const double R = 0.005, d = 0.01, h = d/20;

} // End anonymous namespace


TEST(sphereOverlap, lensOfEqualSpheresMatchesClosedForm)
{
    // Equal balls at distance s: V = pi (4R + s)(2R - s)^2 / 12
    for (double s : {0.002, 0.006, 0.0099})
    {
        const auto g = sphereOverlap::lens(vec3::Zero(), R, vec3(s, 0, 0), R);
        ASSERT_EQ(g.regions.size(), 1u);
        EXPECT_NEAR(g.volume(), M_PI*(4*R + s)*std::pow(2*R - s, 2)/12, 1e-18);
        EXPECT_NEAR(g.regions[0].point.x(), s/2, 1e-15);
        EXPECT_NEAR(g.regions[0].area, M_PI*(R*R - s*s/4), 1e-15);
        EXPECT_EQ(g.regions[0].normal, vec3::UnitX());
    }
    EXPECT_TRUE(sphereOverlap::lens(vec3::Zero(), R, vec3(2*R, 0, 0), R).regions.empty());
}


TEST(sphereOverlap, needsTwoSpheres)
{
    const sphereShape s(R);
    const triangleMeshShape box(primitiveMeshes::box(vec3::Constant(R)), "box");
    EXPECT_THROW(sphereOverlap().evaluate(s, bodyPose(), box, bodyPose(), {h, 4}), coreError);
}


TEST(overlapEngine, selectorListsValidMethods)
{
    EXPECT_EQ(overlapEngine::New("virtualMesh")->type(), "virtualMesh");
    EXPECT_EQ(overlapEngine::New("sphere")->type(), "sphere");
    try
    {
        overlapEngine::New("octree");
        FAIL() << "no error";
    }
    catch (const coreError& e)
    {
        EXPECT_NE(std::string(e.what()).find("Unknown overlap method 'octree'"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("virtualMesh"), std::string::npos);
    }
}
