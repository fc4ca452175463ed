// The DEM's side of the fluid coupling: a fluid force set between two
// advances acts from the first sub-step of the next one, and the added-mass
// stabilisation relaxes a velocity change within a CFD step like a drag
// m_a/dt (v - v_ref), exponentially, towards the reference velocity, and
// leaves a motion that follows the extrapolated reference alone.

#include "demSolver.H"
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
    EXPECT_NEAR(b.velocity.x(), expected, 1e-4*expected);
    EXPECT_NEAR(b.appliedFluidForce(dem.time()).x(), -c*(b.velocity.x() - 0.1), 1e-12);
}


TEST(demFluidLoads, addedMassDampingLeavesTheReferenceMotionAlone)
{
    demSolver dem = oneSphere(1e-5);
    rigidBody& b = dem.bodies()[0];
    const double m = b.mass();
    // A constant fluid force F and a reference moving with acceleration
    // F/m: the body follows it exactly, the damping never acts
    const vec3 F(0, 0, 3e-3);
    b.fluid.force = F;
    b.velocity = vec3(0, 0, 0.05);
    b.fluid.referenceVelocity = b.velocity;
    b.fluid.referenceAcceleration = F/m;
    b.fluid.referenceTime = dem.time();
    b.fluid.damping = 10*m/1e-3;
    dem.advance(1e-3);
    EXPECT_NEAR(b.velocity.z(), 0.05 + F.z()/m*1e-3, 1e-12);
    EXPECT_NEAR((b.appliedFluidForce(dem.time()) - F).norm(), 0, 1e-12);
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
    EXPECT_NEAR(b.angularVelocity.y(), expected, 1e-4*expected);
    EXPECT_NEAR(b.angularVelocity.x(), 0, 1e-14);
}
