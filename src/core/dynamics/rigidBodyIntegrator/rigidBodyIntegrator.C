#include "rigidBodyIntegrator.H"

#include <Eigen/Cholesky>

#include <cmath>

namespace immersedDEM
{

namespace
{

//- Exact rotation of the pose by the world angular velocity w over dt
void rotateByWorldAngularVelocity(bodyPose& pose, const vec3& w, double dt)
{
    const double w2 = w.squaredNorm();
    if (w2 == 0 || dt == 0)
    {
        return;
    }
    // World-frame increment, applied on the left: the unit quaternion
    // (cos(x), sin(x) w/|w|) of the half angle x = |w| dt/2. This runs for
    // every body and step, where x is small: there cos(x) and sin(x)/x by
    // their series, exact to round-off below x = 0.01 (the first term
    // left out is below x^8/40320 = 2.5e-21), with no root, division or
    // call
    const double x2 = 0.25*w2*dt*dt;
    // (the series' coefficients as constants: the core is compiled with
    // CGAL's -frounding-math, under which 1.0/24 written in the expression
    // is divided at run time, five divisions per body and step)
    constexpr double c2 = 1.0/2, c24 = 1.0/24, c720 = 1.0/720;
    constexpr double s6 = 1.0/6, s120 = 1.0/120, s5040 = 1.0/5040;
    double c, k;        // cos(x), sin(x)/|w|
    if (x2 < 1e-4)
    {
        c = 1 - x2*(c2 - x2*(c24 - x2*c720));
        k = 0.5*dt*(1 - x2*(s6 - x2*(s120 - x2*s5040)));
    }
    else
    {
        const double wMag = std::sqrt(w2);
        const double x = 0.5*wMag*dt;
        c = std::cos(x);
        k = std::sin(x)/wMag;
    }
    pose.rotateBy(quat(c, k*w.x(), k*w.y(), k*w.z()));
}


//- The free-rotor flow of the body-frame momentum pi and orientation q
//  over dt by the symmetric splitting into exact rotations about the
//  principal axes
void freeRotorSplitting(quat& q, vec3& pi, const vec3& I, double dt)
{
    const auto rotateAbout = [&](int k, double tau)
    {
        const double theta = tau*pi[k]/I[k];
        if (theta == 0)
        {
            return;
        }
        const double c = std::cos(theta);
        const double s = std::sin(theta);

        // The world momentum is fixed, so the body-frame one turns the
        // other way: pi <- Rot_k(-theta) pi
        const int i = (k + 1) % 3;
        const int j = (k + 2) % 3;
        const double pi_i = pi[i];
        const double pi_j = pi[j];
        pi[i] = c*pi_i + s*pi_j;
        pi[j] = -s*pi_i + c*pi_j;

        // Body-frame increment: applied on the right
        quat dq(std::cos(0.5*theta), 0, 0, 0);
        dq.vec()[k] = std::sin(0.5*theta);
        q = q*dq;
    };

    rotateAbout(0, 0.5*dt);
    rotateAbout(1, 0.5*dt);
    rotateAbout(2, dt);
    rotateAbout(1, 0.5*dt);
    rotateAbout(0, 0.5*dt);
}

//- The kick's rotation with locked axes (apart: its 3x3 solve's stack
//  frame would make every kick dearer)
__attribute__((noinline)) void kickLocked(rigidBody& b, const vec3& T, double halfDt)
{
    // Locked axes: omega lives on the free world axes f, where the
    // constrained Euler equation is I_ff d(omega_f)/dt = T_f (the constraint
    // torque does no work on the free axes). It equals the simpler
    // P I^-1 T when the locked axes are principal (the usual 2D body); for a
    // tilted body P I^-1 T would let a torque about a locked axis spin it
    // about a free one, and would use the wrong inertia about the free axis.
    int freeAxes[3];
    int nFree = 0;
    for (int k = 0; k < 3; ++k)
    {
        if (b.lockRotation[k])
        {
            b.angularVelocity[k] = 0;
        }
        else
        {
            freeAxes[nFree++] = k;
        }
    }
    if (nFree == 0)
    {
        return;
    }

    // At most 3x3: fixed-capacity storage, no heap allocation per kick
    using smallMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3, 3>;
    using smallVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 3, 1>;

    const mat3 Iw = b.worldInertia();
    smallMatrix Iff(nFree, nFree);
    smallVector rhs(nFree);
    // The fluid's added moment of inertia and its damper, implicit
    // (fluidLoad.H): (I_ff + I_a + h c) dw = h T_f
    const double Ia = b.fluid.addedInertia + halfDt*b.fluid.angularDamping;
    for (int a = 0; a < nFree; ++a)
    {
        rhs[a] = T[freeAxes[a]]*halfDt;
        for (int c = 0; c < nFree; ++c)
        {
            Iff(a, c) = Iw(freeAxes[a], freeAxes[c]);
        }
        if (Ia > 0)
        {
            Iff(a, a) += Ia;
        }
    }
    const smallVector dw = Iff.ldlt().solve(rhs);
    for (int a = 0; a < nFree; ++a)
    {
        b.angularVelocity[freeAxes[a]] += dw[a];
    }
}

} // End anonymous namespace


void rigidBodyIntegrator::kick(rigidBody& b, double halfDt)
{
    if (b.motion != motionType::free)
    {
        return;
    }

    // Translation

    // The fluid's added mass m_a and damper c (fluidLoad.H; both 0
    // without a fluid), the damper implicit: the force is taken at the
    // velocity after the kick, F - c (v_new - v), stable for any c/m.
    // With a contact force in this sub-step the body moves with its own
    // added mass (an impact is far faster than the fluid's answer); the
    // term m_a a_ref, which cancels the fluid's answer to the last step's
    // acceleration held in its force, stays whole. A body under the
    // contact rule has no added mass as inertia (0 in both)
    const double ma =
        b.contactForce.isZero() ? b.fluid.addedMass : b.fluid.nominalAddedMass;
    b.velocity +=
        (b.totalForce() + b.fluid.inertialForce())
       *(halfDt/(b.mass() + ma + halfDt*b.fluid.damping));
    for (int k = 0; k < 3; ++k)
    {
        if (b.lockTranslation[k])
        {
            b.velocity[k] = 0;
        }
    }

    // Rotation

    const vec3 I = b.inertia();

    if (b.fluid.addedInertia > 0 || b.fluid.angularDamping > 0)
    {
        const vec3 T = b.totalTorque() + b.fluid.inertialTorque();
        if (!b.lockRotation.isZero())
        {
            kickLocked(b, T, halfDt);
            return;
        }
        // Per principal axis (I_k + I_a + h c) dw_k = h T_k: the added
        // moment is isotropic, the damper's torque taken after the kick
        const double extra =
            b.fluid.addedInertia + halfDt*b.fluid.angularDamping;
        const vec3 dwBody =
            (b.pose.vectorToBody(T)*halfDt).cwiseQuotient
            (
                I + vec3::Constant(extra)
            );
        b.angularVelocity += b.pose.vectorToWorld(dwBody);
        return;
    }

    const vec3 T = b.totalTorque();

    if (b.lockRotation.isZero())
    {
        // Isotropic body (sphere, cube; as drift decides): L = I w in any
        // frame, the kick needs no rotation
        if (b.isotropic())
        {
            b.angularVelocity += T*(halfDt/I.x());
            return;
        }
        // Kick the angular momentum, not omega: with the drift's exact
        // momentum-conserving rotor this keeps |L| exact when T = 0. Done in
        // the body frame, where the inertia is diagonal.
        const vec3 Lbody =
            I.cwiseProduct(b.pose.vectorToBody(b.angularVelocity))
          + b.pose.vectorToBody(T)*halfDt;
        b.angularVelocity = b.pose.vectorToWorld(Lbody.cwiseQuotient(I));
        return;
    }

    kickLocked(b, T, halfDt);
}


void rigidBodyIntegrator::drift(rigidBody& b, double dt)
{
    switch (b.motion)
    {
        case motionType::fixed:
        {
            return;
        }

        case motionType::prescribed:
        {
            b.pose.setPosition(b.pose.position() + b.velocity*dt);
            rotateByWorldAngularVelocity(b.pose, b.angularVelocity, dt);
            return;
        }

        case motionType::free:
        {
            b.pose.setPosition(b.pose.position() + b.velocity*dt);

            if (!b.lockRotation.isZero())
            {
                rotateByWorldAngularVelocity(b.pose, b.angularVelocity, dt);
                return;
            }

            // Isotropic body (sphere, cube): the free rotor is the exact
            // rotation about the fixed omega, cheaper and without the
            // splitting error
            if (b.isotropic())
            {
                rotateByWorldAngularVelocity(b.pose, b.angularVelocity, dt);
                return;
            }
            const vec3 I = b.inertia();

            quat q = b.pose.orientation();
            vec3 pi = I.cwiseProduct(b.pose.vectorToBody(b.angularVelocity));

            freeRotorSplitting(q, pi, I, dt);

            // Every factor was unit, so this only removes round-off drift
            q.normalize();
            b.pose.setOrientation(q);
            b.angularVelocity = b.pose.vectorToWorld(pi.cwiseQuotient(I));
            return;
        }
    }
}

} // End namespace immersedDEM
