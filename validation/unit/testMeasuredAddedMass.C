// The measured added mass (src/core/coupling/measuredAddedMass) against a
// model fluid whose force answers the body's last acceleration with a
// known added mass M, F_n = -M a_n + W - c v_n, coupled to the DEM as
// immersedFluidCoupling::fluidLoads couples the real one (the force held
// over the next step, stabilised by m_a). With m_a = Ca rho V and
// M > m + 2 m_a the coupling is unstable, as in the packed bed at 3 cells
// per pellet (M = 3.5-5.8 rho V, m = 2.5 rho V, Ca = 1); with m_a from
// the measured M (measuredAddedMass::stabilisation) it settles.

#include "demSolver.H"
#include "measuredAddedMass.H"
#include "sphereShape.H"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace immersedDEM;

namespace
{

struct modelRun
{
    double largestAcceleration = 0;     // over the last 20 steps
    double finalVelocity = 0;
    double measured = 0;
    double measuredWithoutDrag = 0;     // the fit on F + c v
};

// A 2.5 g/cm3 sphere falling sideways (x) in a model fluid of density 1000
// with added mass M = kM rho V, drag c, CFD step dt; Ca the stabilisation's
// coefficient; measure: m_a from the measured M, at least Ca rho V
modelRun run(const double kM, const double Ca, const bool measure, const int steps)
{
    const double dt = 1e-3, rho = 1000;
    contactMaterial mat{"m", 1e7, 0.3, 0.5, 0.3};
    demSettings s;
    s.deltaT = dt/10;
    s.gravity = vec3::Zero();
    demSolver dem({mat}, s);
    dem.addBody(rigidBody("ball", std::make_shared<sphereShape>(0.0015), 2500));
    rigidBody& b = dem.bodies()[0];
    const double V = b.geometry->volume(), m = b.mass();
    const double M = kM*rho*V;
    const double W = 1.5*rho*V*9.81;         // its weight in water, sideways
    const double c = W/0.05;                 // terminal velocity 0.05 m/s
    measuredAddedMass est, withoutDrag;
    vec3 vPrevious = b.velocity;
    modelRun r;
    for (int n = 0; n < steps; ++n)
    {
        const vec3 a = (b.velocity - vPrevious)/dt;
        const vec3 F = -M*a + vec3(W, 0, 0) - c*b.velocity;
        est.record(F, a, 1e-4);
        withoutDrag.record(F + c*b.velocity, a, 1e-4);
        const double ma =
            measure ? est.stabilisation(m, Ca*rho*V, 100*rho*V) : Ca*rho*V;
        b.fluid = fluidLoad::held
        (
            F, vec3::Zero(), ma, 0, Ca*rho*V, dt, dem.time(),
            b.velocity, (b.velocity - vPrevious)/dt,
            b.angularVelocity, vec3::Zero()
        );
        vPrevious = b.velocity;
        dem.advance(dt);
        if (n >= steps - 20)
        {
            r.largestAcceleration = std::max(r.largestAcceleration, a.norm());
        }
    }
    r.finalVelocity = b.velocity.x();
    r.measured = est.value()/(rho*V);
    r.measuredWithoutDrag = withoutDrag.value()/(rho*V);
    return r;
}

} // End anonymous namespace


TEST(measuredAddedMass, fixedCoefficientBelowTheFluidsAddedMassIsUnstable)
{
    // M = 7 rho V > m + 2 m_a = 4.5 rho V: the acceleration alternates and
    // grows by |r| = (M - m_a)/(m + m_a) = 1.71 a step
    const modelRun r = run(7, 1, false, 60);
    // 1e3 m/s2: a stable run never exceeds its first acceleration,
    // W/(m + m_a) = 4.2 m/s2; the unstable one is 4.2*1.71^58 by the end
    EXPECT_GT(r.largestAcceleration, 1e3);
    // Stable when the fixed coefficient is large enough (4: m + 2 m_a =
    // 10.5 rho V)
    const modelRun s = run(7, 4, false, 400);
    // 1e-5 m/s: 0.4 s is 12 time constants (m + M)/c = 0.032 s, which
    // leave 4e-6 of the approach (2e-7 m/s); a run at half that rate
    // would be 1e-4 off and fail
    EXPECT_NEAR(s.finalVelocity, 0.05, 1e-5);
}


TEST(measuredAddedMass, measuredAddedMassSettlesWhatTheCoefficientCannot)
{
    // 2 s: 18 time constants (m + M)/c of the heaviest (M = 30 rho V)
    for (const double kM : {7.0, 30.0, 0.3})
    {
        const modelRun r = run(kM, 1, true, 2000);
        // 1e-6 m/s and 1e-5 m/s2: 18 time constants leave 1.5e-8 of the
        // approach (8e-10 m/s, 7e-9 m/s2 for M = 30); a run settling at
        // half the rate would leave 1.2e-4 of it (6e-6 m/s, 3e-5 m/s2)
        // and fail
        EXPECT_NEAR(r.finalVelocity, 0.05, 1e-6) << "M = " << kM << " rho V";
        EXPECT_LT(r.largestAcceleration, 1e-5) << "M = " << kM << " rho V";
        if (kM > 1)
        {
            // The fluid's own added mass, measured while the body
            // accelerated from rest. The drag's change, -c dv = -c a dt,
            // is in the fitted change of force too: it adds
            // c dt sum(a da)/sum(da^2) to the fit, negative while the
            // approach is smooth (a > 0 falling, da < 0), so the fit is
            // low by the model's drag and not by the estimator: without
            // the drag's change the same data give M to round-off.
            // Measured (2026-12-05, the coupling's held load of 677503c):
            // 4.37 for 7 (0.62 M), 23.0 for 30 (0.77 M); 0.6 M as before
            // eb881fb, where a changed stabilisation moved the approach
            // (4.1 for 7 then). An oscillation, where it matters, is
            // measured exactly: the next test. Above the body's mass
            // (2.5 rho V), so the measured value is the one in use.
            EXPECT_NEAR(r.measuredWithoutDrag, kM, 1e-9*kM)    // round-off
                << "M = " << kM << " rho V";
            EXPECT_GT(r.measured, 0.6*kM) << "M = " << kM << " rho V";
            EXPECT_GT(r.measured, 2.5) << "M = " << kM << " rho V";
            // 1.001: the drag's share can only lower the fit (above);
            // 0.1% for round-off of the sums
            EXPECT_LT(r.measured, 1.001*kM) << "M = " << kM << " rho V";
        }
    }
}


TEST(measuredAddedMass, holdsItsValueWhileTheDataSayNothing)
{
    measuredAddedMass est;
    const double M = 0.02;
    // Accelerations changing by 1 m/s2 a step: measured
    for (int n = 0; n < 10; ++n)
    {
        const vec3 a(n % 2 ? 1.0 : -1.0, 0, 0);
        est.record(-M*a + vec3(0, 0, 0.3), a, 1e-4);
    }
    EXPECT_NEAR(est.value(), M, 1e-12);     // exact data: round-off
    // Then a smooth motion with force noise: the changes of acceleration
    // stay below the floor (1e-2 m/s2) once the old ones are forgotten,
    // and the value is held
    for (int n = 0; n < 200; ++n)
    {
        const vec3 a(0, 1e-4*n, 0);
        est.record(vec3(0, 0, 0.3 + 1e-3*((n*7919) % 13 - 6)), a, 1e-4);
    }
    // Held: the noisy steps weigh in only while the alternating ones keep
    // sum(da^2) above the floor (forget 0.8: a few steps), and moved it
    // by 5e-4 M; 1% bounds that for any draw of the noise (a refit to
    // the noise, which says nothing of M, lands anywhere)
    EXPECT_NEAR(est.value(), M, 0.01*M);
    // A force that grows with the acceleration (not an added mass) gives
    // no negative mass
    measuredAddedMass other;
    for (int n = 0; n < 10; ++n)
    {
        const vec3 a(n % 2 ? 1.0 : -1.0, 0, 0);
        other.record(M*a, a, 1e-4);
    }
    EXPECT_EQ(other.value(), 0);
    est.reset();
    EXPECT_EQ(est.value(), 0);
}


TEST(measuredAddedMass, forceNoiseThatDoesNotFollowTheAccelerationMeasuresNothing)
{
    // A sphere falling in water at 16 cells per diameter (study
    // wetBouncing): force noise of +-5e-3 N from cells changing sides,
    // changes of acceleration of about 1 m/s2 that it does not follow.
    // The plain fit measured up to 31.7 rho V (rho V = 5.2e-4 kg) from
    // such data; the value held unless significant (value(true), for
    // bodies carrying their added mass as inertia) measures nothing.
    measuredAddedMass plain;
    {
        unsigned seed = 12345;
        for (int n = 0; n < 300; ++n)
        {
            seed = seed*1103515245u + 12345u;
            const double na = double((seed >> 8) % 2001)/1000.0 - 1;
            seed = seed*1103515245u + 12345u;
            const double nF = double((seed >> 8) % 2001)/1000.0 - 1;
            plain.record(vec3(0, 0, 0.015 + 5e-3*nF), vec3(0, 0, na), 1e-4);
        }
    }
    EXPECT_GT(plain.value(), 0);
    measuredAddedMass est;
    unsigned seed = 12345;
    auto noise = [&seed]()
    {
        seed = seed*1103515245u + 12345u;
        return double((seed >> 8) % 2001)/1000.0 - 1;    // [-1, 1]
    };
    for (int n = 0; n < 300; ++n)
    {
        const vec3 a(0, 0, noise());
        est.record(vec3(0, 0, 0.015 + 5e-3*noise()), a, 1e-4);
    }
    EXPECT_EQ(est.value(true), 0);
    EXPECT_EQ(est.stabilisation(1e-4, 2e-4, 1, true), 2e-4);
    // the plain fit, kept alongside, measures the noise
    EXPECT_GT(est.value(), 0);
    // An oscillation of the coupling (the force answers the acceleration,
    // M = 1e-2 kg) over the same noise: measured
    for (int n = 0; n < 20; ++n)
    {
        const vec3 a(0, 0, n % 2 ? 5.0 : -5.0);
        est.record(vec3(0, 0, 0.015 + 5e-3*noise()) - 1e-2*a, a, 1e-4);
    }
    // 5e-4 (5%): each step's force noise (standard deviation of dF
    // 4e-3 N) over da = 10 m/s2 is 4% of M, the fit weighs about 9
    // steps (forget 0.8), so 1.4% is one standard deviation; measured
    // 0.7% for this draw
    EXPECT_NEAR(est.value(true), 1e-2, 5e-4);
    EXPECT_NEAR(est.stabilisation(1e-4, 2e-4, 1, true), est.value(true), 1e-15);  // the same number
}


TEST(measuredAddedMass, stabilisationOnlyWhereTheCouplingNeedsIt)
{
    measuredAddedMass est;
    for (int n = 0; n < 10; ++n)
    {
        const vec3 a(n % 2 ? 1.0 : -1.0, 0, 0);
        est.record(-0.01*a, a, 1e-4);
    }
    ASSERT_NEAR(est.value(), 0.01, 1e-12);  // exact data: round-off
    // (1e-12 below: the same value passed through min/max)
    // M for a body of 5 g (M above its mass); the floor and the cap bound it
    EXPECT_NEAR(est.stabilisation(0.005, 1e-3, 1), 0.01, 1e-12);
    EXPECT_NEAR(est.stabilisation(0.005, 0.02, 1), 0.02, 1e-12);
    EXPECT_NEAR(est.stabilisation(0.005, 1e-3, 0.004), 0.004, 1e-12);
    // A body heavier than M (a glass sphere in air): its own inertia
    // keeps the coupling stable; the floor (Ca rho V) stays
    EXPECT_EQ(est.stabilisation(0.011, 1e-6, 1), 1e-6);
    EXPECT_EQ(est.stabilisation(1.0, 1e-6, 1), 1e-6);
}
