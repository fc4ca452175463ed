/*---------------------------------------------------------------------------*\
Description
    The DEM's pair evaluations shared out among processes
    (demSolver::setCommunicator): the processes are threads here, each with
    its own replicated demSolver, exchanging through a shared-memory
    allGather. A pile of faceted bodies and spheres in a tank of wall
    patches, in a liquid (lubrication on), contact reuse on, a body removed
    on the way: every process's trajectories and contact histories are the
    serial run's, bit for bit, and the pairs are shared out.
\*---------------------------------------------------------------------------*/

#include "demSolver.H"
#include "demCommunicator.H"
#include "sphereShape.H"
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


//- Twelve bodies (non-convex tori, icosahedra measured on the octree,
//  spheres) dropped in a tank of wall patches, in a liquid; body 5 removed
//  half way
runResult runPile(std::shared_ptr<demCommunicator> comm)
{
    demSettings s;
    s.gravity = vec3(0, 0, -9.81);
    s.overlap = overlapSettings{0.001, 1};
    s.overlap.convexExact = false;
    s.reuseContacts = true;
    demSolver dem({test::material("soft", 1e6)}, s);
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

    const auto torus = std::make_shared<triangleMeshShape>
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
            k % 3 == 0 ? std::shared_ptr<const shape>(torus)
          : k % 3 == 1 ? std::shared_ptr<const shape>(ico)
          : std::shared_ptr<const shape>(ball);
        rigidBody b("b" + std::to_string(k), g, 2500);
        const int i = k % 2, j = (k/2) % 2, l = k/4;
        b.pose = bodyPose
        (
            vec3(0.011 + 0.018*i, 0.011 + 0.018*j, 0.006 + 0.0085*l)
          + test::randomVec(gen, -0.0005, 0.0005),
            test::randomQuat(gen)
        );
        b.velocity = test::randomVec(gen, -0.05, 0.05);
        b.angularVelocity = test::randomVec(gen, -5, 5);
        b.fluidCellSize = 0.002;
        dem.addBody(b);
    }

    runResult r;
    for (int a = 0; a < 10; ++a)
    {
        if (a == 5)
        {
            dem.removeBodies({5});
        }
        dem.advance(0.002);
        for (const rigidBody& b : dem.bodies())
        {
            const vec3 x = b.pose.position();
            const quat& q = b.pose.orientation();
            r.states.insert
            (
                r.states.end(),
                {
                    x.x(), x.y(), x.z(), q.w(), q.x(), q.y(), q.z(),
                    b.velocity.x(), b.velocity.y(), b.velocity.z(),
                    b.angularVelocity.x(), b.angularVelocity.y(), b.angularVelocity.z(),
                    b.contactForce.x(), b.contactForce.y(), b.contactForce.z(),
                    b.lubricationForce.x(), b.lubricationForce.y(), b.lubricationForce.z()
                }
            );
        }
        r.contacts += long(dem.contacts().size());
    }
    for (const auto& h : dem.histories())
    {
        r.histories.insert(r.histories.end(), {double(h.first.first), double(h.first.second)});
        for (const contactHistory& c : h.second)
        {
            r.histories.insert
            (
                r.histories.end(),
                {
                    c.tangentialSpring.x(), c.tangentialSpring.y(), c.tangentialSpring.z(),
                    c.point.x(), c.approach, c.maxNormalForce
                }
            );
        }
    }
    r.pairEvaluations = dem.work().pairEvaluations;
    r.reusedEvaluations = dem.work().reusedEvaluations;
    r.lubricatedPairs = dem.work().lubricatedPairs;
    return r;
}


//- The pile run on n threads sharing the pairs
std::vector<runResult> runOn(int n)
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
                results[rank] = runPile(std::make_shared<threadCommunicator>(board, rank, n));
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
        EXPECT_GT(c, 780/3*0.85);
        EXPECT_LT(c, 780/3*1.15);
    }
    EXPECT_EQ(demCommunicator::owner(3, 9, 1), 0);
}


TEST(demProcesses, sharedPairsGiveTheSerialTrajectoriesBitForBit)
{
    const runResult serial = runPile(nullptr);
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
        const std::vector<runResult> ranks = runOn(n);
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
