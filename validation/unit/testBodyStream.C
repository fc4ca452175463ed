// Insertion over time (bodyStream): the schedule (bodies due by t, with
// start, end, number and volume-fraction limits), placement free of
// overlap with what is present, reproducibility (also when the stream is
// rebuilt from its state, as at a restart), bodies waiting when the region
// is blocked; removal (bodyRemoval, demSolver::removeBodies) keeps the
// other bodies and their contact histories.

#include "bodyStream.H"
#include "bodyRemoval.H"
#include "bodySeparation.H"
#include "sphereShape.H"
#include "halfSpaceShape.H"
#include "coreError.H"

#include "testHelpers.H"

#include "demOutput.H"

#include <filesystem>
#include <fstream>
#include <map>

#include <gtest/gtest.h>

#include <cmath>

using namespace immersedDEM;

namespace
{

demSolver emptyDem(const vec3& g = vec3::Zero())
{
    demSettings s;
    s.gravity = g;
    return demSolver({test::glass()}, s);
}

bodyTemplate ball(double R)
{
    bodyTemplate t;
    t.name = "ball";
    t.geometry = std::make_shared<sphereShape>(R);
    t.density = 2500;
    t.size = sizeDistribution::uniform(0.8, 1.2);
    t.velocity = vec3(0, 0, -0.1);
    t.velocitySpread = vec3(0.01, 0.01, 0);
    return t;
}

streamSettings feed(double rate)
{
    streamSettings s;
    s.name = "feed";
    s.region = insertionRegion::box(vec3(0, 0, 0), vec3(0.1, 0.1, 0.1));
    s.rate = rate;
    s.seed = 7;
    return s;
}

// No two bodies of the DEM overlap (spheres: analytic)
void expectApart(const demSolver& dem)
{
    const auto& b = dem.bodies();
    for (size_t i = 0; i < b.size(); ++i)
        for (size_t j = i + 1; j < b.size(); ++j)
        {
            const posedBody A(*b[i].geometry, b[i].pose), B(*b[j].geometry, b[j].pose);
            EXPECT_TRUE(bodySeparation::apart(A, B, 0)) << b[i].name << " " << b[j].name;
        }
}

} // End anonymous namespace


TEST(BodyStream, ScheduleCountsByTime)
{
    streamSettings s = feed(50);
    s.start = 0.1;
    s.end = 0.5;
    bodyStream st(ball(0.002), s);
    EXPECT_EQ(st.due(0.0), 0);
    EXPECT_EQ(st.due(0.0999), 0);
    EXPECT_EQ(st.due(0.1), 1);          // body 0 at start
    EXPECT_EQ(st.due(0.3), 11);         // 0.1 + k/50 <= 0.3: k = 0..10
    EXPECT_EQ(st.due(0.1 + 0.2), 11);   // round-off of the time absorbed
    EXPECT_EQ(st.due(0.5), 21);
    EXPECT_EQ(st.due(10.0), 21);        // nothing due after end
    s.number = 5;
    EXPECT_EQ(bodyStream(ball(0.002), s).due(10.0), 5);

    // Inserted at the output times 0, 0.01, ...: the count by t is due(t)
    demSolver dem = emptyDem();
    bodyStream a(ball(0.002), feed(250));
    for (int k = 0; k <= 20; ++k)
    {
        const double t = 0.01*k;
        const streamStepReport r = a.insert(dem, t);
        EXPECT_EQ(r.waiting, 0);
        EXPECT_EQ(long(dem.bodies().size()), std::lround(std::floor(250*t + 1e-6)) + 1) << t;
    }
    EXPECT_EQ(dem.bodies().size(), 51u);
    EXPECT_EQ(dem.bodies().back().name, "feed_50");
    expectApart(dem);
    for (const rigidBody& b : dem.bodies())
    {
        // Wholly inside the box, velocity from the template's spread
        const double R = b.geometry->boundingRadius();
        EXPECT_GE((b.pose.position().array() - R).minCoeff(), 0);
        EXPECT_LE((b.pose.position().array() + R).maxCoeff(), 0.1);
        EXPECT_NEAR(b.velocity.z(), -0.1, 1e-15);
        EXPECT_LE(std::abs(b.velocity.x()), 0.01);
        EXPECT_GE(R, 0.8*0.002 - 1e-15);
        EXPECT_LE(R, 1.2*0.002 + 1e-15);
    }
}


TEST(BodyStream, ReproducibleAndRestartable)
{
    // Uninterrupted: inserting at 0, 0.02, ..., 0.2 with the bodies moving
    // between insertions (a drift standing in for the DEM)
    auto run = [](bodyStream& st, demSolver& dem, int from, int to)
    {
        for (int k = from; k <= to; ++k)
        {
            for (rigidBody& b : dem.bodies())
            {
                b.pose = bodyPose(b.pose.position() + 0.02*b.velocity, b.pose.orientation());
            }
            st.insert(dem, 0.02*k);
        }
    };
    demSolver full = emptyDem();
    bodyStream a(ball(0.004), feed(200));
    run(a, full, 0, 10);

    // The same, stopped at 0.1 and continued by a new stream that knows
    // only the state, with the bodies rebuilt from body(n) and their poses
    demSolver first = emptyDem();
    bodyStream b(ball(0.004), feed(200));
    run(b, first, 0, 5);
    const streamState saved = b.state();
    demSolver second = emptyDem();
    bodyStream c(ball(0.004), feed(200));
    c.setState(saved);
    for (long n = 0; n < saved.placed; ++n)
    {
        rigidBody r = c.body(n);
        r.pose = first.bodies()[n].pose;
        r.velocity = first.bodies()[n].velocity;
        second.addBody(std::move(r));
    }
    run(c, second, 6, 10);

    ASSERT_EQ(full.bodies().size(), second.bodies().size());
    EXPECT_EQ(a.state().placed, c.state().placed);
    EXPECT_EQ(a.state().attempts, c.state().attempts);
    for (size_t i = 0; i < full.bodies().size(); ++i)
    {
        const rigidBody& x = full.bodies()[i];
        const rigidBody& y = second.bodies()[i];
        EXPECT_EQ(x.name, y.name);
        EXPECT_EQ(x.pose.position(), y.pose.position()) << x.name;
        EXPECT_EQ(x.velocity, y.velocity) << x.name;
        EXPECT_EQ(x.geometry->volume(), y.geometry->volume()) << x.name;
    }
    expectApart(full);

    // Another seed, other bodies
    demSolver other = emptyDem();
    streamSettings s = feed(200);
    s.seed = 8;
    bodyStream d(ball(0.004), s);
    run(d, other, 0, 10);
    EXPECT_NE(other.bodies()[0].pose.position(), full.bodies()[0].pose.position());
}


TEST(BodyStream, BlockedRegionWaitsThenContinues)
{
    // A box with room for one sphere: the second waits until the first
    // has been moved away, then goes in
    demSolver dem = emptyDem();
    streamSettings s = feed(100);
    // Centres within a cube of side 5 mm: two spheres of 5 mm radius
    // never fit (its diagonal is 8.7 mm)
    s.region = insertionRegion::box(vec3(0, 0, 0), vec3(0.015, 0.015, 0.015));
    s.maxAttempts = 200;
    bodyTemplate t = ball(0.005);
    t.size = sizeDistribution();
    bodyStream st(t, s);
    streamStepReport r = st.insert(dem, 0.0);
    EXPECT_EQ(r.placed, 1);
    r = st.insert(dem, 0.02);           // bodies 1 and 2 due
    EXPECT_EQ(r.placed, 0);
    EXPECT_EQ(r.waiting, 2);
    EXPECT_EQ(r.attempts, 200);
    EXPECT_NE(r.summary().find("2 WAITING"), std::string::npos) << r.summary();
    dem.bodies()[0].pose = bodyPose(vec3(1, 1, 1), quat::Identity());
    r = st.insert(dem, 0.03);           // 1 placed, then 2 and 3 wait
    EXPECT_EQ(r.placed, 1);
    EXPECT_EQ(r.waiting, 2);
    EXPECT_EQ(dem.bodies().back().name, "feed_1");
    expectApart(dem);
}


TEST(BodyStream, VolumeFractionEndsTheStream)
{
    demSolver dem = emptyDem();
    streamSettings s = feed(1000);
    s.volumeFraction = 0.05;
    bodyTemplate t = ball(0.005);
    t.size = sizeDistribution();
    bodyStream st(t, s);
    const double V = 4.0/3*M_PI*std::pow(0.005, 3);
    // 0.05 of 1e-3 m3 is 95.5 spheres of 5.24e-7 m3: 95 (the nearer count)
    st.insert(dem, 0.05);
    EXPECT_EQ(dem.bodies().size(), 51u);
    const streamStepReport r = st.insert(dem, 1.0);
    EXPECT_TRUE(r.finishedNow);
    EXPECT_EQ(r.waiting, 0);
    EXPECT_EQ(dem.bodies().size(), 95u);
    EXPECT_NEAR(st.state().placedVolume, 95*V, 1e-15);
    EXPECT_EQ(st.insert(dem, 2.0).placed, 0);
    expectApart(dem);
}


TEST(BodyStream, BadSettingsThrow)
{
    streamSettings s = feed(0);
    EXPECT_THROW(bodyStream x(ball(0.002), s), coreError);
    s = feed(10);
    s.end = s.start;
    EXPECT_THROW(bodyStream x(ball(0.002), s), coreError);
    s = feed(10);
    s.volumeFraction = 1;
    EXPECT_THROW(bodyStream x(ball(0.002), s), coreError);
}


TEST(BodyRemoval, OutletRemovesBodiesAndTheirContacts)
{
    // A column of three touching spheres on a floor; the lowest is in an
    // outlet box: it goes, with its contacts; the others keep theirs
    demSolver dem = emptyDem(vec3(0, 0, -9.81));
    rigidBody floor("floor", std::make_shared<halfSpaceShape>(), 1);
    floor.pose = halfSpaceShape::poseOf(vec3::Zero(), vec3::UnitZ());
    floor.motion = motionType::fixed;
    dem.addBody(floor, true);
    for (int i = 0; i < 3; ++i)
    {
        rigidBody b("s" + std::to_string(i), std::make_shared<sphereShape>(0.01), 2500, 0);
        b.pose = bodyPose(vec3(0, 0, 0.0099 + 0.0199*i), quat::Identity());
        dem.addBody(std::move(b));
    }
    dem.advance(1e-6);
    ASSERT_EQ(dem.histories().count({2, 3}), 1u);
    const auto kept12 = dem.histories().at({2, 3});

    const std::vector<insertionRegion> outlets
    {
        insertionRegion::box(vec3(-1, -1, -1), vec3(1, 1, 0.005)),
        insertionRegion::box(vec3(-1, -1, 0.009), vec3(1, 1, 0.0101))
    };
    const std::vector<int> gone = bodyRemoval::bodiesIn(dem, outlets);
    ASSERT_EQ(gone, std::vector<int>({1}));     // the floor is a wall: never
    const std::vector<int> kept = dem.removeBodies(gone);
    EXPECT_EQ(kept, std::vector<int>({0, 2, 3}));
    ASSERT_EQ(dem.bodies().size(), 3u);
    EXPECT_EQ(dem.bodies()[1].name, "s1");
    EXPECT_EQ(dem.bodies()[2].name, "s2");
    EXPECT_EQ(dem.histories().count({0, 1}), 0u);   // floor-s0 gone with s0
    ASSERT_EQ(dem.histories().count({1, 2}), 1u);   // s1-s2 renumbered
    EXPECT_EQ(dem.histories().at({1, 2}).size(), kept12.size());
    EXPECT_EQ(dem.histories().at({1, 2})[0].tangentialSpring, kept12[0].tangentialSpring);
    for (const contactRecord& c : dem.contacts())
    {
        EXPECT_LT(c.b, 3);
        EXPECT_NE(dem.bodies()[c.a].name, "s0");
    }
    // The run goes on with the renumbered bodies
    EXPECT_NO_THROW(dem.advance(1e-5));
    for (const contactRecord& c : dem.contacts())
    {
        EXPECT_LT(c.a, 3);
        EXPECT_LT(c.b, 3);
    }
    // Each keeps its identity (the output's body number): the order it
    // was added in, the floor first
    EXPECT_EQ(dem.identity(1), 2u);
    EXPECT_EQ(dem.identity(2), 3u);
    EXPECT_EQ(dem.nextIdentity(), 4u);
    // Nothing to remove: nothing changes
    EXPECT_EQ(dem.removeBodies({}), std::vector<int>({0, 1, 2}));
    EXPECT_EQ(dem.bodies()[2].name, "s2");
    EXPECT_THROW(dem.removeBodies({0}), coreError);
    EXPECT_THROW(dem.removeBodies({7}), coreError);

    // A restart gives them back the identities of the run it continues,
    // and the VTK output numbers each body by it
    rigidBody late("s9", std::make_shared<sphereShape>(0.01), 2500, 0);
    late.pose = bodyPose(vec3(0.05, 0, 0.0099), quat::Identity());
    dem.addBody(std::move(late));
    EXPECT_EQ(dem.identity(3), 4u);
    dem.restoreIdentities({0, 2, 3, 9}, 10);
    EXPECT_EQ(dem.identity(3), 9u);
    EXPECT_EQ(dem.nextIdentity(), 10u);
    EXPECT_THROW(dem.restoreIdentities({0, 2, 3}, 10), coreError);       // one short
    EXPECT_THROW(dem.restoreIdentities({0, 2, 2, 9}, 10), coreError);    // twice
    EXPECT_THROW(dem.restoreIdentities({0, 2, 3, 9}, 9), coreError);     // not below next
    EXPECT_EQ(dem.identity(3), 9u);     // a refused call changes nothing
    const std::string dir = ::testing::TempDir() + "/bodyNumbers";
    std::filesystem::remove_all(dir);
    demOutput out(dir, "0");
    out.writeVTK(0.5, dem);
    std::ifstream vtk(dir + "/VTK/bodies_0.5.vtk");
    ASSERT_TRUE(vtk.good());
    std::string line;
    while (std::getline(vtk, line) && line != "LOOKUP_TABLE default") {}
    std::map<int, int> facesOf;
    for (int b; vtk >> b;) ++facesOf[b];
    // The three spheres' faces under 2, 3 and 9 (the floor is not drawn)
    ASSERT_EQ(facesOf.size(), 3u);
    EXPECT_EQ(facesOf.begin()->first, 2);
    EXPECT_EQ(facesOf.rbegin()->first, 9);
}
