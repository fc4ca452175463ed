// The DEM step of an advance comes from the pairs that can meet within it
// (issue 20, item 7): bodies that cannot touch anything in the step take
// one long step (free flight, bounded by the fluid's damping); a pair that
// can meet sets the step by its own contact time, not by the stiffest pair
// anywhere; and the answer is the one of the small step everywhere.

#include "demSolver.H"
#include "timeStepExplanation.H"
#include "sphereShape.H"
#include "halfSpaceShape.H"
#include "triangleMeshShape.H"
#include "primitiveMeshes.H"

#include "testHelpers.H"

#include <gtest/gtest.h>

using namespace immersedDEM;
using immersedDEM::test::material;

namespace
{
rigidBody sphere(const std::string& name, double r, const vec3& x, int mat = 0)
{
    rigidBody b(name, std::make_shared<sphereShape>(r), 2500, mat);
    b.pose = bodyPose(x, quat::Identity());
    return b;
}

rigidBody floorAt(double z, int mat = 0)
{
    rigidBody f("floor", std::make_shared<halfSpaceShape>(), 1, mat);
    f.pose = bodyPose(vec3(0, 0, z), quat::Identity());
    f.motion = motionType::fixed;
    return f;
}
}


TEST(stepFor, bodiesThatCannotMeetTakeOneStep)
{
    demSettings s;
    demSolver dem({material("glass", 6.3e10)}, s);
    dem.addBody(sphere("a", 0.005, vec3(0, 0, 0.1)));
    dem.addBody(sphere("b", 0.005, vec3(0.05, 0, 0.1)));
    dem.addBody(floorAt(0), true);
    dem.bodies()[0].velocity = vec3(0.1, 0, 0);

    // In 1 ms a reaches 0.2 mm at most: 40 mm from b, 95 mm from the floor
    const demSolver::stepChoice c = dem.stepFor(1e-3);
    EXPECT_EQ(c.deltaT, 1e-3);
    EXPECT_EQ(c.a, -1);
    EXPECT_EQ(c.pairs, 0);
    EXPECT_GT(c.deltaT, 100*dem.timeStep());
    EXPECT_EQ(dem.advance(1e-3), 1);
    EXPECT_EQ(dem.lastStep().a, -1);

    // Over 0.5 s it could reach b: b's contact time sets the step, the
    // softest-case one here
    const demSolver::stepChoice d = dem.stepFor(0.5);
    EXPECT_EQ(d.a, 0);
    EXPECT_EQ(d.b, 1);
    EXPECT_EQ(d.nameA, "a");
    EXPECT_EQ(d.nameB, "b");
    EXPECT_DOUBLE_EQ(d.deltaT, dem.timeStep());
}


TEST(stepFor, theStiffPairFarAwayDoesNotSetTheStep)
{
    demSettings s;
    demSolver dem({material("rubber", 1e6), material("steel", 2e11)}, s);
    // Two soft spheres touching, a small steel sphere far above them
    dem.addBody(sphere("soft1", 0.005, vec3(0, 0, 0.1)));
    dem.addBody(sphere("soft2", 0.005, vec3(0.0099, 0, 0.1)));
    rigidBody steel = sphere("steel", 0.001, vec3(0, 0, 0.3), 1);
    steel.density = 7800;
    dem.addBody(steel);
    const demSolver::stepChoice c = dem.stepFor(1e-3);
    EXPECT_EQ(c.a, 0);
    EXPECT_EQ(c.b, 1);
    EXPECT_EQ(c.pairs, 1);
    // The steel sphere's contact time is far shorter: the old step
    EXPECT_GT(c.deltaT, 10*dem.timeStep());

    // Brought to touch soft1, the light steel sphere sets the step (its
    // contact with rubber: still longer than the steel-on-steel one)
    dem.bodies()[2].pose = bodyPose(vec3(0, 0, 0.106), quat::Identity());
    const demSolver::stepChoice d = dem.stepFor(1e-3);
    EXPECT_EQ(d.a, 0);
    EXPECT_EQ(d.b, 2);
    EXPECT_EQ(d.pairs, 2);
    EXPECT_LT(d.deltaT, c.deltaT);
    EXPECT_GT(d.deltaT, dem.timeStep());
}


TEST(stepFor, aWallWithinTheStepsTravel)
{
    demSettings s;
    s.gravity = vec3(0, 0, -9.81);
    demSolver dem({material("glass", 6.3e10)}, s);
    // A block (a mesh: its flat face's spring) falling onto a floor
    rigidBody block("block", std::make_shared<triangleMeshShape>(primitiveMeshes::box(vec3(0.005, 0.005, 0.005)), "block"), 2500, 0);
    block.pose = bodyPose(vec3(0, 0, 0.02), quat::Identity());
    block.velocity = vec3(0, 0, -1);
    dem.addBody(block);
    dem.addBody(floorAt(0), true);
    // Its lower face is 15 mm above the floor. In 7 ms it falls 7.2 mm
    // (1 m/s and gravity), doubled 14.5 mm: it cannot touch
    EXPECT_EQ(dem.stepFor(7e-3).a, -1);
    // 8 ms: 16.6 mm
    const demSolver::stepChoice c = dem.stepFor(8e-3);
    EXPECT_EQ(c.a, 1);
    EXPECT_EQ(c.b, 0);
    // Against the floor (m, R), not a like body (m/2, R/2): the flat
    // face's spring period is twice the softest-case one
    EXPECT_NEAR(c.deltaT, 2*dem.timeStep(), 1e-9*c.deltaT);
}


TEST(stepFor, aTurningWallMovesAtItsSpeedNearTheBody)
{
    demSettings s;
    demSolver dem({material("glass", 6.3e10)}, s);
    dem.addBody(sphere("a", 0.005, vec3(0, 0, 0.02)));
    // A floor turning at 1 rad/s about an axis 1 m away: under the sphere
    // it rises at about 1 m/s, 15 mm below the sphere's surface
    rigidBody floor = floorAt(0);
    floor.pose = bodyPose(vec3(1, 0, 0), quat::Identity());
    floor.motion = motionType::prescribed;
    floor.angularVelocity = vec3(0, -1, 0);
    dem.addBody(floor, true);
    // 5 ms: 5.1 mm, doubled 10.2 mm; 10 ms: 20.4 mm
    EXPECT_EQ(dem.stepFor(5e-3).a, -1);
    EXPECT_EQ(dem.stepFor(1e-2).a, 1);
    // Standing still it cannot meet the sphere in 10 ms
    dem.bodies()[1].angularVelocity = vec3::Zero();
    EXPECT_EQ(dem.stepFor(1e-2).a, -1);
}


TEST(stepFor, theFluidsDampingBoundsTheFreeFlight)
{
    demSettings s;
    demSolver dem({material("glass", 6.3e10)}, s);
    dem.addBody(sphere("a", 0.005, vec3(0, 0, 0.1)));
    rigidBody& b = dem.bodies()[0];
    // A strong damper (m/c = 5e-5 s, a twentieth of the CFD step) and an
    // added mass of half the body's: the free flight takes a tenth of the
    // relaxation time (m + m_a)/c
    b.fluid.damping = b.mass()/5e-5;
    b.fluid.addedMass = 0.5*b.mass();
    const demSolver::stepChoice c = dem.stepFor(1e-3);
    const double tau = (b.mass() + b.fluid.addedMass)/b.fluid.damping;
    EXPECT_EQ(c.a, -1);
    EXPECT_NEAR(c.deltaT, 0.1*tau, 1e-15);

    // The damped relaxation towards the reference velocity over one CFD
    // step follows the exact exponential: within 5% of the velocity
    // change at every CFD step (implicit kicks of a twentieth of the
    // relaxation time each: an error of a few per cent of the change)
    b.fluid.referenceVelocity = vec3(0, 0, -0.1);
    for (int k = 1; k <= 3; ++k)
    {
        dem.advance(0.2*tau);
        const double exact = -0.1*(1 - std::exp(-0.2*k));
        EXPECT_NEAR(b.velocity.z(), exact, 0.05*std::abs(exact)) << k;
    }
    // and ends on the reference velocity, however long the CFD step (13
    // relaxation times here: implicit kicks lag the exponential, e^-13 is
    // 2e-6 of the change; 1e-5 of it allowed)
    dem.advance(1e-3);
    EXPECT_NEAR(b.velocity.z(), -0.1, 1e-6);
}


TEST(stepFor, aBounceAdvancedInLongChunksIsTheBounceOfTheSmallStep)
{
    // A glass sphere dropped on a glass floor, advanced in 1 ms chunks: the
    // chunks far from the floor take one step each, those near it the
    // contact's step. Against the same drop with the softest-case step
    // everywhere (the user's deltaT): the same rebound
    auto drop = [](bool chunks, int& steps)
    {
        demSettings s;
        s.gravity = vec3(0, 0, -9.81);
        demSolver probe({material("glass", 6.3e10)}, s);
        probe.addBody(sphere("ball", 0.005, vec3(0, 0, 0.05)));
        probe.addBody(floorAt(0), true);
        probe.bodies()[0].velocity = vec3(0, 0, -1);
        if (!chunks) s.deltaT = probe.timeStep();
        demSolver dem({material("glass", 6.3e10)}, s);
        dem.addBody(sphere("ball", 0.005, vec3(0, 0, 0.05)));
        dem.addBody(floorAt(0), true);
        dem.bodies()[0].velocity = vec3(0, 0, -1);
        steps = 0;
        double vMin = 0, vUp = 0;
        for (int k = 0; k < 80; ++k)
        {
            steps += dem.advance(1e-3);
            vMin = std::min(vMin, dem.bodies()[0].velocity.z());
            if (dem.bodies()[0].pose.position().z() > 0.02)
            {
                vUp = std::max(vUp, dem.bodies()[0].velocity.z());
            }
        }
        EXPECT_LT(vMin, -1.0);
        return std::make_pair(dem.bodies()[0].pose.position().z(), vUp);
    };
    int nChunks = 0, nSmall = 0;
    const auto a = drop(true, nChunks);
    const auto b = drop(false, nSmall);
    EXPECT_GT(a.second, 0.5) << "it bounced";
    // The two contacts' steps differ (the speed they are estimated at):
    // the rebounds differ by their discretisation errors
    EXPECT_NEAR(a.second, b.second, 3e-3*b.second);
    EXPECT_NEAR(a.first, b.first, 1e-4);
    EXPECT_LT(nChunks, nSmall/5) << nChunks << " steps against " << nSmall;
}


TEST(stepFor, theLogLineNamesThePairAfterBodiesWereRemoved)
{
    // Streams remove bodies after the advance, before the log line: the
    // pair is named as it was chosen (no stale index)
    demSettings s;
    demSolver dem({material("glass", 6.3e10)}, s);
    dem.addBody(sphere("a", 0.005, vec3(0, 0, 0.1)));
    dem.addBody(sphere("b", 0.005, vec3(0.0099, 0, 0.1)));
    dem.advance(1e-4);
    EXPECT_EQ(dem.lastStep().a, 0);
    dem.removeBodies({0, 1});
    const std::string line = timeStepExplanation::lastStep(dem);
    EXPECT_NE(line.find("(a against b, 1 pair can meet)"), std::string::npos) << line;
}
