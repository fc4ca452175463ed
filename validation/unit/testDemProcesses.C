/*---------------------------------------------------------------------------*\
Description
    The DEM's pair evaluations shared out among processes
    (demSolver::setCommunicator): the processes are threads here, each with
    its own replicated demSolver, exchanging through a shared-memory
    allGather. A pile of faceted bodies and spheres in a tank of wall
    patches, in a liquid (lubrication on), contact reuse on, a body removed
    on the way, and the same with Raschig rings of convex pieces (exact
    contacts and films): every process's trajectories and contact
    histories are the serial run's, bit for bit, and the pairs are shared
    out. A pour of
    spheres on plane walls: the sphere sweep gives the general loop's
    results bit for bit, alone and shared.
\*---------------------------------------------------------------------------*/

#include "demSolver.H"
#include "demCommunicator.H"
#include "sphereShape.H"
#include "halfSpaceShape.H"
#include "triangleMeshShape.H"
#include "wallMeshShape.H"
#include "primitiveMeshes.H"
#include "testHelpers.H"

#include <gtest/gtest.h>

#include <condition_variable>
#include <memory>
#include <mutex>
#include <random>
#include <thread>

using namespace immersedDEM;

namespace
{

//- The buffers of n threads, exchanged at a barrier
class sharedBoard
{
    std::mutex mutex_;
    std::condition_variable cv_;
    const int n_;
    int arrived_ = 0;
    int left_ = 0;
    long round_ = 0;
    std::vector<std::vector<double>> buffers_;
    std::vector<std::vector<double>> result_;

public:

    explicit sharedBoard(int n) : n_(n), buffers_(n) {}

    std::vector<std::vector<double>> exchange(int rank, const std::vector<double>& mine)
    {
        std::unique_lock<std::mutex> lock(mutex_);
        // The last round's readers must all have left
        cv_.wait(lock, [this] { return left_ == 0; });
        buffers_[rank] = mine;
        const long round = round_;
        if (++arrived_ == n_)
        {
            result_ = buffers_;
            arrived_ = 0;
            left_ = n_;
            ++round_;
            cv_.notify_all();
        }
        else
        {
            cv_.wait(lock, [this, round] { return round_ != round; });
        }
        std::vector<std::vector<double>> all = result_;
        if (--left_ == 0)
        {
            cv_.notify_all();
        }
        return all;
    }
};


class threadCommunicator
:
    public demCommunicator
{
    sharedBoard& board_;
    const int rank_, size_;

public:

    threadCommunicator(sharedBoard& board, int rank, int size)
    :
        board_(board), rank_(rank), size_(size)
    {}

    int rank() const override { return rank_; }
    int size() const override { return size_; }

    std::vector<std::vector<double>> allGather(const std::vector<double>& mine) override
    {
        return board_.exchange(rank_, mine);
    }
};


//- What a run leaves: every body's state after each advance, flat, and
//  the contact histories at the end; the work done
struct runResult
{
    std::vector<double> states;
    std::vector<double> histories;
    long contacts = 0;
    long pairEvaluations = 0;
    long reusedEvaluations = 0;
    long lubricatedPairs = 0;
};


//- Body b at p moved by up to +-jitter per axis, turned at random, with
//  velocities up to v and w per axis (drawn in this order from gen)
void placeAtRandom
(
    rigidBody& b, const vec3& p, double jitter, double v, double w, std::mt19937& gen
)
{
    const vec3 x = p + test::randomVec(gen, -jitter, jitter);
    b.pose = bodyPose(x, test::randomQuat(gen));
    b.velocity = test::randomVec(gen, -v, v);
    b.angularVelocity = test::randomVec(gen, -w, w);
}


//- Every body's state, flat: pose, velocities, contact force and torque,
//  film force
void appendStates(const demSolver& dem, std::vector<double>& out)
{
    for (const rigidBody& b : dem.bodies())
    {
        const vec3 x = b.pose.position();
        const quat& q = b.pose.orientation();
        out.insert
        (
            out.end(),
            {
                x.x(), x.y(), x.z(), q.w(), q.x(), q.y(), q.z(),
                b.velocity.x(), b.velocity.y(), b.velocity.z(),
                b.angularVelocity.x(), b.angularVelocity.y(), b.angularVelocity.z(),
                b.contactForce.x(), b.contactForce.y(), b.contactForce.z(),
                b.contactTorque.x(), b.contactTorque.y(), b.contactTorque.z(),
                b.lubricationForce.x(), b.lubricationForce.y(), b.lubricationForce.z()
            }
        );
    }
}


//- Every contact history, flat, with its pair
void appendHistories(const demSolver& dem, std::vector<double>& out)
{
    for (const auto& h : dem.histories())
    {
        out.insert(out.end(), {double(h.first.first), double(h.first.second)});
        for (const contactHistory& c : h.second)
        {
            out.insert
            (
                out.end(),
                {
                    c.tangentialSpring.x(), c.tangentialSpring.y(), c.tangentialSpring.z(),
                    c.point.x(), c.normal.z(), c.approach, c.maxNormalForce,
                    c.rolling.x(), c.rolling.y(), c.rolling.z()
                }
            );
        }
    }
}


//- n advances of dt, body 'gone' removed before the middle one; the
//  states (and the contact records, if asked) after each, the histories
//  at the end
void advanceAndRecord
(
    demSolver& dem, int n, double dt, int gone, bool records, runResult& r
)
{
    for (int a = 0; a < n; ++a)
    {
        if (a == n/2)
        {
            dem.removeBodies({gone});
        }
        dem.advance(dt);
        appendStates(dem, r.states);
        for (const contactRecord& c : dem.contacts())
        {
            if (!records) break;
            r.states.insert
            (
                r.states.end(),
                {
                    double(c.a), double(c.b), c.region.volume, c.region.point.x(),
                    c.region.normal.y(), c.force.normalForce, c.force.tangentialForce.z()
                }
            );
        }
        r.contacts += long(dem.contacts().size());
    }
    appendHistories(dem, r.histories);
}


//- Twelve bodies (non-convex tori, icosahedra measured on the octree,
//  spheres; or twelve Raschig rings of convex pieces, measured exactly)
//  dropped in a tank of wall patches, in a liquid; body 5 removed half way
runResult runPile(std::shared_ptr<demCommunicator> comm, bool rings = false)
{
    demSettings s;
    s.gravity = vec3(0, 0, -9.81);
    s.overlap = overlapSettings{0.001, 1};
    s.overlap.convexExact = rings;
    s.reuseContacts = true;
    // (rolling friction: its springs are exchanged with the histories)
    contactMaterial soft = test::material("soft", 1e6);
    soft.rollingFriction = 0.02;
    demSolver dem({soft}, s);
    dem.setCommunicator(comm);
    dem.setFluidViscosity(1e-3);

    rigidBody tank
    (
        "tank",
        std::make_shared<wallMeshShape>
        (
            primitiveMeshes::openBox(vec3(0, 0, 0), vec3(0.04, 0.04, 0.06), 4), "tank", 0.01
        ),
        1
    );
    tank.motion = motionType::fixed;
    dem.addBody(tank, true);

    // (rings: Raschig rings of convex pieces, contacts and films exact)
    const auto nonConvex = rings
      ? std::make_shared<triangleMeshShape>
        (
            primitiveMeshes::hollowCylinder(0.004, 0.002, 0.006, 24), "ring"
        )
      : std::make_shared<triangleMeshShape>
        (
            primitiveMeshes::torus(0.004, 0.0015, 16, 8), "torus"
        );
    const auto ico = std::make_shared<triangleMeshShape>
    (
        primitiveMeshes::icosphere(0.004, 0), "icosahedron"
    );
    const auto ball = std::make_shared<sphereShape>(0.004);
    std::mt19937 gen(7);
    for (int k = 0; k < 12; ++k)
    {
        const std::shared_ptr<const shape> g =
            rings || k % 3 == 0 ? std::shared_ptr<const shape>(nonConvex)
          : k % 3 == 1 ? std::shared_ptr<const shape>(ico)
          : std::shared_ptr<const shape>(ball);
        rigidBody b("b" + std::to_string(k), g, 2500);
        const int i = k % 2, j = (k/2) % 2, l = k/4;
        placeAtRandom
        (
            b, vec3(0.011 + 0.018*i, 0.011 + 0.018*j, 0.006 + 0.0085*l), 0.0005, 0.05, 5, gen
        );
        b.fluidCellSize = 0.002;
        dem.addBody(b);
    }

    runResult r;
    advanceAndRecord(dem, 10, 0.002, 5, false, r);
    r.pairEvaluations = dem.work().pairEvaluations;
    r.reusedEvaluations = dem.work().reusedEvaluations;
    r.lubricatedPairs = dem.work().lubricatedPairs;
    return r;
}


//- The pile run on n threads sharing the pairs
std::vector<runResult> runOn(int n, bool rings = false)
{
    sharedBoard board(n);
    std::vector<runResult> results(n);
    std::vector<std::thread> threads;
    for (int rank = 0; rank < n; ++rank)
    {
        threads.emplace_back
        (
            [&, rank]
            {
                results[rank] = runPile(std::make_shared<threadCommunicator>(board, rank, n), rings);
            }
        );
    }
    for (std::thread& t : threads) t.join();
    return results;
}

} // End anonymous namespace


TEST(demProcesses, pairOwnersAreSpreadAndFixed)
{
    // Every pair of 40 identities has one owner among 3, the same each
    // time; each process owns about a third
    int count[3] = {0, 0, 0};
    for (std::uint64_t a = 0; a < 40; ++a)
    {
        for (std::uint64_t b = a + 1; b < 40; ++b)
        {
            const int o = demCommunicator::owner(a, b, 3);
            ASSERT_GE(o, 0);
            ASSERT_LT(o, 3);
            EXPECT_EQ(o, demCommunicator::owner(a, b, 3));
            ++count[o];
        }
    }
    for (const int c : count)
    {
        // 15%: a hash's spread over 780 pairs (one standard deviation of
        // a third's count is 13, 5%): even, not one process with most
        EXPECT_GT(c, 780/3*0.85);
        EXPECT_LT(c, 780/3*1.15);
    }
    EXPECT_EQ(demCommunicator::owner(3, 9, 1), 0);
}


void expectSharedPairsGiveTheSerialRun(bool rings)
{
    const runResult serial = runPile(nullptr, rings);
    // The run must have contacts, carried contacts and films to share
    ASSERT_GT(serial.contacts, 10);
    ASSERT_GT(serial.reusedEvaluations, 0);
    ASSERT_GT(serial.lubricatedPairs, 0);
    ASSERT_FALSE(serial.histories.empty());
    std::cout << "serial: " << serial.contacts << " contact rows, "
        << serial.pairEvaluations << " pair evaluations, "
        << serial.reusedEvaluations << " carried, "
        << serial.lubricatedPairs << " films" << std::endl;

    for (const int n : {2, 3})
    {
        const std::vector<runResult> ranks = runOn(n, rings);
        long evaluations = 0, carried = 0, films = 0;
        for (int rank = 0; rank < n; ++rank)
        {
            const runResult& r = ranks[rank];
            // == on doubles: the same bits
            ASSERT_EQ(r.states.size(), serial.states.size());
            for (size_t k = 0; k < r.states.size(); ++k)
            {
                ASSERT_EQ(r.states[k], serial.states[k])
                    << n << " processes, rank " << rank << ", state value " << k;
            }
            ASSERT_EQ(r.histories, serial.histories) << n << " processes, rank " << rank;
            EXPECT_EQ(r.contacts, serial.contacts);
            // The work is shared: no process does all of it
            EXPECT_LT(r.pairEvaluations, serial.pairEvaluations) << n << " processes, rank " << rank;
            evaluations += r.pairEvaluations;
            carried += r.reusedEvaluations;
            films += r.lubricatedPairs;
            std::cout << n << " processes, rank " << rank << ": "
                << r.pairEvaluations << " pair evaluations, "
                << r.reusedEvaluations << " carried, " << r.lubricatedPairs << " films" << std::endl;
        }
        // Each pair evaluated once, by its owner, as the serial run did
        EXPECT_EQ(evaluations, serial.pairEvaluations);
        EXPECT_EQ(carried, serial.reusedEvaluations);
        EXPECT_EQ(films, serial.lubricatedPairs);
    }
}


TEST(demProcesses, sharedPairsGiveTheSerialTrajectoriesBitForBit)
{
    expectSharedPairsGiveTheSerialRun(false);
}


TEST(demProcesses, sharedPairsOfRingsOfConvexPiecesGiveTheSerialTrajectoriesBitForBit)
{
    expectSharedPairsGiveTheSerialRun(true);
}


namespace
{

//- A pour of spheres of two sizes and two materials into a box of plane
//  walls (one tilted), one fixed sphere in the way, with the Hertz law and
//  the analytic engine; body 9 removed half way. sweep: the sphere sweep
//  or the general loop
runResult runSpherePour(bool sweep, std::shared_ptr<demCommunicator> comm)
{
    demSettings s;
    s.gravity = vec3(0, 0, -9.81);
    s.contactLaw = "hertzMindlin";
    s.overlapMethod = "sphere";
    s.sphereSweep = sweep;
    contactMaterial glass = test::material("glass", 1e7);
    glass.friction = 0.5;
    glass.restitution = 0.3;
    contactMaterial steel = test::material("steel", 2e7);
    steel.restitution = 0.2;
    steel.friction = 0.3;
    glass.rollingFriction = 0.02;
    steel.rollingFriction = 0.01;
    demSolver dem({glass, steel}, s);
    dem.setCommunicator(comm);

    const double L = 0.03;
    const std::vector<std::pair<vec3, vec3>> planes
    {
        {vec3(0, 0, 0), vec3(0, 0.2, 1).normalized()},
        {vec3(0, 0, 0), vec3(1, 0, 0)},
        {vec3(L, 0, 0), vec3(-1, 0, 0)},
        {vec3(0, 0, 0), vec3(0, 1, 0)},
        {vec3(0, L, 0), vec3(0, -1, 0)}
    };
    for (size_t k = 0; k < planes.size(); ++k)
    {
        rigidBody w("wall" + std::to_string(k), std::make_shared<halfSpaceShape>(), 1, int(k % 2));
        w.pose = halfSpaceShape::poseOf(planes[k].first, planes[k].second);
        w.motion = motionType::fixed;
        dem.addBody(w, true);
    }
    rigidBody post("post", std::make_shared<sphereShape>(0.004), 2500, 1);
    post.pose = bodyPose(vec3(0.5*L, 0.5*L, 0.008), quat::Identity());
    post.motion = motionType::fixed;
    dem.addBody(post);

    const auto small = std::make_shared<sphereShape>(0.0018);
    const auto large = std::make_shared<sphereShape>(0.0025);
    std::mt19937 gen(11);
    for (int k = 0; k < 40; ++k)
    {
        rigidBody b("s" + std::to_string(k), k % 3 ? small : large, 2500, k % 2);
        const int i = k % 5, j = (k/5) % 4, l = k/20;
        placeAtRandom
        (
            b, vec3(0.004 + 0.0055*i, 0.005 + 0.0065*j, 0.018 + 0.006*l), 0.0004, 0.1, 20, gen
        );
        dem.addBody(b);
    }

    runResult r;
    advanceAndRecord(dem, 12, 0.015, 9, true, r);
    r.pairEvaluations = dem.work().sphereSweeps;
    return r;
}

} // End anonymous namespace


TEST(demProcesses, sphereSweepIsTheGeneralLoopBitForBit)
{
    // The general loop (pair filter, engine, pairContacts::apply) against the
    // sphere sweep, alone and with the pairs shared by 2 processes: the
    // same states, contact records and histories, bit for bit
    const runResult general = runSpherePour(false, nullptr);
    ASSERT_EQ(general.pairEvaluations, 0);      // no sweep taken
    ASSERT_GT(general.contacts, 200);
    ASSERT_FALSE(general.histories.empty());

    const runResult sweep = runSpherePour(true, nullptr);
    ASSERT_GT(sweep.pairEvaluations, 1000);     // every evaluation a sweep
    ASSERT_EQ(sweep.states.size(), general.states.size());
    for (size_t k = 0; k < sweep.states.size(); ++k)
    {
        ASSERT_EQ(sweep.states[k], general.states[k]) << "value " << k;
    }
    ASSERT_EQ(sweep.histories, general.histories);
    EXPECT_EQ(sweep.contacts, general.contacts);

    sharedBoard board(2);
    std::vector<runResult> ranks(2);
    std::vector<std::thread> threads;
    for (int rank = 0; rank < 2; ++rank)
    {
        threads.emplace_back
        (
            [&, rank]
            {
                ranks[rank] =
                    runSpherePour(true, std::make_shared<threadCommunicator>(board, rank, 2));
            }
        );
    }
    for (std::thread& t : threads) t.join();
    for (int rank = 0; rank < 2; ++rank)
    {
        ASSERT_EQ(ranks[rank].states, general.states) << "rank " << rank;
        ASSERT_EQ(ranks[rank].histories, general.histories) << "rank " << rank;
    }
}
