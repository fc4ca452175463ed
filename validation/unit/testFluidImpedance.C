// The implicit part of the coupling (fluidImpedance.H, fluidLoad.H): the
// unsteady Stokes estimates in their exact limits, and the property the
// coupling rests on: a body driven by a fluid force that answers its
// motion one CFD step late (the partitioned coupling) converges to the
// fluid's velocity for density ratios from 0.01 to 10 and steps from 0.1
// to 100 viscous response times, with the fluid's true added mass from
// 0.3 to 1 times the estimate and its true resistance from 0.5 to 1.9
// times it; without the implicit part the same loop diverges.

#include "demSolver.H"
#include "fluidImpedance.H"
#include "sphereShape.H"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace immersedDEM;

namespace
{

constexpr double pi = 3.14159265358979323846;

fluidImpedance::bodySize sphereSize(double a)
{
    fluidImpedance::bodySize s;
    s.volume = 4.0/3*pi*a*a*a;
    s.area = 4*pi*a*a;
    s.circumscribedRadius = a;
    return s;
}

fluidImpedance::bodySize cylinderSize(double a, double L)
{
    fluidImpedance::bodySize s;
    s.volume = pi*a*a;
    s.area = 2*pi*a;
    s.circumscribedRadius = a;
    s.depth = L;
    return s;
}

} // End anonymous namespace


TEST(fluidImpedance, besselRatioMatchesQuadrature)
{
    // K1/K0 from the integral K_n(q) = int_0^inf exp(-q cosh t) cosh(n t) dt
    // (trapezoidal rule, 8e5 intervals on [0, 8]; independent of the code)
    const double q[] = {0.1, 1, 10, 50, 100};
    const double ratio[] =
        {4.059977149632329, 1.4296253982604024, 1.048858722889177,
         1.0099509699867855, 1.004987623086483};
    for (int k = 0; k < 5; ++k)
    {
        // 1e-8: the quadrature's accuracy, and the asymptotic series'
        // past q = 50
        EXPECT_NEAR(fluidImpedance::besselRatio10(q[k]), ratio[k], 1e-8*ratio[k]) << q[k];
    }
}


TEST(fluidImpedance, sphereLimits)
{
    const double rho = 1000, nu = 1e-6, mu = rho*nu, a = 1e-3;
    const double V = 4.0/3*pi*a*a*a;
    // Steady limit (q = a/sqrt(nu dt) = 1e-6): Stokes' drag and torque
    const double dtSlow = a*a/nu*1e12;
    const auto slow = fluidImpedance::estimate(sphereSize(a), rho, nu, dtSlow);
    // 2e-6: the history term still there at q = 1e-6 (a factor 1 + q)
    EXPECT_NEAR(slow.damping, 6*pi*mu*a, 2e-6*6*pi*mu*a);
    EXPECT_NEAR(slow.angularDamping, 8*pi*mu*a*a*a, 2e-6*8*pi*mu*a*a*a);
    // The added mass of a sphere, half its displaced fluid, at any step;
    // no added moment of inertia (its rotation pushes no fluid aside)
    EXPECT_NEAR(slow.addedMass, 0.5*rho*V, 1e-12*rho*V);
    EXPECT_NEAR(slow.addedInertia, 0, 1e-12*rho*V*a*a);
    // Short step (q = 100): the history term 6 pi mu a q dominates
    const double dtFast = a*a/nu/1e4;
    const auto fast = fluidImpedance::estimate(sphereSize(a), rho, nu, dtFast);
    EXPECT_NEAR(fast.damping, 6*pi*mu*a*101, 1e-12*fast.damping);
    EXPECT_NEAR(fast.angularDamping, 8*pi*mu*a*a*a*(1 + 1e4/303), 1e-12*fast.angularDamping);
    // Inviscid: the added mass alone
    const auto inviscid = fluidImpedance::estimate(sphereSize(a), rho, 0, dtFast);
    EXPECT_EQ(inviscid.damping, 0);
    EXPECT_EQ(inviscid.angularDamping, 0);
    EXPECT_NEAR(inviscid.addedMass, 0.5*rho*V, 1e-12*rho*V);
    // A body with more surface than its volume-equivalent ball (a cube)
    // gets the added mass of the ball of its surface, and the moment of
    // the fluid between that ball and the circumscribed one
    fluidImpedance::bodySize cube;
    cube.volume = 8*a*a*a;
    cube.area = 24*a*a;
    cube.circumscribedRadius = std::sqrt(3.0)*a;
    const auto c = fluidImpedance::estimate(cube, rho, nu, dtFast);
    const double R = std::sqrt(3.0)*a, aV = std::cbrt(6/pi)*a;
    const double aS = std::sqrt(6/pi)*a;
    EXPECT_NEAR(c.addedMass, 0.5*rho*4.0/3*pi*aS*aS*aS, 1e-12*c.addedMass);
    // its contacts move with its own potential-flow added mass
    EXPECT_NEAR(c.nominalAddedMass, 0.5*rho*8*a*a*a, 1e-12*c.nominalAddedMass);
    EXPECT_NEAR(c.addedInertia, 8.0/15*pi*rho*(std::pow(R, 5) - std::pow(aV, 5)), 1e-12*c.addedInertia);
    EXPECT_GT(c.addedInertia, 0);
    // On a mesh of cells h the body the forcing makes reaches h/2 further
    fluidImpedance::bodySize onMesh = sphereSize(a);
    onMesh.cellSize = 0.4*a;
    const auto m = fluidImpedance::estimate(onMesh, rho, nu, dtSlow);
    EXPECT_NEAR(m.addedMass, 0.5*rho*4.0/3*pi*std::pow(1.2*a, 3), 1e-12*m.addedMass);
    EXPECT_NEAR(m.damping, 6*pi*mu*1.2*a, 2e-6*m.damping);   // q = 1e-6, as above
    // and a round body's rotation still pushes no fluid aside
    EXPECT_NEAR(m.addedInertia, 0, 1e-12*rho*V*a*a);
}


TEST(fluidImpedance, lensesAndTheSolidFractionAround)
{
    // Two unit spheres (circles) one apart: 5 pi/12 (2 pi/3 - sqrt(3)/2)
    EXPECT_NEAR(fluidImpedance::lens(1, 1, 1, false), 5*pi/12, 1e-12);
    EXPECT_NEAR(fluidImpedance::lens(1, 1, 1, true), 2*pi/3 - std::sqrt(3.0)/2, 1e-12);
    // One inside the other; apart
    EXPECT_NEAR(fluidImpedance::lens(2, 0.5, 1, false), 4.0/3*pi*0.125, 1e-12);
    EXPECT_EQ(fluidImpedance::lens(1, 1, 2.5, false), 0);
    // Alone: nothing around. A neighbour of the same size touching it:
    // its part in the shell between a and 2a
    EXPECT_EQ(fluidImpedance::surroundingFraction(1, {}, false), 0);
    const double touching = fluidImpedance::surroundingFraction(1, {{2, 1}}, false);
    EXPECT_NEAR(touching, fluidImpedance::lens(2, 1, 2, false)/(4.0/3*pi*7), 1e-12);
    // Twelve touching neighbours (a close packing) fill much of the shell
    std::vector<std::pair<double, double>> twelve(12, {2, 1});
    EXPECT_NEAR
    (
        fluidImpedance::surroundingFraction(1, twelve, false), 12*touching, 1e-12
    );
    EXPECT_GT(12*touching, 0.3);    // a floor for "much": 12 lenses, not a sliver
    // The added mass grows with it as Zuber's (1 + 2 phi)/(1 - phi)
    fluidImpedance::bodySize s = sphereSize(1e-3);
    const auto alone = fluidImpedance::estimate(s, 1000, 1e-6, 1e-3);
    s.solidFraction = 0.4;
    const auto packed = fluidImpedance::estimate(s, 1000, 1e-6, 1e-3);
    EXPECT_NEAR(packed.addedMass/alone.addedMass, 1.8/0.6, 1e-12);
    EXPECT_EQ(packed.damping, alone.damping);
}


TEST(fluidImpedance, cylinderLimits)
{
    const double rho = 1000, nu = 1e-4, mu = rho*nu, a = 1e-3, L = 2e-3;
    // The added mass of a circular cylinder: its displaced fluid
    const auto fast = fluidImpedance::estimate(cylinderSize(a, L), rho, nu, a*a/nu/1e4);
    EXPECT_NEAR(fast.addedMass, rho*pi*a*a*L, 1e-12*fast.addedMass);
    // q = 100: K1/K0 -> 1 + 1/(2q): 4 pi mu (q + 1/2) per length; 1e-4:
    // the expansion's next term, 3/(8 q^2) = 4e-5
    EXPECT_NEAR(fast.damping, 4*pi*mu*(100 + 0.5)*L, 1e-4*fast.damping);
    // Slow (q = 1e-3): q K1(q) -> 1, so 4 pi mu/K0(q); K0 from its series
    // -ln(q/2) - gamma (error q^2 ln q, 7e-6 here)
    const double q = 1e-3, gamma = 0.5772156649015329;
    const auto slow = fluidImpedance::estimate(cylinderSize(a, L), rho, nu, a*a/nu/(q*q));
    EXPECT_NEAR(slow.damping, 4*pi*mu/(-std::log(q/2) - gamma)*L, 1e-4*slow.damping);  // over the 7e-6
    // A rotating cylinder: 4 pi mu a^2 per length in the steady limit;
    // 1e-3: the step's correction at q = 1e-3 is of order q
    EXPECT_NEAR(slow.angularDamping, 4*pi*mu*a*a*L, 1e-3*slow.angularDamping);
    EXPECT_NEAR(slow.addedInertia, 0, 1e-15);
}


namespace
{

// The partitioned coupling on a model fluid: over each CFD step T the
// fluid sees the body at its velocity of the step before and answers
// with F^{n+1} = -M (v^n - v^{n-1})/T - C v^n (a fluid at rest far away,
// M and C the fluid's true added mass and resistance); the body then
// moves over the next step in the DEM with that force and the implicit
// part z (none: z zero). Returns the largest |v| over the run and the
// final |v|, the body starting at 1 m/s.
std::pair<double, double> coupledRun
(
    double densityRatio,
    double stepOverResponse,
    double addedMassTruth,
    double resistanceTruth,
    bool implicitPart,
    int steps
)
{
    const double rho = 1000, nu = 1e-4, a = 1e-3;
    contactMaterial mat{"m", 1e7, 0.3, 0.5, 0.3};
    demSettings s;
    s.gravity = vec3::Zero();
    demSolver dem({mat}, s);
    dem.addBody(rigidBody("ball", std::make_shared<sphereShape>(a), densityRatio*rho));
    rigidBody& b = dem.bodies()[0];
    const double m = b.mass();

    // The step as a multiple of the viscous response time m/C (C the
    // steady Stokes drag)
    const double T = stepOverResponse*m/(6*pi*rho*nu*a);
    const fluidImpedance::coefficients z =
        fluidImpedance::estimate(sphereSize(a), rho, nu, T);
    const double M = addedMassTruth*z.addedMass;
    const double C = resistanceTruth*z.damping;

    b.velocity = vec3(1, 0, 0);
    vec3 vPrevious = b.velocity;
    double largest = 1;
    for (int n = 0; n < steps; ++n)
    {
        const vec3 F = -M*(b.velocity - vPrevious)/T - C*b.velocity;
        fluidImpedance::coefficients zn = implicitPart ? z : fluidImpedance::coefficients();
        b.fluid = fluidLoad::coupled
        (
            F, vec3::Zero(), zn, dem.time(),
            b.velocity, (b.velocity - vPrevious)/T, vec3::Zero(), vec3::Zero()
        );
        vPrevious = b.velocity;
        dem.advance(T);
        largest = std::max(largest, b.velocity.norm());
        if (!std::isfinite(largest) || largest > 1e6) break;
    }
    return {largest, b.velocity.norm()};
}

} // End anonymous namespace


TEST(fluidImpedance, implicitCouplingIsStableWhereExplicitIsNot)
{
    for (const double ratio : {0.01, 0.1, 0.3, 1.0, 10.0})
    {
        for (const double response : {0.1, 1.0, 10.0, 100.0})
        {
            for (const double M : {0.3, 1.0})
            {
                for (const double C : {0.5, 1.0, 1.9})
                {
                    const auto r = coupledRun(ratio, response, M, C, true, 400);
                    // Decays to 1e-6 of the start within 400 steps, and
                    // never above it (the body cannot move faster than
                    // it started; 1e-9 for round-off)
                    EXPECT_LT(r.second, 1e-6)
                        << "density ratio " << ratio << ", step/response "
                        << response << ", truth/estimate " << M << ' ' << C;
                    EXPECT_LT(r.first, 1 + 1e-9)
                        << "density ratio " << ratio << ", step/response "
                        << response << ", truth/estimate " << M << ' ' << C;
                }
            }
        }
    }
    // Without the implicit part the same loop blows up, for a light body
    // (added mass 5 times its mass) and for a heavy one whose viscous
    // response is a tenth of the step
    EXPECT_GT(coupledRun(0.1, 0.1, 1, 1, false, 100).first, 1e3);
    EXPECT_GT(coupledRun(10, 10, 1, 1, false, 100).first, 1e3);
}
