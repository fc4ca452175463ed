// The DEM's side of the fluid coupling: a fluid force set between two
// advances acts from the first sub-step of the next one. The coupling's
// implicit part (fluidLoad.H): the damper relaxes a velocity change
// within a CFD step like a drag c (v - v_ref), exponentially, towards the
// reference velocity, implicitly (stable for any c); the added mass is
// inertia, (m + m_a) dv/dt = F + m_a a_ref, so a contact within the step
// moves the body and its added mass together (an elastic bounce keeps its
// speed) and a motion that follows the reference is left alone. The
// rotation's damper relaxes the spin towards its reference.

#include "demSolver.H"
#include "halfSpaceShape.H"
#include "sphereShape.H"

#include <gtest/gtest.h>

#include <cmath>

using namespace immersedDEM;

namespace
{

demSolver oneSphere(double deltaT)
{
    contactMaterial m{"m", 1e7, 0.3, 0.5, 0.3};
    demSettings s;
    s.deltaT = deltaT;
    demSolver dem({m}, s);
    dem.addBody(rigidBody("ball", std::make_shared<sphereShape>(0.005), 1000));
    return dem;
}

} // End anonymous namespace


TEST(demFluidLoads, newFluidForceActsFromTheNextAdvance)
{
    demSolver dem = oneSphere(1e-4);
    dem.advance(1e-2);                      // forces computed, no fluid force
    rigidBody& b = dem.bodies()[0];
    const double m = b.mass();
    b.fluid.force = vec3(0, 0, 2e-3);
    b.fluid.torque = vec3(1e-7, 0, 0);
    dem.advance(1e-2);
    // Constant force over the whole interval: v = F T/m exactly
    EXPECT_NEAR(b.velocity.z(), 2e-3*1e-2/m, 1e-12);
    EXPECT_NEAR(b.pose.position().z(), 0.5*2e-3/m*1e-4, 1e-12);
    EXPECT_GT(b.angularVelocity.x(), 0);
}


TEST(demFluidLoads, addedMassDampingRelaxesTowardsTheReference)
{
    const double dt = 1e-6;
    demSolver dem = oneSphere(dt);
    rigidBody& b = dem.bodies()[0];
    const double m = b.mass();
    const double c = 0.5*m/1e-3;            // m_a = m/2 over a CFD step of 1 ms
    b.velocity = vec3(0.2, 0, 0);
    b.fluid.referenceVelocity = vec3(0.1, 0, 0);
    b.fluid.damping = c;
    const double T = 2e-3;
    dem.advance(T);
    const double expected = 0.1 + 0.1*std::exp(-c*T/m);
    // 1e-4: the sub-steps' discretisation of the exponential (dt 1e-6 s
    // against the time constant m/c = 2 ms)
    EXPECT_NEAR(b.velocity.x(), expected, 1e-4*expected);
    EXPECT_NEAR(b.appliedFluidForce(dem.time()).x(), -c*(b.velocity.x() - 0.1), 1e-12);
}


TEST(demFluidLoads, addedMassLeavesTheReferenceMotionAlone)
{
    // A constant fluid force F and a reference acceleration F/m: the body
    // carrying an added mass of 10 m as inertia follows F/m exactly
    demSolver dem = oneSphere(1e-5);
    rigidBody& b = dem.bodies()[0];
    const double m = b.mass();
    const vec3 F(0, 0, 3e-3);
    b.fluid.force = F;
    b.velocity = vec3(0, 0, 0.05);
    b.fluid.referenceVelocity = b.velocity;
    b.fluid.referenceAcceleration = F/m;
    b.fluid.referenceTime = dem.time();
    b.fluid.addedMass = 10*m;
    dem.advance(1e-3);
    EXPECT_NEAR(b.velocity.z(), 0.05 + F.z()/m*1e-3, 1e-12);
    EXPECT_NEAR((b.appliedFluidForce(dem.time()) - F).norm(), 0, 1e-12);
}


TEST(demFluidLoads, implicitDamperIsTheDragOfTheNewVelocity)
{
    // A constant force F on a body with the damper c towards the velocity
    // the fluid saw (0): the body tends to the terminal velocity F/c
    // whatever c T/m (50 here, stable: the kick is implicit), and in one
    // CFD step it has relaxed to exp(-c T/m) of the way
    demSolver dem = oneSphere(1e-4);
    rigidBody& b = dem.bodies()[0];
    const double m = b.mass();
    const double T = 1e-2, c = 50*m/T;
    const vec3 F(2e-3, 0, 0);
    b.fluid.force = F;
    b.fluid.damping = c;
    dem.advance(T);
    // Implicit Euler with steps of at most 0.1 m/c: within 3% of the
    // exact relaxation 1 - exp(-50) at the end of the step
    EXPECT_NEAR(b.velocity.x(), F.x()/c, 0.03*F.x()/c);
    EXPECT_NEAR(b.velocity.y(), 0, 1e-15);
}


TEST(demFluidLoads, addedMassIsInertiaAgainstADeparture)
{
    demSolver dem = oneSphere(1e-5);
    rigidBody& b = dem.bodies()[0];
    const double m = b.mass();
    // A force the reference motion (at rest) does not have: the body and
    // its added mass accelerate together, F/(m + m_a)
    const vec3 F(3e-3, 0, 0);
    b.fluid.force = F;
    b.fluid.addedMass = 1.5*m;
    dem.advance(1e-3);
    EXPECT_NEAR(b.velocity.x(), F.x()/(2.5*m)*1e-3, 1e-12);
    EXPECT_NEAR(b.velocity.z(), 0, 1e-12);
}


TEST(demFluidLoads, elasticBounceKeepsItsSpeedWithTheAddedMass)
{
    // A sphere at 0.3 m/s onto a plane, restitution 1, no gravity, within
    // one CFD step: with its added mass as inertia it leaves at its impact
    // speed (a damper towards the approach velocity, as the stabilisation
    // was before, took half of it: issue 15's wet bounce)
    contactMaterial mat{"m", 1e7, 0.3, 1, 0};
    demSettings s;
    s.deltaT = 2e-6;
    s.gravity = vec3::Zero();
    s.overlapMethod = "sphere";
    demSolver dem({mat}, s);
    rigidBody floor("floor", std::make_shared<halfSpaceShape>(), 1);
    floor.pose = halfSpaceShape::poseOf(vec3::Zero(), vec3::UnitZ());
    floor.motion = motionType::fixed;
    dem.addBody(floor, true);
    rigidBody ball("ball", std::make_shared<sphereShape>(0.005), 2500);
    ball.pose = bodyPose(vec3(0, 0, 0.0052), quat::Identity());
    ball.velocity = vec3(0, 0, -0.3);
    const int i = dem.addBody(ball);
    rigidBody& b = dem.bodies()[i];
    b.fluid.addedMass = 1.5*b.mass();
    b.fluid.referenceVelocity = b.velocity;
    dem.advance(1e-2);
    EXPECT_GT(b.pose.position().z(), 0.0052);
    // 1e-3: restitution 1 exactly in the law; the contact's stepping
    // (2e-6 s) loses less; the damper of before lost half
    EXPECT_NEAR(b.velocity.z(), 0.3, 1e-3*0.3);
}


TEST(demFluidLoads, angularDampingRelaxesTheSpinTowardsTheReference)
{
    const double dt = 1e-6;
    demSolver dem = oneSphere(dt);
    rigidBody& b = dem.bodies()[0];
    const double I = b.inertia().x();       // a sphere: isotropic
    const double D = 0.8*I/1e-3;
    b.angularVelocity = vec3(0, 3, 0);
    b.fluid.referenceAngularVelocity = vec3(0, 1, 0);
    b.fluid.angularDamping = D;
    const double T = 2e-3;
    dem.advance(T);
    const double expected = 1 + 2*std::exp(-D*T/I);
    // 1e-4: as the velocity's above (time constant I/D = 1.25 ms)
    EXPECT_NEAR(b.angularVelocity.y(), expected, 1e-4*expected);
    EXPECT_NEAR(b.angularVelocity.x(), 0, 1e-14);
}
