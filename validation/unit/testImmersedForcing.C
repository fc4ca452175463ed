// The forcing's formulas (immersedForcing) and the fluid load's restart
// list (fluidLoad::fields), without a mesh.

#include "immersedForcing.H"
#include "fluidLoad.H"

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

using namespace immersedDEM;

// One implicit step of dU/dt = -K (U - Uib) from U* gives the volume
// average of the body's and the fluid's velocities in the cell
TEST(immersedForcing, diffuseStepGivesTheVolumeAverage)
{
    const double deltaT = 1e-3, Ustar = 0.3, Uib = -0.2;
    for (const double l : {0.01, 0.2, 0.5, 0.9, 0.99})
    {
        const double K = immersedForcing::diffuseCoefficient(l, deltaT, 1e3);
        const double U = (Ustar + K*deltaT*Uib)/(1 + K*deltaT);
        EXPECT_NEAR(U, l*Uib + (1 - l)*Ustar, 1e-14) << "lambda " << l;
    }
}

TEST(immersedForcing, diffusePenaltyCapsTheFullCells)
{
    const double deltaT = 2e-3;
    EXPECT_DOUBLE_EQ(immersedForcing::diffuseCoefficient(1, deltaT, 50), 50/deltaT);
    EXPECT_DOUBLE_EQ(immersedForcing::diffuseCoefficient(0.999, deltaT, 50), 50/deltaT);
    EXPECT_DOUBLE_EQ(immersedForcing::diffuseCoefficient(0.5, deltaT, 50), 1/deltaT);
    EXPECT_EQ(immersedForcing::diffuseCoefficient(0, deltaT, 50), 0);
    EXPECT_EQ(immersedForcing::diffuseCoefficient(0.5, 0, 50), 0);
}

TEST(immersedForcing, sharpCoefficientInsideAndCapped)
{
    const double deltaT = 1e-3, penalty = 1e3;
    EXPECT_DOUBLE_EQ(immersedForcing::sharpCoefficient(-1, deltaT, penalty), 1e6);
    EXPECT_DOUBLE_EQ(immersedForcing::sharpCoefficient(20, deltaT, penalty), 20);
    EXPECT_DOUBLE_EQ(immersedForcing::sharpCoefficient(1e9, deltaT, penalty), 1e6);
    EXPECT_EQ(immersedForcing::sharpCoefficient(-1, 0, penalty), 0);
}

// A fluid cell of a uniform 1D grid (spacing d, face area A) whose
// neighbour's centre is inside the body: the Laplacian's flux to that
// neighbour, nu A (Uib - U)/d, plus the source K V (Uib - U) must be the
// wall's shear nu A (Uib - U)/phiC, with the wall a distance phiC away
TEST(immersedForcing, wallShearPutsTheWallWhereItIs)
{
    const double nu = 1e-6, d = 2e-3, A = d*d, V = d*d*d;
    for (const double phiC : {0.05*d, 0.3*d, 0.5*d, 0.99*d})
    {
        const double phiN = phiC - d;
        const double K =
            immersedForcing::wallShearCoefficient(nu, A/d, V, phiC, phiN);
        EXPECT_NEAR((nu*A/d + K*V)/(nu*A/phiC), 1, 1e-12) << "phiC/d " << phiC/d;
    }
}

TEST(immersedForcing, fluidForceTermsAndBuoyancy)
{
    const double rho = 1000, deltaT = 1e-3, Vb = 1e-6;
    const vec3 g(0, 0, -9.81);
    const vec3 P(1e-6, 0, 2e-6), M(0, 3e-9, 0), M0(0, 1e-9, 0);
    const auto ddt = immersedForcing::timeDerivative::euler(deltaT);
    const vec3 F = immersedForcing::fluidForce(rho, P, ddt.of(M, M0, vec3::Zero()), Vb, g);
    EXPECT_NEAR(F.x(), rho*1e-6, 1e-15);
    EXPECT_NEAR(F.y(), rho*2e-9/deltaT, 1e-15);
    EXPECT_NEAR(F.z(), rho*2e-6 + rho*Vb*9.81, 1e-15);   // buoyancy upwards
    const vec3 T = immersedForcing::fluidTorque(rho, P, ddt.of(M, M0, vec3::Zero()));
    EXPECT_NEAR(T.z(), rho*2e-6, 1e-15);
}

TEST(immersedForcing, backwardDerivativeIsExactForQuadratics)
{
    // x(t) = 3 + 2 t + 5 t^2 at t = -0.3, 0, 0.7 (steps 0.3 then 0.7):
    // BDF2 with variable steps is exact for a quadratic, dx/dt(0.7) = 9
    const auto x = [](double t) { return vec3(3 + 2*t + 5*t*t, 0, 0); };
    const auto d = immersedForcing::timeDerivative::backward(0.7, 0.3);
    EXPECT_NEAR(d.of(x(0.7), x(0), x(-0.3)).x(), 2 + 10*0.7, 1e-12);
    // equal steps: the textbook (3 x - 4 x0 + x00)/(2 dt)
    const auto e = immersedForcing::timeDerivative::backward(0.5, 0.5);
    EXPECT_NEAR(e.c, 1.5, 1e-15);
    EXPECT_NEAR(e.c0, 2, 1e-15);
    EXPECT_NEAR(e.c00, 0.5, 1e-15);
    // Euler is exact for a line
    const auto f = immersedForcing::timeDerivative::euler(0.7);
    EXPECT_NEAR(f.of(vec3(1 + 0.7*4, 0, 0), vec3(1, 0, 0), vec3(-7, 0, 0)).x(), 4, 1e-12);
}

// The scheme's rates taken as first-order rates: from an Euler first step
// and backward after it (OpenFOAM's start), with steps that vary, the
// derivatives of any sequence become (x - x0)/deltaT. An impulsive start
// (x 0, then 1 at every step): backward's second step answers -c00/deltaT,
// and the rates summed over the steps give 1 - c00 of the change (0.5 at
// equal steps); taken as first-order rates they give all of it
TEST(immersedForcing, firstOrderTakesTheSchemesRatesAsTheChange)
{
    const std::vector<double> x{0.3, -1.2, 4.0, 4.5, 4.5, 2.0, 2.25, -0.5};
    const std::vector<double> dt{0.1, 0.13, 0.07, 0.2, 0.2, 0.05, 0.11};
    double r0 = 0;
    for (size_t n = 1; n < x.size(); ++n)
    {
        const auto d = n == 1
            ? immersedForcing::timeDerivative::euler(dt[0])
            : immersedForcing::timeDerivative::backward(dt[n - 1], dt[n - 2]);
        const double rate = d.of
        (
            vec3(x[n], 0, 0), vec3(x[n - 1], 0, 0), vec3(n > 1 ? x[n - 2] : 0, 0, 0)
        ).x();
        const double r = d.firstOrder(vec3(rate, 0, 0), vec3(r0, 0, 0)).x();
        EXPECT_NEAR(r, (x[n] - x[n - 1])/dt[n - 1], 1e-12) << "step " << n;
        r0 = r;
    }

    // The impulsive start at equal steps
    const double h = 0.01;
    double sumScheme = 0, sumTaken = 0;
    r0 = 0;
    const std::vector<double> u{0, 1, 1, 1, 1, 1};
    for (size_t n = 1; n < u.size(); ++n)
    {
        const auto d = n == 1
            ? immersedForcing::timeDerivative::euler(h)
            : immersedForcing::timeDerivative::backward(h, h);
        const double rate = d.of
        (
            vec3(u[n], 0, 0), vec3(u[n - 1], 0, 0), vec3(n > 1 ? u[n - 2] : 0, 0, 0)
        ).x();
        if (n == 2) EXPECT_NEAR(rate, -0.5/h, 1e-9);
        const double r = d.firstOrder(vec3(rate, 0, 0), vec3(r0, 0, 0)).x();
        sumScheme += rate*h;
        sumTaken += r*h;
        r0 = r;
    }
    EXPECT_NEAR(sumScheme, 0.5, 1e-12);
    EXPECT_NEAR(sumTaken, 1, 1e-12);
    // Euler's rates are taken as they are
    const auto e = immersedForcing::timeDerivative::euler(h);
    EXPECT_EQ(e.firstOrder(vec3(2, 0, 0), vec3(7, 0, 0)).x(), 2);
}

// The restart writes what fields() lists: every member, each name once
TEST(fluidLoad, fieldsListEveryMemberOnce)
{
    fluidLoad l;
    std::set<std::string> names;
    int nVectors = 0, nScalars = 0;
    struct counter
    {
        std::set<std::string>& names; int& nv; int& ns;
        void operator()(const char* n, vec3& v) { names.insert(n); ++nv; v.setConstant(1); }
        void operator()(const char* n, double& s) { names.insert(n); ++ns; s = 1; }
    };
    fluidLoad::fields(l, counter{names, nVectors, nScalars});
    EXPECT_EQ(nVectors, 6);
    EXPECT_EQ(nScalars, 8);
    EXPECT_EQ(names.size(), 14u);
    // Every member was reached: none is left at its default
    EXPECT_EQ(l.force.sum() + l.torque.sum() + l.referenceVelocity.sum()
        + l.referenceAcceleration.sum() + l.referenceAngularVelocity.sum()
        + l.referenceAngularAcceleration.sum(), 18);
    EXPECT_EQ(l.damping + l.addedMass + l.nominalAddedMass + l.referenceTime
        + l.angularDamping + l.addedInertia + l.courseExtrapolated
        + l.impactRestartsCourse, 8);
    EXPECT_EQ(sizeof(fluidLoad), 6*sizeof(vec3) + 8*sizeof(double));
}

// The contact rule: no inertia, dampers m_a/dt and I_a/dt on the
// departure from the course extrapolated with the reference accelerations
TEST(fluidLoad, heldDampsTheDepartureFromTheExtrapolatedCourse)
{
    const double t = 0.5, dt = 1e-3;
    const vec3 v(0.1, 0, 0), a(10, 0, 0), w(0, 1, 0), alpha(0, 0, 3);
    const fluidLoad l = fluidLoad::held
    (
        vec3(0, 0, 1), vec3(0, 0, 2), 0.2, 0.01, 0.05, dt, t, v, a, w, alpha
    );
    EXPECT_EQ(l.addedMass, 0);
    EXPECT_EQ(l.addedInertia, 0);
    EXPECT_EQ(l.nominalAddedMass, 0.05);
    EXPECT_NEAR(l.damping, 0.2/dt, 1e-9);
    EXPECT_NEAR(l.angularDamping, 0.01/dt, 1e-9);
    EXPECT_TRUE(l.inertialForce().isZero());
    // On the course at a later time: the plain load
    const double s = 2e-4;
    EXPECT_NEAR((l.appliedForce(v + s*a, t + s) - vec3(0, 0, 1)).norm(), 0, 1e-12);
    EXPECT_NEAR((l.appliedTorque(w + s*alpha, t + s) - vec3(0, 0, 2)).norm(), 0, 1e-12);
    // Off it: the damper
    EXPECT_NEAR(l.appliedForce(v, t + s).x(), 0.2/dt*s*10, 1e-9);
    EXPECT_NEAR(l.appliedTorque(w, t + s).z(), 2 + 0.01/dt*s*3, 1e-9);
}

TEST(fluidLoad, coupledAnswersADepartureFromWhatTheFluidSaw)
{
    const double t = 0.5;
    const vec3 v(0.1, 0, 0), a(10, 0, 0), w(0, 1, 0), alpha(0, 0, 3);
    fluidImpedance::coefficients z;
    z.addedMass = 0.2;
    z.damping = 40;
    z.addedInertia = 0.01;
    z.angularDamping = 5;
    z.nominalAddedMass = 0.1;
    const fluidLoad l = fluidLoad::coupled(vec3(0, 0, 1), vec3(0, 0, 2), z, t, v, a, w, alpha);
    EXPECT_EQ(l.damping, 40);
    EXPECT_EQ(l.addedMass, 0.2);
    // (the body's own added mass, what its contacts move with it)
    EXPECT_EQ(l.nominalAddedMass, 0.1);
    EXPECT_EQ(l.addedInertia, 0.01);
    EXPECT_EQ(l.angularDamping, 5);
    // At the velocities the fluid saw: the plain load
    // (at any time within the step: the course is not extrapolated)
    EXPECT_NEAR((l.appliedForce(v, t + 0.1) - vec3(0, 0, 1)).norm(), 0, 1e-12);
    EXPECT_NEAR((l.appliedTorque(w, t + 0.1) - vec3(0, 0, 2)).norm(), 0, 1e-12);
    // Another velocity meets the viscous resistance
    EXPECT_NEAR(l.appliedForce(v + vec3(0.01, 0, 0), t).x(), -40*0.01, 1e-12);
    EXPECT_NEAR(l.appliedTorque(w + vec3(0.1, 0, 0), t).x(), -5*0.1, 1e-12);
    // The added mass and moment carry the reference accelerations
    EXPECT_NEAR((l.inertialForce() - 0.2*a).norm(), 0, 1e-12);
    EXPECT_NEAR((l.inertialTorque() - 0.01*alpha).norm(), 0, 1e-12);
}
