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
    - V0 from the pair's largest flat face: a face's first-touch stiffness
      is the volume law's, never above it;
    - two STL icospheres (e = 1, head-on and off-centre) give the kinetic
      energy back within 0.1%, with contacts reused;
    - a sphere and two blocks in a closed box of six planes (e = 1,
      mu = 0, no gravity): the kinetic energy at contact-free moments
      within 0.1% over 1e5 steps at stepsPerContact 30, at the default
      level (the suite runs 2e4).
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
#include <cstdlib>
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
    std::shared_ptr<const shape> g, double v, double b, bool reuse = true
)
{
    contactMaterial rubber{"rubber", Y, nu, 1.0, 0};
    demSettings s;
    s.contactLaw = law;
    s.overlapMethod = method;
    s.overlap = {2*R/20, 4};
    s.stepsPerContact = 60;
    s.referenceSpeed = v;
    s.reuseContacts = reuse;
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
        // 2%: S and M are the overlap's surface integrals, the differences
        // of a faceted body's exact volume at steps 1e-6 m and 1e-4 rad
        // cross facet edges, which kink V
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
    // as testDemCollision's: 1% for the sampled peak and end, 1e-3 of the
    // energy for the integrator over one contact
    EXPECT_NEAR(pot.peakForce/vol.peakForce, 1, 0.01);
    EXPECT_NEAR(pot.duration/vol.duration, 1, 0.01);
    EXPECT_NEAR(pot.energyRatio, 1, 1e-3);
}


TEST(potentialContact, faceStiffnessBoundsTheStep)
{
    // A face of area A <= A_f on a face: the force w'(A d) A has its
    // largest slope at zero depth, Y* A^2/(l_c A_f), the volume law's
    // Y* A/l_c at A = A_f (faceStiffness) and below it for smaller faces;
    // it stays within 0.1% of the volume law's force down to depths
    // d << A_f/(4 pi R*)
    const potentialContactLaw law;
    contactMaterial m{"m", Y, nu, 1.0, 0};
    const pairMaterial pm = pairMaterial::of(m, m);
    const double Af = 1e-5, Rs = 0.003, lc = Rs, Ys = pm.effectiveModulus;
    const double V0 = potentialContactLaw::referenceVolume(Af, Rs);
    EXPECT_NEAR(V0, Af*Af/(4*M_PI*Rs), 1e-12*V0);
    const double kVolume = law.faceStiffness(pm, Af, Rs, lc);
    EXPECT_NEAR(kVolume, Ys*Af/lc, 1e-12*kVolume);
    for (const double A : {Af, 0.3*Af})
    {
        for (double d : {1e-12, 1e-9, 1e-7, 1e-5})
        {
            const double slope =
                (potentialContactLaw::dWdV(A*(d + 1e-13), Ys, lc, Rs, V0)
               - potentialContactLaw::dWdV(A*d, Ys, lc, Rs, V0))*A/1e-13;
            EXPECT_LE(slope, Ys*A*A/(lc*Af)*(1 + 1e-6)) << d;
        }
    }
    const double d = 1e-4*Af/(4*M_PI*Rs);
    // 1e-4: the floor's share at this depth (1e-4 of the reference)
    EXPECT_NEAR(potentialContactLaw::dWdV(Af*d, Ys, lc, Rs, V0)*Af/(Ys*Af*d/lc), 1, 1e-4);
    // Spheres and smooth shapes: the floor pi R* (eps R*)^2
    EXPECT_EQ(potentialContactLaw::referenceVolume(0, Rs), M_PI*Rs*std::pow(1e-3*Rs, 2));
    // w is the integral of w'
    const double V = 2e-10, dV = 1e-16;
    EXPECT_NEAR
    (
        (potentialContactLaw::energy(V + dV, Ys, lc, Rs, V0)
       - potentialContactLaw::energy(V - dV, Ys, lc, Rs, V0))/(2*dV),
        potentialContactLaw::dWdV(V, Ys, lc, Rs, V0),
        1e-6*potentialContactLaw::dWdV(V, Ys, lc, Rs, V0)
    );
}


TEST(potentialContact, largestFlatFace)
{
    // Coplanar edge-connected triangles make a face: a box's largest is
    // 2a x 2b; an icosphere's is one triangle; spheres none, planes all
    const triangleMeshShape block(primitiveMeshes::box(vec3(0.005, 0.003, 0.002)), "block");
    EXPECT_NEAR(block.largestFlatFace(), 0.010*0.006, 1e-12);
    const triangleMeshShape ico(primitiveMeshes::icosphere(R, 2), "ico");
    EXPECT_GT(ico.largestFlatFace(), 0);
    EXPECT_LT(ico.largestFlatFace(), 4*M_PI*R*R/320*1.5);
    EXPECT_EQ(sphereShape(R).largestFlatFace(), 0);
    EXPECT_TRUE(std::isinf(halfSpaceShape().largestFlatFace()));
}


namespace
{

struct energyRun
{
    double worstDrift = 0;      //!< max |E/E0 - 1| at contact-free moments
    double finalDrift = 0;      //!< at the last contact-free moment
    long freeMoments = 0;
    long contactSteps = 0;
    double dt = 0;
};

// A sphere and two blocks (the templates' block.stl, 10 x 6 x 4 mm) in a
// closed box of six planes, e = 1, mu = 0, no gravity (issue 19)
energyRun closedBox(const std::string& law, long steps, int level, bool reuse = true)
{
    contactMaterial rubber{"rubber", 1e6, 0.45, 1.0, 0};
    demSettings s;
    s.contactLaw = law;
    s.overlap = {2e-3, level};      // the bouncingBodies template's cell
    s.stepsPerContact = 30;
    s.referenceSpeed = 1;
    s.reuseContacts = reuse;
    demSolver dem({rubber}, s);
    const double L = 0.03;
    for (int k = 0; k < 6; ++k)
    {
        const vec3 n = (k%2 ? 1.0 : -1.0)*vec3::Unit(k/2);
        rigidBody w("wall" + std::to_string(k), std::make_shared<halfSpaceShape>(), 1);
        w.pose = halfSpaceShape::poseOf(-L*n, n);
        w.motion = motionType::fixed;
        dem.addBody(w, true);
    }
    auto block = std::make_shared<triangleMeshShape>
    (
        primitiveMeshes::box(vec3(0.005, 0.003, 0.002)), "block.stl"
    );
    rigidBody ball("ball", std::make_shared<sphereShape>(0.005), 1000);
    ball.pose = bodyPose(vec3(-0.015, 0.002, 0.001), quat::Identity());
    ball.velocity = vec3(1.0, 0.3, -0.2);
    dem.addBody(ball);
    rigidBody b1("block1", block, 2500);
    b1.pose = bodyPose(vec3(0.012, 0.012, -0.01), bodyPose::axisAngle(vec3(1, 1, 0).normalized(), 0.35));
    b1.velocity = vec3(-0.5, 0.8, 0.1);
    b1.angularVelocity = vec3(20, -10, 30);
    dem.addBody(b1);
    rigidBody b2("block2", block, 2500);
    b2.pose = bodyPose(vec3(0.0, -0.015, 0.013), bodyPose::axisAngle(vec3(0.2, -1, 0.5).normalized(), 1.1));
    b2.velocity = vec3(0.3, -0.6, 0.7);
    b2.angularVelocity = vec3(-15, 25, 5);
    dem.addBody(b2);

    const double E0 = dem.kineticEnergy();
    energyRun r;
    r.dt = dem.timeStep();
    for (long n = 0; n < steps; ++n)
    {
        dem.step(r.dt);
        if (!dem.contacts().empty())
        {
            ++r.contactSteps;
            continue;
        }
        const double e = dem.kineticEnergy()/E0 - 1;
        r.worstDrift = std::max(r.worstDrift, std::abs(e));
        r.finalDrift = e;
        ++r.freeMoments;
    }
    return r;
}

} // End anonymous namespace


TEST(potentialContact, closedBoxKeepsTheEnergy)
{
    // The bodies' pairs: ball-wall exact (a sphere and a plane), block-wall
    // and block-block exact (convex), ball-block on the octree. Measured
    // over 1e5 steps (IMMERSEDDEM_ENERGY_STEPS=100000, 20 s): at level 4
    // (the default level) worst drift 0.018%, final -0.017%; at the
    // bouncingBodies template's level 2 (leaves of 0.5 mm against a 4 mm
    // block) 0.195%, nearly all of it from one ball-block contact (+0.18%),
    // level 3 0.074%: the octree's volume at that resolution, not the law
    // (with every contact measured afresh, no reuse, the same figures).
    // Before the exact convex pairs (the blocks on the octree too), 0.35%
    // at level 2. IMMERSEDDEM_VOLUME_LAW=1 adds the volume law (8.6% with
    // reuse, 6.7% without, at level 2, before the convex pairs). The suite
    // runs the first 2e4 steps, at level 4 against the 0.1%, and
    // at level 2 printed
    long steps = 20000;
    if (const char* n = std::getenv("IMMERSEDDEM_ENERGY_STEPS")) steps = std::atol(n);
    if (std::getenv("IMMERSEDDEM_VOLUME_LAW"))
    {
        for (const bool reuse : {true, false})
        {
            const energyRun vol = closedBox("volume", steps, 2, reuse);
            std::cout << "closed box, volume law, level 2, reuse " << reuse << ": dt " << vol.dt
                << " s, worst drift " << vol.worstDrift << ", final " << vol.finalDrift
                << ", contact steps " << vol.contactSteps << std::endl;
        }
    }
    for (const int level : {2, 4})
    {
        const energyRun pot = closedBox("potential", steps, level);
        std::cout << "closed box, potential, level " << level << ": dt " << pot.dt
            << " s, worst drift " << pot.worstDrift << ", final " << pot.finalDrift
            << ", contact steps " << pot.contactSteps << std::endl;
        EXPECT_GT(pot.contactSteps, 1000);      // enough contact to test
        EXPECT_GT(pot.freeMoments, 1000);
        // 1e-3 at level 4: the 0.1% (measured 0.018% over 1e5
        // steps); 5e-3 at level 2: the octree's volume error at 0.5 mm
        // leaves (measured 0.195%, above)
        EXPECT_LT(pot.worstDrift, level == 4 ? 1e-3 : 5e-3) << "level " << level;
    }
}


TEST(potentialContact, icospheresGiveTheEnergyBack)
{
    // Two STL icospheres (320 faces), e = 1, head-on and off-centre, on the
    // virtual mesh: the kinetic energy back within 0.1%, angular momentum
    // kept (the couple w'(V) M)
    auto ico = std::make_shared<triangleMeshShape>(primitiveMeshes::icosphere(R, 2), "ico");
    for (const double b : {0.0, 0.6*R})
    {
        const run pot = collide("potential", "virtualMesh", ico, 1.0, b);
        std::cout << "icospheres, offset " << b/R << " R: energy " << pot.energyRatio
            << ", peak " << pot.peakForce << " N, duration " << pot.duration
            << " s, angular momentum error " << pot.momentumError << std::endl;
        EXPECT_GT(pot.duration, 0);
        // 0.1% of the energy (the header's); 1e-6 of the angular momentum:
        // the couple w'(V) M conserves it up to the integrator's round-off
        EXPECT_NEAR(pot.energyRatio, 1, 1e-3) << "offset " << b;
        EXPECT_LT(pot.momentumError, 1e-6) << "offset " << b;
    }
}
