// The forcing's formulas (immersedForcing) and the fluid load's restart
// list (fluidLoad::fields), without a mesh.

#include "immersedForcing.H"
#include "fluidLoad.H"

#include <gtest/gtest.h>

#include <set>
#include <string>

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
    const vec3 F = immersedForcing::fluidForce(rho, P, M, M0, deltaT, Vb, g);
    EXPECT_NEAR(F.x(), rho*1e-6, 1e-15);
    EXPECT_NEAR(F.y(), rho*2e-9/deltaT, 1e-15);
    EXPECT_NEAR(F.z(), rho*2e-6 + rho*Vb*9.81, 1e-15);   // buoyancy upwards
    const vec3 T = immersedForcing::fluidTorque(rho, P, M, M0, deltaT);
    EXPECT_NEAR(T.z(), rho*2e-6, 1e-15);
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
    EXPECT_EQ(nScalars, 5);
    EXPECT_EQ(names.size(), 11u);
    // Every member was reached: none is left at its default
    EXPECT_EQ(l.force.sum() + l.torque.sum() + l.referenceVelocity.sum()
        + l.referenceAcceleration.sum() + l.referenceAngularVelocity.sum()
        + l.referenceAngularAcceleration.sum(), 18);
    EXPECT_EQ(l.damping + l.addedMass + l.nominalAddedMass + l.referenceTime + l.angularDamping, 5);
    EXPECT_EQ(sizeof(fluidLoad), 6*sizeof(vec3) + 5*sizeof(double));
}

TEST(fluidLoad, stabilisedFollowsTheExtrapolatedMotion)
{
    const double deltaT = 1e-3, t = 0.5;
    const vec3 v(0.1, 0, 0), vPrev(0.09, 0, 0), w(0, 1, 0), wPrev(0, 1, 0);
    // A body in contact: the damper
    const fluidLoad l = fluidLoad::stabilised
    (
        vec3(0, 0, 1), vec3(0, 0, 2), 0.2, 0.1, false, 0.01, deltaT, t, v, vPrev, w, wPrev
    );
    EXPECT_DOUBLE_EQ(l.damping, 0.2/deltaT);
    EXPECT_EQ(l.addedMass, 0);
    EXPECT_EQ(l.nominalAddedMass, 0);
    EXPECT_DOUBLE_EQ(l.angularDamping, 0.01/deltaT);
    // On the extrapolated course: the plain load
    const vec3 vLater = v + 0.5*deltaT*(v - vPrev)/deltaT;
    EXPECT_NEAR((l.appliedForce(vLater, t + 0.5*deltaT) - vec3(0, 0, 1)).norm(), 0, 1e-12);
    // A departure meets the added mass
    EXPECT_NEAR(l.appliedForce(v + vec3(0.01, 0, 0), t).x(), -0.2/deltaT*0.01, 1e-12);
    EXPECT_NEAR((l.appliedTorque(w, t) - vec3(0, 0, 2)).norm(), 0, 1e-12);
    EXPECT_NEAR(l.inertialForce().norm(), 0, 1e-15);

    // A body free of contacts: the added mass is inertia, the force plain
    const fluidLoad f = fluidLoad::stabilised
    (
        vec3(0, 0, 1), vec3(0, 0, 2), 0.2, 0.1, true, 0.01, deltaT, t, v, vPrev, w, wPrev
    );
    EXPECT_EQ(f.damping, 0);
    EXPECT_DOUBLE_EQ(f.addedMass, 0.2);
    EXPECT_DOUBLE_EQ(f.nominalAddedMass, 0.1);
    EXPECT_NEAR((f.appliedForce(v + vec3(0.01, 0, 0), t) - vec3(0, 0, 1)).norm(), 0, 1e-12);
    EXPECT_NEAR((f.inertialForce() - 0.2*(v - vPrev)/deltaT).norm(), 0, 1e-12);
    EXPECT_DOUBLE_EQ(f.angularDamping, 0.01/deltaT);
}
