/*---------------------------------------------------------------------------*\
Description
    The potential contact law (contactLaw potential, issue 19): the force
    w'(V) S and couple w'(V) M are the gradient of w(V), so
    - the area vector S and area moment M of the virtual mesh are minus the
      derivatives of the exact overlap volume with respect to B's
      translation and rotation (central differences of the exact engine);
    - two spheres collide with the volume law's peak force and duration
      (within 1%) and give the energy back;
    - the regularised face stiffness k0 bounds the slope of the force and
      w is the integral of w'.
    (STL icospheres and the closed box with e = 1: not yet a test, the
    automatic step of meshes under this law is ~45x the volume law's
    steps, see issue 19's report.)
\*---------------------------------------------------------------------------*/

#include "demSolver.H"
#include "sphereShape.H"
#include "sphereOverlap.H"
#include "halfSpaceShape.H"
#include "triangleMeshShape.H"
#include "primitiveMeshes.H"
#include "virtualMeshOverlap.H"
#include "exactOverlap.H"
#include "potentialContactLaw.H"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

using namespace immersedDEM;

namespace
{

const double R = 0.005, rho = 1000, Y = 1e8, nu = 0.5;

struct run
{
    double peakForce = 0;
    double duration = 0;
    double energyRatio = 0;
    double momentumError = 0;   //!< |L_after - L_before| / (m v R)
};

// Two bodies at relative speed v along x, B offset by b in y; until they
// separate (the contact ends)
run collide
(
    const std::string& law, const std::string& method,
    std::shared_ptr<const shape> g, double v, double b
)
{
    contactMaterial rubber{"rubber", Y, nu, 1.0, 0};
    demSettings s;
    s.contactLaw = law;
    s.overlapMethod = method;
    s.overlap = {2*R/20, 4};
    s.stepsPerContact = 60;
    s.referenceSpeed = v;
    demSolver dem({rubber}, s);
    rigidBody A("a", g, rho), B("b", g, rho);
    A.pose = g->poseFromFilePlacement(quat::Identity(), vec3::Zero());
    B.pose = g->poseFromFilePlacement(quat::Identity(), vec3(2*R + 0.01*R, b, 0));
    A.velocity = vec3(0.5*v, 0, 0);
    B.velocity = vec3(-0.5*v, 0, 0);
    dem.addBody(A);
    dem.addBody(B);
    auto L = [&]
    {
        vec3 l = vec3::Zero();
        for (const rigidBody& x : dem.bodies())
        {
            l += x.mass()*x.pose.position().cross(x.velocity) + x.angularMomentum();
        }
        return l;
    };
    const double E0 = dem.kineticEnergy();
    const vec3 L0 = L();
    const double dt = dem.timeStep();
    run r;
    bool touched = false;
    double t0 = -1;
    for (int n = 0; n < 200000; ++n)
    {
        dem.step(dt);
        const double f = dem.bodies()[1].contactForce.norm();
        r.peakForce = std::max(r.peakForce, f);
        if (f > 0 && !touched) { touched = true; t0 = dem.time(); }
        if (touched && f == 0) { r.duration = dem.time() - t0; break; }
    }
    r.energyRatio = dem.kineticEnergy()/E0;
    r.momentumError = (L() - L0).norm()/(dem.bodies()[0].mass()*v*R);
    return r;
}

} // End anonymous namespace


TEST(potentialContact, areaVectorAndMomentAreTheVolumeGradient)
{
    // A cube tilted about two axes pressing an edge and corner region into
    // a bigger cube's face, off-centre: S = -dV/dx_B, M_p = -dV/dtheta_B
    // about the contact point p, V from the exact engine
    const triangleMeshShape big(primitiveMeshes::box(vec3::Constant(0.005)), "big");
    const triangleMeshShape small(primitiveMeshes::box(vec3::Constant(0.002)), "small");
    const bodyPose pA = big.poseFromFilePlacement(quat::Identity(), vec3::Zero());
    const quat q = bodyPose::axisAngle(vec3(1, 0.3, 0).normalized(), 0.5)
        *bodyPose::axisAngle(vec3(0, 0, 1), 0.2);
    const bodyPose p0 = small.poseFromFilePlacement(q, vec3(0.0064, 0.0015, -0.001));

    overlapSettings s{0.0002, 5};
    const auto g = virtualMeshOverlap().evaluate(big, pA, small, p0, s);
    ASSERT_EQ(g.regions.size(), 1u);
    const contactRegion& r = g.regions[0];
    ASSERT_GT(r.volume, 0);
    const double V = exactOverlap().evaluate(big, pA, small, p0, {}).volume();
    std::cout << "V " << r.volume << " (exact " << V << "), S " << r.areaVector.transpose()
        << ", M " << r.areaMoment.transpose() << std::endl;

    auto volumeAt = [&](const vec3& dx, const vec3& dtheta)
    {
        // B translated by dx and turned by dtheta about the point p
        const double a = dtheta.norm();
        const quat dq = a > 0 ? bodyPose::axisAngle(dtheta/a, a) : quat::Identity();
        const vec3 c = r.point + dq*(p0.position() - r.point) + dx;
        const bodyPose p(c, dq*p0.orientation());
        return exactOverlap().evaluate(big, pA, small, p, {}).volume();
    };
    const double e = 1e-6, a = 1e-4;
    const double Sref = r.areaVector.norm();
    const double lref = std::cbrt(r.volume/Sref*Sref);
    for (int k = 0; k < 3; ++k)
    {
        const vec3 u = vec3::Unit(k);
        const double dVdx = (volumeAt(e*u, vec3::Zero()) - volumeAt(-e*u, vec3::Zero()))/(2*e);
        const double dVdt = (volumeAt(vec3::Zero(), a*u) - volumeAt(vec3::Zero(), -a*u))/(2*a);
        std::cout << "axis " << k << ": -dV/dx " << -dVdx << " S " << r.areaVector[k]
            << "; -dV/dtheta " << -dVdt << " M " << r.areaMoment[k] << std::endl;
        EXPECT_NEAR(r.areaVector[k], -dVdx, 0.02*Sref) << "axis " << k;
        EXPECT_NEAR(r.areaMoment[k], -dVdt, 0.02*Sref*std::sqrt(Sref)) << "axis " << k;
    }
    (void)lref;
}


TEST(potentialContact, spheresMatchTheVolumeLaw)
{
    auto sph = std::make_shared<sphereShape>(R);
    const run vol = collide("volume", "sphere", sph, 1.0, 0);
    const run pot = collide("potential", "sphere", sph, 1.0, 0);
    std::cout << "spheres: peak " << pot.peakForce << " N (volume law " << vol.peakForce
        << "), duration " << pot.duration << " s (" << vol.duration << "), energy "
        << pot.energyRatio << std::endl;
    EXPECT_NEAR(pot.peakForce/vol.peakForce, 1, 0.01);
    EXPECT_NEAR(pot.duration/vol.duration, 1, 0.01);
    EXPECT_NEAR(pot.energyRatio, 1, 1e-3);
}


TEST(potentialContact, faceStiffnessBoundsTheStep)
{
    // The regularised force on a face of area A: k0 = Y* A^2/(2 l_c
    // sqrt(pi R* V0)) is its largest slope (at zero depth)
    const potentialContactLaw law;
    contactMaterial m{"m", Y, nu, 1.0, 0};
    const pairMaterial pm = pairMaterial::of(m, m);
    const double A = 1e-5, Rs = 0.003, lc = Rs;
    const double k0 = law.faceStiffness(pm, A, Rs, lc);
    for (double d : {1e-12, 1e-9, 1e-7, 1e-5})
    {
        const double slope =
            (potentialContactLaw::dWdV(A*(d + 1e-13), pm.effectiveModulus, lc, Rs)
           - potentialContactLaw::dWdV(A*d, pm.effectiveModulus, lc, Rs))*A/1e-13;
        EXPECT_LE(slope, k0*(1 + 1e-6)) << d;
    }
    // w is the integral of w'
    const double V = 2e-10, dV = 1e-16;
    EXPECT_NEAR
    (
        (potentialContactLaw::energy(V + dV, pm.effectiveModulus, lc, Rs)
       - potentialContactLaw::energy(V - dV, pm.effectiveModulus, lc, Rs))/(2*dV),
        potentialContactLaw::dWdV(V, pm.effectiveModulus, lc, Rs),
        1e-6*potentialContactLaw::dWdV(V, pm.effectiveModulus, lc, Rs)
    );
}
