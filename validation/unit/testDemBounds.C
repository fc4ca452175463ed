// Bounded work of the DEM (issue 19, item 4): materials that would make
// the automatic step vanish are errors naming the keyword, a step count
// that an int cannot hold is an error naming youngsModulus and density
// (it was a SIGFPE), and the automatic step keeps a fast body from passing
// through a wall (a tenth of its size per step at most).

#include "demSolver.H"
#include "sphereShape.H"
#include "halfSpaceShape.H"
#include "testHelpers.H"

#include <gtest/gtest.h>

using namespace immersedDEM;

namespace
{

const double R = 0.005;

demSolver sphereOnPlane
(
    const contactMaterial& m, double density, double speed, vec3 start = vec3(0, 0, 0.02)
)
{
    demSettings s;
    s.overlapMethod = "virtualMesh";
    demSolver dem({m}, s);
    rigidBody floor("floor", std::make_shared<halfSpaceShape>(), 1);
    floor.pose = halfSpaceShape::poseOf(vec3::Zero(), vec3::UnitZ());
    floor.motion = motionType::fixed;
    dem.addBody(floor, true);
    rigidBody b("ball", std::make_shared<sphereShape>(R), density);
    b.pose = bodyPose(start, quat::Identity());
    b.velocity = vec3(0, 0, -speed);
    dem.addBody(b);
    return dem;
}

} // End anonymous namespace


TEST(demBounds, youngsModulusBeyondAnySolidIsAnError)
{
    const contactMaterial m{"steel", 1e30, 0.3, 1, 0};
    EXPECT_TRUE(test::throwsCoreError
    (
        [&]{ demSolver({m}, demSettings()); },
        {"Material 'steel'", "youngsModulus", "1e+30", "1e13"}
    ));
}


TEST(demBounds, unrepresentableStepIsAnError)
{
    // The stiffest material allowed on a body of almost no mass: the
    // contact lasts ~1e-19 s, 1e19 steps per second (was SIGFPE)
    const contactMaterial m{"diamond", 1e13, 0.2, 1, 0};
    demSolver dem = sphereOnPlane(m, 1e-20, 1);
    EXPECT_TRUE(test::throwsCoreError
    (
        [&]{ dem.advance(1.0); },
        {"DEM time step", "youngsModulus", "diamond", "density", "ball"}
    ));
}


TEST(demBounds, fastBodyBouncesOffAPlane)
{
    // Glass at 1000 m/s: the step keeps to a tenth of the diameter per step
    // (relative to the wall), the ball comes back from the plane and not
    // faster than it came (restitution 1)
    const contactMaterial glass{"glass", 6.3e10, 0.23, 1, 0};
    const double v = 1000;
    demSolver dem = sphereOnPlane(glass, 2500, v);
    const double dt = dem.timeStep();
    EXPECT_LE(v*dt, demSolver::maxTravel*2*R*0.5*(1 + 1e-12));
    double zMin = 1;
    for (int n = 0; n < 20000 && dem.bodies()[1].velocity.z() < 0; ++n)
    {
        dem.step(dem.timeStep());
        zMin = std::min(zMin, dem.bodies()[1].pose.position().z());
    }
    // Out of contact again
    for (int n = 0; n < 20000 && dem.bodies()[1].pose.position().z() < 1.5*R; ++n)
    {
        dem.step(dem.timeStep());
    }
    const rigidBody& b = dem.bodies()[1];
    EXPECT_GT(b.velocity.z(), 0);
    EXPECT_GT(zMin, 0) << "the ball's centre went through the plane";
    // restitution 1: not faster (0.1% for the integrator's energy error),
    // and 2% for a contact at 1000 m/s resolved in few steps
    EXPECT_LT(b.velocity.norm(), v*1.001);
    EXPECT_GT(b.velocity.norm(), v*0.98);
}
