#include "rigidBody.H"
#include "rigidBodyIntegrator.H"
#include "sphereShape.H"
#include "triangleMeshShape.H"
#include "primitiveMeshes.H"
#include "testHelpers.H"

#include <gtest/gtest.h>

#include <cstdio>
#include <functional>

using namespace immersedDEM;
using immersedDEM::test::relErr;

namespace
{

//- Box of half extents (0.03 0.02 0.01): three distinct principal moments
std::shared_ptr<const shape> boxShape()
{
    static const std::shared_ptr<const shape> s =
        std::make_shared<triangleMeshShape>
        (
            primitiveMeshes::box(vec3(0.03, 0.02, 0.01)), "box"
        );
    return s;
}

std::shared_ptr<const shape> sphere(double R)
{
    return std::make_shared<sphereShape>(R);
}

//- One velocity-Verlet step; setForce sets the body's external force and
//  torque from its current state
void step
(
    rigidBody& b,
    double dt,
    const std::function<void(rigidBody&)>& setForce
)
{
    setForce(b);
    rigidBodyIntegrator::kick(b, 0.5*dt);
    rigidBodyIntegrator::drift(b, dt);
    setForce(b);
    rigidBodyIntegrator::kick(b, 0.5*dt);
}

void noForce(rigidBody&) {}

//- Rotation-matrix distance: well conditioned near zero, unlike an angle
//  from acos, and blind to the sign of the quaternion
double rotationDistance(const quat& a, const quat& b)
{
    return (a.toRotationMatrix() - b.toRotationMatrix()).norm();
}

//- A free box at a random orientation spinning at |omega| = 10 rad/s with
//  the body-frame direction omegaBody
rigidBody spinningBox(const vec3& omegaBody, unsigned seed = 1)
{
    rigidBody b("box", boxShape(), 1000);
    std::mt19937 gen(seed);
    b.pose = bodyPose(vec3(0.1, 0.2, 0.3), test::randomQuat(gen));
    b.angularVelocity = b.pose.vectorToWorld(10*omegaBody.normalized());
    return b;
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * * rigidBody * * * * * * * * * * * * * * * //

TEST(rigidBody, massAndInertiaFromShapeAndDensity)
{
    const double R = 0.01;
    const rigidBody s("sphere", sphere(R), 2500);
    const double m = 2500*4.0/3.0*M_PI*R*R*R;
    EXPECT_LT(relErr(s.mass(), m), 1e-14);
    for (int k = 0; k < 3; ++k)
    {
        EXPECT_LT(relErr(s.inertia()[k], 0.4*m*R*R), 1e-14);
    }
    EXPECT_LT(relErr(s.equivalentRadius(), R), 1e-14);

    // Box 2a x 2b x 2c: I = m/3 (b^2 + c^2) etc., ascending
    const rigidBody b("box", boxShape(), 1000);
    const double mb = 1000*8*0.03*0.02*0.01;
    EXPECT_LT(relErr(b.mass(), mb), 1e-12);
    EXPECT_LT(relErr(b.inertia()[0], mb/3*(0.0004 + 0.0001)), 1e-12);
    EXPECT_LT(relErr(b.inertia()[1], mb/3*(0.0009 + 0.0001)), 1e-12);
    EXPECT_LT(relErr(b.inertia()[2], mb/3*(0.0009 + 0.0004)), 1e-12);
    EXPECT_LT
    (
        relErr(b.equivalentRadius(), std::cbrt(3*8*0.03*0.02*0.01/(4*M_PI))),
        1e-12
    );
    EXPECT_EQ(b.motion, motionType::free);
    EXPECT_TRUE(b.dynamic());
}

TEST(rigidBody, worldInertiaEnergyAndMomentum)
{
    rigidBody b("box", boxShape(), 1000);
    std::mt19937 gen(7);
    b.pose = bodyPose(vec3(1, 2, 3), test::randomQuat(gen));
    b.velocity = vec3(0.3, -0.1, 0.2);
    b.angularVelocity = vec3(2, -5, 1);

    const mat3 R = b.pose.rotation();
    const mat3 Iw = b.worldInertia();
    const mat3 expected = R*b.inertia().asDiagonal()*R.transpose();
    EXPECT_LT((Iw - expected).norm(), 1e-14*expected.norm());
    EXPECT_LT((Iw - Iw.transpose()).norm(), 1e-14*expected.norm());

    const vec3& w = b.angularVelocity;
    const double E = 0.5*b.mass()*b.velocity.squaredNorm() + 0.5*w.dot(Iw*w);
    EXPECT_LT(relErr(b.kineticEnergy(), E), 1e-13);
    EXPECT_LT((b.angularMomentum() - Iw*w).norm(), 1e-13*(Iw*w).norm());

    // The material point velocity includes the rotation
    const vec3 x = b.pose.position() + vec3(0.01, 0, 0);
    EXPECT_LT
    (
        (b.pointVelocity(x) - (b.velocity + w.cross(vec3(0.01, 0, 0)))).norm(),
        1e-15
    );
}

TEST(rigidBody, badInputThrows)
{
    const auto s = sphere(0.01);
    for (double rho : {0.0, -1.0, std::nan(""), HUGE_VAL})
    {
        EXPECT_TRUE
        (
            test::throwsCoreError
            (
                [&]{ rigidBody("grain", s, rho); }, {"grain", "density"}
            )
        ) << "density " << rho;
    }
    EXPECT_TRUE
    (
        test::throwsCoreError
        (
            [&]{ rigidBody("grain", nullptr, 1000); }, {"grain", "shape"}
        )
    );
}

TEST(rigidBody, motionTypeNames)
{
    for (motionType m : {motionType::free, motionType::fixed, motionType::prescribed})
    {
        EXPECT_EQ(motionTypeFromName(motionTypeName(m)), m);
    }
    EXPECT_EQ(motionTypeName(motionType::prescribed), "prescribed");
    EXPECT_TRUE
    (
        test::throwsCoreError
        (
            []{ motionTypeFromName("x"); },
            {"Unknown motion type 'x'", "(fixed free prescribed)"}
        )
    );
}


// * * * * * * * * * * * * * * * Translation * * * * * * * * * * * * * * * //

TEST(rigidBodyIntegrator, constantForceIsExact)
{
    rigidBody b("grain", sphere(0.01), 2500);
    const vec3 g(0.5, -9.81, 1.2);
    const vec3 x0(0.1, 2, -0.3);
    const vec3 v0(0.4, 1.5, -0.2);
    b.pose.setPosition(x0);
    b.velocity = v0;

    const auto gravity = [&](rigidBody& body)
    {
        body.externalForce = body.mass()*g;
    };

    const double dt = 1e-3;
    const int N = 2000;
    for (int n = 0; n < N; ++n)
    {
        step(b, dt, gravity);
    }

    const double t = N*dt;
    const vec3 x = x0 + v0*t + 0.5*g*t*t;
    const vec3 v = v0 + g*t;
    EXPECT_LT((b.pose.position() - x).norm(), 1e-12*x.norm());
    EXPECT_LT((b.velocity - v).norm(), 1e-12*v.norm());
    EXPECT_EQ(b.angularVelocity, vec3::Zero());
    EXPECT_EQ(b.pose.orientation().coeffs(), quat::Identity().coeffs());
}

namespace
{

struct oscillatorRun
{
    double maxEnergyError;      //!< relative
    double lastPeriodMaxError;  //!< relative, over the last period only
};

//- Isotropic 3D oscillator of period 1 s on an elliptic orbit
oscillatorRun runOscillator(double dt, int nPeriods)
{
    rigidBody b("grain", sphere(0.01), 2500);
    const double omega = 2*M_PI;
    const double k = b.mass()*omega*omega;
    b.pose.setPosition(vec3(0.1, 0, 0.02));
    b.velocity = vec3(0, 0.3, 0.1);

    const auto spring = [&](rigidBody& body)
    {
        body.externalForce = -k*body.pose.position();
    };
    const auto energy = [&]
    {
        return b.kineticEnergy() + 0.5*k*b.pose.position().squaredNorm();
    };

    const double E0 = energy();
    const int stepsPerPeriod = int(std::lround(1/dt));
    oscillatorRun r{0, 0};
    for (int n = 0; n < nPeriods*stepsPerPeriod; ++n)
    {
        step(b, dt, spring);
        const double e = relErr(energy(), E0);
        r.maxEnergyError = std::max(r.maxEnergyError, e);
        if (n >= (nPeriods - 1)*stepsPerPeriod)
        {
            r.lastPeriodMaxError = std::max(r.lastPeriodMaxError, e);
        }
    }
    return r;
}

} // End anonymous namespace

TEST(rigidBodyIntegrator, harmonicOscillatorEnergyIsBoundedSecondOrder)
{
    const oscillatorRun coarse = runOscillator(0.01, 100);
    const oscillatorRun fine = runOscillator(0.005, 100);
    std::printf
    (
        "    oscillator: max relative energy error %.3e (dt = T/100), "
        "%.3e (dt = T/200), ratio %.3f\n",
        coarse.maxEnergyError, fine.maxEnergyError,
        coarse.maxEnergyError/fine.maxEnergyError
    );

    // Velocity Verlet: about (omega dt)^2/8 here, and no secular growth
    // over 100 periods
    // over 100 periods (0.25 (omega dt)^2: twice the theory's; 0.9: the
    // last period's error is the largest's, not growing past it; 4 +- 0.2:
    // second order, halving dt quarters it, the rest the (omega dt)^4 term)
    const double wdt = 2*M_PI*0.01;
    EXPECT_LT(coarse.maxEnergyError, 0.25*wdt*wdt);
    EXPECT_GT(coarse.lastPeriodMaxError, 0.9*coarse.maxEnergyError);
    EXPECT_NEAR(coarse.maxEnergyError/fine.maxEnergyError, 4, 0.2);
}

TEST(rigidBodyIntegrator, harmonicOscillatorIsTimeReversible)
{
    rigidBody b("grain", sphere(0.01), 2500);
    const double k = b.mass()*4*M_PI*M_PI;
    const vec3 x0(0.1, 0, 0.02);
    const vec3 v0(0, 0.3, 0.1);
    b.pose.setPosition(x0);
    b.velocity = v0;
    const auto spring = [&](rigidBody& body)
    {
        body.externalForce = -k*body.pose.position();
    };

    // Not a whole number of periods: the turning point is far from the start
    const double dt = 0.01;
    const int N = 1234;
    for (int n = 0; n < N; ++n)
    {
        step(b, dt, spring);
    }
    EXPECT_GT((b.pose.position() - x0).norm(), 0.05);

    b.velocity = -b.velocity;
    for (int n = 0; n < N; ++n)
    {
        step(b, dt, spring);
    }
    std::printf
    (
        "    oscillator reversed after %d steps: position error %.3e, "
        "velocity error %.3e (relative)\n",
        N, (b.pose.position() - x0).norm()/x0.norm(),
        (b.velocity + v0).norm()/v0.norm()
    );
    EXPECT_LT((b.pose.position() - x0).norm(), 1e-9*x0.norm());
    EXPECT_LT((b.velocity + v0).norm(), 1e-9*v0.norm());
}

TEST(rigidBodyIntegrator, lockedTranslation)
{
    rigidBody b("grain", sphere(0.01), 2500);
    b.lockTranslation = Eigen::Vector3i(0, 0, 1);
    const vec3 x0(0.1, 0.2, 0.3);
    b.pose.setPosition(x0);
    b.velocity = vec3(0, 0, 1);     // locked component: removed by the kick
    const vec3 a(1, 2, 3);
    const auto force = [&](rigidBody& body) { body.externalForce = body.mass()*a; };

    const double dt = 1e-3;
    const int N = 500;
    for (int n = 0; n < N; ++n)
    {
        step(b, dt, force);
        ASSERT_EQ(b.velocity.z(), 0);
    }
    const double t = N*dt;
    EXPECT_EQ(b.pose.position().z(), x0.z());
    EXPECT_NEAR(b.pose.position().x(), x0.x() + 0.5*a.x()*t*t, 1e-13);
    EXPECT_NEAR(b.pose.position().y(), x0.y() + 0.5*a.y()*t*t, 1e-13);
    EXPECT_NEAR(b.velocity.x(), a.x()*t, 1e-13);
    EXPECT_NEAR(b.velocity.y(), a.y()*t, 1e-13);
}


// * * * * * * * * * * * * * * * * Rotation  * * * * * * * * * * * * * * * //

namespace
{

struct rotorRun
{
    double maxEnergyError = 0;      //!< relative
    double maxMomentumError = 0;    //!< |L - L0|/|L0|
    double maxQuatNormError = 0;
};

rotorRun runFreeRotor(rigidBody& b, double dt, int N)
{
    const double E0 = b.kineticEnergy();
    const vec3 L0 = b.angularMomentum();
    rotorRun r;
    for (int n = 0; n < N; ++n)
    {
        step(b, dt, noForce);
        r.maxEnergyError = std::max(r.maxEnergyError, relErr(b.kineticEnergy(), E0));
        r.maxMomentumError =
            std::max(r.maxMomentumError, (b.angularMomentum() - L0).norm()/L0.norm());
        r.maxQuatNormError =
            std::max(r.maxQuatNormError, std::abs(b.pose.orientation().norm() - 1));
    }
    return r;
}

} // End anonymous namespace

TEST(rigidBodyIntegrator, torqueFreeAsymmetricBodyConservesEnergyAndMomentum)
{
    // |omega| dt = 0.01 over 1e5 steps (about 160 turns)
    const double dt = 1e-3;
    const int N = 100000;
    const char* names[2] = {"max", "min"};
    const vec3 omegaBody[2] = {vec3(0.1, -0.1, 1), vec3(1, 0.1, -0.1)};

    for (int c = 0; c < 2; ++c)
    {
        rigidBody b = spinningBox(omegaBody[c], 3 + c);
        const vec3 I = b.inertia();
        ASSERT_LT(I[0], I[1]);
        ASSERT_LT(I[1], I[2]);

        const rotorRun r = runFreeRotor(b, dt, N);
        std::printf
        (
            "    free box about the %s axis, 1e5 steps: max relative energy "
            "error %.3e, max |L - L0|/|L0| %.3e, max | |q| - 1 | %.3e\n",
            names[c], r.maxEnergyError, r.maxMomentumError, r.maxQuatNormError
        );
        // 1e-3: second order at |omega| dt = 0.01 bounds the energy and
        // momentum errors to about (|omega| dt)^2 times a shape factor,
        // without drift over the 1e5 steps; 1e-12: |q| renormalised
        // every step, round-off only
        EXPECT_LT(r.maxEnergyError, 1e-3) << names[c];
        EXPECT_LT(r.maxMomentumError, 1e-3) << names[c];
        EXPECT_LT(r.maxQuatNormError, 1e-12) << names[c];

        // The body really tumbles: its spin axis precesses about L (0.9:
        // near it, as a perturbation of 0.1 keeps it)
        EXPECT_GT(b.angularVelocity.normalized().dot(b.angularMomentum().normalized()), 0.9);
    }
}

TEST(rigidBodyIntegrator, freeRotorEnergyErrorIsSecondOrder)
{
    // About the min axis with a large perturbation, over 10 s
    const vec3 omegaBody(1, 0.4, -0.3);
    rigidBody coarseBody = spinningBox(omegaBody);
    rigidBody fineBody = spinningBox(omegaBody);
    const rotorRun coarse = runFreeRotor(coarseBody, 2e-3, 5000);
    const rotorRun fine = runFreeRotor(fineBody, 1e-3, 10000);
    std::printf
    (
        "    free box energy error: %.3e (|w| dt = 0.02), %.3e (0.01), "
        "ratio %.3f\n",
        coarse.maxEnergyError, fine.maxEnergyError,
        coarse.maxEnergyError/fine.maxEnergyError
    );
    // second order: 4, +- 0.4 for the higher-order terms at |w| dt = 0.02
    EXPECT_NEAR(coarse.maxEnergyError/fine.maxEnergyError, 4, 0.4);
}

TEST(rigidBodyIntegrator, freeRotorIsTimeReversible)
{
    rigidBody b = spinningBox(vec3(1, 0.3, 0.2));
    const quat q0 = b.pose.orientation();
    const vec3 w0 = b.angularVelocity;

    // About 1.6 turns: the round-off of the way back grows about as the
    // square of the steps (1e-11 after 1000, 1e-10 after 3000)
    const double dt = 1e-3;
    const int N = 1000;
    for (int n = 0; n < N; ++n)
    {
        step(b, dt, noForce);
    }
    EXPECT_GT(rotationDistance(b.pose.orientation(), q0), 0.1);

    b.angularVelocity = -b.angularVelocity;
    for (int n = 0; n < N; ++n)
    {
        step(b, dt, noForce);
    }
    std::printf
    (
        "    free box reversed after %d steps: orientation error %.3e, "
        "omega error %.3e (relative)\n",
        N, rotationDistance(b.pose.orientation(), q0),
        (b.angularVelocity + w0).norm()/w0.norm()
    );
    EXPECT_LT(rotationDistance(b.pose.orientation(), q0), 1e-9);
    EXPECT_LT((b.angularVelocity + w0).norm(), 1e-9*w0.norm());
}

TEST(rigidBodyIntegrator, intermediateAxisFlips)
{
    // Dzhanibekov: spin about the intermediate axis, perturbed by 1e-4
    rigidBody b = spinningBox(vec3(1e-4, 1, 1e-4));
    const vec3 Lhat = b.angularMomentum().normalized();

    const double dt = 1e-3;
    const int N = 20000;
    double minComponent = 1;
    double firstFlip = -1;      // time the axis first turns against L
    double firstFull = -1;      // time it is first within 26 deg of -L
    int nFlips = 0;
    double previous = 1;
    for (int n = 1; n <= N; ++n)
    {
        step(b, dt, noForce);
        const double c = b.pose.rotation().col(1).dot(Lhat);
        minComponent = std::min(minComponent, c);
        if (firstFlip < 0 && c < 0) firstFlip = n*dt;
        if (firstFull < 0 && c < -0.9) firstFull = n*dt;
        if ((c < 0) != (previous < 0)) ++nFlips;
        previous = c;
    }

    // Linear growth rate of the perturbation, for the report
    const vec3 I = b.inertia();
    const double lambda =
        10*std::sqrt((I[1] - I[0])*(I[2] - I[1])/(I[0]*I[2]));
    std::printf
    (
        "    intermediate axis: first sign change at t = %.3f s, below -0.9 "
        "at t = %.3f s, min component %.6f, %d sign changes in %.0f s "
        "(growth rate %.3f 1/s)\n",
        firstFlip, firstFull, minComponent, nFlips, N*dt, lambda
    );
    EXPECT_LT(minComponent, -0.9);  // a full flip (to -1 less the perturbation's share)
    EXPECT_GT(firstFlip, 0);
}

TEST(rigidBodyIntegrator, extremeAxesAreStable)
{
    const double dt = 1e-3;
    const int N = 20000;
    for (int axis : {0, 2})
    {
        vec3 omegaBody = vec3::Constant(1e-4);
        omegaBody[axis] = 1;
        rigidBody b = spinningBox(omegaBody);
        const vec3 Lhat = b.angularMomentum().normalized();

        double maxAngle = 0;
        for (int n = 0; n < N; ++n)
        {
            step(b, dt, noForce);
            const double c = b.pose.rotation().col(axis).dot(Lhat);
            maxAngle = std::max(maxAngle, std::acos(std::min(c, 1.0)));
        }
        std::printf
        (
            "    spin about body axis %d: max angle to L %.3e deg\n",
            axis, maxAngle*180/M_PI
        );
        // 5 degrees: a perturbation of 1e-4 stays near the axis (a flip
        // is 180); the stable axes' wobble is of the perturbation's order
        EXPECT_LT(maxAngle, 5*M_PI/180) << "axis " << axis;
    }
}

TEST(rigidBodyIntegrator, isotropicBodyRotatesExactly)
{
    rigidBody b("grain", sphere(0.01), 2500);
    std::mt19937 gen(5);
    const quat q0 = test::randomQuat(gen);
    b.pose.setOrientation(q0);
    const vec3 w(3, -4, 12);
    b.angularVelocity = w;

    const double dt = 1e-3;
    const int N = 1000;
    for (int n = 0; n < N; ++n)
    {
        step(b, dt, noForce);
    }
    const quat expected = quat(Eigen::AngleAxisd(w.norm()*N*dt, w.normalized()))*q0;
    EXPECT_LT(rotationDistance(b.pose.orientation(), expected), 1e-10);
    EXPECT_LT((b.angularVelocity - w).norm(), 1e-12*w.norm());
}

TEST(rigidBodyIntegrator, lockedRotationTurnsAboutFreeAxisOnly)
{
    rigidBody b("box", boxShape(), 1000);
    b.lockRotation = Eigen::Vector3i(1, 1, 0);
    b.angularVelocity = vec3(1, 2, 0);  // locked components: removed by the kick
    const vec3 T(3e-5, 0, 1e-5);
    const auto torque = [&](rigidBody& body) { body.externalTorque = T; };

    // Body frame = world frame: world z is the max principal axis
    const double Izz = b.inertia()[2];
    const double dt = 1e-3;
    const int N = 1000;
    for (int n = 0; n < N; ++n)
    {
        step(b, dt, torque);
        ASSERT_EQ(b.angularVelocity.x(), 0);
        ASSERT_EQ(b.angularVelocity.y(), 0);
    }
    const double t = N*dt;
    const double alpha = T.z()/Izz;
    EXPECT_LT(relErr(b.angularVelocity.z(), alpha*t), 1e-12);

    // Constant angular acceleration about a fixed axis: Verlet is exact
    const quat expected(Eigen::AngleAxisd(0.5*alpha*t*t, vec3::UnitZ()));
    EXPECT_LT(rotationDistance(b.pose.orientation(), expected), 1e-12);
}

TEST(rigidBodyIntegrator, lockedRotationOfTiltedBodyUsesFreeAxisInertia)
{
    // Tilted about x: z is no principal axis, the world inertia couples
    // y and z. The torque about the locked x axis must not turn the body.
    rigidBody b("box", boxShape(), 1000);
    b.pose.setOrientation(quat(Eigen::AngleAxisd(0.5, vec3::UnitX())));
    b.lockRotation = Eigen::Vector3i(1, 1, 0);
    const double Izz = b.worldInertia()(2, 2);
    ASSERT_GT(std::abs(b.worldInertia()(1, 2)), 0.1*Izz);

    const vec3 T(3e-5, 2e-5, 1e-5);
    const auto torque = [&](rigidBody& body) { body.externalTorque = T; };
    const double dt = 1e-3;
    const int N = 1000;
    for (int n = 0; n < N; ++n)
    {
        step(b, dt, torque);
        ASSERT_EQ(b.angularVelocity.x(), 0);
        ASSERT_EQ(b.angularVelocity.y(), 0);
    }
    // Turning about z keeps the zz inertia
    EXPECT_LT(relErr(b.worldInertia()(2, 2), Izz), 1e-12);
    EXPECT_LT(relErr(b.angularVelocity.z(), T.z()/Izz*N*dt), 1e-12);

    // Torque-free: omega_z stays, the constraint takes the gyroscopic torque
    const double wz = b.angularVelocity.z();
    b.externalTorque.setZero();
    for (int n = 0; n < N; ++n)
    {
        step(b, dt, noForce);
    }
    EXPECT_EQ(b.angularVelocity.z(), wz);
}


// * * * * * * * * * * * * * * Fixed, prescribed * * * * * * * * * * * * * //

TEST(rigidBodyIntegrator, fixedBodyNeverMoves)
{
    rigidBody b("wall", boxShape(), 1000);
    b.motion = motionType::fixed;
    std::mt19937 gen(11);
    b.pose = bodyPose(vec3(1, 2, 3), test::randomQuat(gen));
    const bodyPose pose0 = b.pose;
    b.velocity = vec3(1, 0, 0);
    b.angularVelocity = vec3(0, 1, 0);
    b.externalForce = vec3(10, 20, 30);
    b.externalTorque = vec3(1, 2, 3);
    b.contactForce = vec3(-5, 1, 2);
    EXPECT_FALSE(b.dynamic());

    for (int n = 0; n < 100; ++n)
    {
        step(b, 1e-3, noForce);
    }
    EXPECT_EQ(b.pose.position(), pose0.position());
    EXPECT_EQ(b.pose.orientation().coeffs(), pose0.orientation().coeffs());
    EXPECT_EQ(b.velocity, vec3(1, 0, 0));
    EXPECT_EQ(b.angularVelocity, vec3(0, 1, 0));
}

TEST(rigidBodyIntegrator, prescribedBodyMovesWithItsVelocity)
{
    rigidBody b("paddle", boxShape(), 1000);
    b.motion = motionType::prescribed;
    std::mt19937 gen(13);
    const vec3 x0(0.5, -0.2, 0.1);
    const quat q0 = test::randomQuat(gen);
    b.pose = bodyPose(x0, q0);
    const vec3 v(0.1, -0.2, 0.05);
    const vec3 w(1, 2, -0.5);
    b.velocity = v;
    b.angularVelocity = w;
    b.externalForce = vec3(100, 200, 300);
    b.externalTorque = vec3(1, -2, 3);
    b.contactForce = vec3(-50, 10, 20);
    b.contactTorque = vec3(0.5, 0.5, 0.5);
    EXPECT_FALSE(b.dynamic());

    const double dt = 1e-3;
    const int N = 1000;
    for (int n = 0; n < N; ++n)
    {
        step(b, dt, noForce);
    }
    const double t = N*dt;
    EXPECT_EQ(b.velocity, v);
    EXPECT_EQ(b.angularVelocity, w);
    EXPECT_LT((b.pose.position() - (x0 + v*t)).norm(), 1e-12*x0.norm());

    const quat expected = quat(Eigen::AngleAxisd(w.norm()*t, w.normalized()))*q0;
    EXPECT_LT(rotationDistance(b.pose.orientation(), expected), 1e-10);
}
