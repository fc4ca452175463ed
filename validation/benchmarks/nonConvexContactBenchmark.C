/*---------------------------------------------------------------------------*\
Application
    nonConvexContactBenchmark

Description
    The DEM's cost for non-convex catalyst shapes (issue 46), the convex
    pieces (the default) and the octree virtual mesh (maxConvexPieces 0,
    the code before) side by side in one run, default DEM settings (the
    octree's resolution chosen per pair type by the volume tolerance,
    contacts reused between sub-steps):

    1. One lasting contact: B pressed onto fixed A by a load of 1000 g
       along the centre line and sliding across at 5 mm/s (glass,
       restitution 0.3), settled from touching with the pieces (20 times
       the timed sub-steps), then both paths from that state, with the
       contacts reused between sub-steps (the default) and measured in
       full every sub-step; CPU per contact per sub-step, mean overlap
       volume, contacts per sub-step:
         - two Raschig rings 4 x 2 x 4 mm (24 segments, 192 triangles),
           side on side;
         - two trilobes (lobes 1.8 mm across at 0.8 mm from the axis,
           4 mm long, 48 outline points);
         - a ring on a plane wall.
    2. Candidate pairs far from contact: 27 rings on a cubic lattice at
       random orientations, spaced so that their bounding spheres overlap
       (1.94 R) and no two come within 0.2 mm, drifting slowly (1 mm/s,
       1 rad/s, no gravity); CPU per candidate pair per sub-step (most
       are rejected by the proof of an earlier sub-step and the motion
       since); and the proof alone, without that reuse: CPU per
       pairFilter::gapLowerBound at 1000 poses with the bounding spheres
       overlapping and the rings 0.05 to 1 mm apart (falling rings, whose
       motion outruns the reuse).

    The figures are thread CPU times (the machine may be shared), the two
    paths alternated and the smaller of two rounds kept.

Usage
    nonConvexContactBenchmark [--steps=n]
        steps   sub-steps per run (default 400)
\*---------------------------------------------------------------------------*/

#include "benchmarkTools.H"
#include "demSolver.H"
#include "halfSpaceShape.H"
#include "overlapEngine.H"
#include "pairFilter.H"
#include "primitiveMeshes.H"
#include "triangleMeshShape.H"
#include "coreError.H"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <time.h>

using namespace immersedDEM;

namespace
{

using benchmark::cpuSeconds;
using benchmark::randomRotation;

const double mm = 0.001;

struct shapes
{
    std::shared_ptr<const triangleMeshShape> ring, trilobe;
};

shapes make(int maxPieces)
{
    return
    {
        std::make_shared<triangleMeshShape>
        (
            primitiveMeshes::hollowCylinder(2*mm, 1*mm, 4*mm, 24), "ring", true, maxPieces
        ),
        std::make_shared<triangleMeshShape>
        (
            primitiveMeshes::lobed(3, 0.8*mm, 0.9*mm, 4*mm, 48), "trilobe", true, maxPieces
        )
    };
}


struct contactCost
{
    double usPerContact = 0;
    double contactsPerStep = 0;
    double volume = 0;          //!< mean overlap volume
};

// 1. A lasting contact: B pressed onto A (a body, or a plane when A is
// null) along -x, sliding along y. The state after settling (B's pose and
// velocities), shared by both paths: settled with the pieces, then the
// timed sub-steps from it with the shapes given
struct pressedState
{
    bodyPose pose;
    vec3 velocity = vec3::Zero(), omega = vec3::Zero();
};

// Wet glass, restitution 0.3 so the pressed body settles soon
const contactMaterial wetGlass{"glass", 6e10, 0.24, 0.3, 0.3};

demSettings pressedSettings(bool reuse = true)
{
    demSettings s;
    s.gravity = vec3(-1000*9.81, 0, 0);
    s.reuseContacts = reuse;
    return s;
}

void addPair
(
    demSolver& dem,
    const std::shared_ptr<const triangleMeshShape>& A,
    const std::shared_ptr<const triangleMeshShape>& B,
    const pressedState& st
)
{
    if (A)
    {
        rigidBody a("A", A, 2500);
        a.motion = motionType::fixed;
        dem.addBody(a);
    }
    else
    {
        rigidBody wall("wall", std::make_shared<halfSpaceShape>(), 1);
        wall.motion = motionType::fixed;
        wall.pose = halfSpaceShape::poseOf(vec3::Zero(), vec3::UnitX());
        dem.addBody(wall, true);
    }
    rigidBody b("B", B, 2500);
    b.pose = st.pose;
    b.velocity = st.velocity;
    b.angularVelocity = st.omega;
    dem.addBody(b);
    dem.computeContacts();
}

pressedState settle
(
    const std::shared_ptr<const triangleMeshShape>& A,
    const std::shared_ptr<const triangleMeshShape>& B,
    int steps
)
{
    const quat qb = bodyPose::axisAngle(vec3(0.3, 1, 0.2), 0.7);
    // From touching: along x by bisection on the exact volume (a plane:
    // B's lowest point)
    double x = 0;
    if (A)
    {
        x = benchmark::touchingDistance(*A, *B, qb);
    }
    else
    {
        const bodyPose p(vec3::Zero(), qb);
        double low = 1;
        for (const vec3& v : B->surface().points) low = std::min(low, p.toWorld(v).x());
        x = -low;
    }
    pressedState st;
    st.pose = bodyPose(vec3(x, 0, 0), qb);
    st.velocity = vec3(0, 0.005, 0);
    demSolver dem({wetGlass}, pressedSettings());
    addPair(dem, A, B, st);
    for (int i = 0; i < steps; ++i) dem.step(dem.timeStep());
    const rigidBody& b = dem.bodies().back();
    return {b.pose, b.velocity, b.angularVelocity};
}

contactCost lasting
(
    const std::shared_ptr<const triangleMeshShape>& A,
    const std::shared_ptr<const triangleMeshShape>& B,
    const pressedState& st,
    int steps,
    bool reuse
)
{
    demSolver dem({wetGlass}, pressedSettings(reuse));
    addPair(dem, A, B, st);
    long contacts = 0;
    double volume = 0;
    const double c0 = cpuSeconds();
    for (int i = 0; i < steps; ++i)
    {
        dem.step(dem.timeStep());
        contacts += long(dem.contacts().size());
        for (const contactRecord& c : dem.contacts()) volume += c.region.volume;
    }
    contactCost r;
    r.usPerContact = 1e6*(cpuSeconds() - c0)/std::max(1L, contacts);
    r.contactsPerStep = double(contacts)/steps;
    r.volume = volume/std::max(1L, contacts);
    return r;
}


struct farCost
{
    double usPerCandidate = 0;
    double candidatesPerStep = 0;
    long contacts = 0;
};

// 2. The lattice of rings apart
farCost lattice(const std::shared_ptr<const triangleMeshShape>& ring, int steps)
{
    const double R = ring->boundingRadius();
    contactMaterial glass{"glass", 6e10, 0.24, 0.9, 0.3};
    demSettings s;
    s.deltaT = 1e-6;
    demSolver dem({glass}, s);
    const int n = 3;
    const double a = 1.94*R;
    std::mt19937 g(1);
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<rigidBody> placed;
    for (int k = 0; k < n*n*n; ++k)
    {
        const vec3 x(a*(k % n), a*((k / n) % n), a*(k/(n*n)));
        rigidBody b("ring" + std::to_string(k), ring, 2500);
        for (int tries = 0; tries < 5000; ++tries)
        {
            b.pose = bodyPose(x, randomRotation(g));
            bool near = false;
            for (const rigidBody& o : placed)
            {
                if ((o.pose.position() - x).norm() > 2*R) continue;
                if (pairFilter::gapLowerBound(*ring, o.pose, *ring, b.pose, 0.2*mm, 1*mm) < 0.2*mm)
                {
                    near = true;
                    break;
                }
            }
            if (!near) break;
        }
        b.velocity = 1e-3*vec3(u(g), u(g), u(g));
        b.angularVelocity = vec3(u(g), u(g), u(g));
        placed.push_back(b);
        dem.addBody(b);
    }
    dem.computeContacts();
    const long t0 = dem.filterWork().tested;
    long contacts = 0;
    const double c0 = cpuSeconds();
    for (int i = 0; i < steps; ++i)
    {
        dem.step(s.deltaT);
        contacts += long(dem.contacts().size());
    }
    farCost r;
    const long tested = dem.filterWork().tested - t0;
    r.usPerCandidate = 1e6*(cpuSeconds() - c0)/std::max(1L, tested);
    r.candidatesPerStep = double(tested)/steps;
    r.contacts = contacts;
    return r;
}

// 2b. The proof that two rings are apart, without reuse: CPU per
// gapLowerBound call at n poses whose bounding spheres overlap and whose
// rings are 0.05 to 1 mm apart (the poses drawn once, with the pieces)
double proofCost
(
    const std::shared_ptr<const triangleMeshShape>& ring,
    const std::vector<std::pair<bodyPose, bodyPose>>& poses,
    double& meanGap
)
{
    double sum = 0;
    const double c0 = cpuSeconds();
    for (const auto& p : poses)
    {
        sum += pairFilter::gapLowerBound(*ring, p.first, *ring, p.second, 0.02*mm, 2*mm);
    }
    meanGap = sum/poses.size();
    return 1e6*(cpuSeconds() - c0)/poses.size();
}

std::vector<std::pair<bodyPose, bodyPose>> apartPoses
(
    const std::shared_ptr<const triangleMeshShape>& ring, int n
)
{
    std::mt19937 g(3);
    std::uniform_real_distribution<double> u(0, 1);
    std::normal_distribution<double> z;
    const double R = ring->boundingRadius();
    std::vector<std::pair<bodyPose, bodyPose>> out;
    while (int(out.size()) < n)
    {
        const bodyPose a(vec3::Zero(), randomRotation(g));
        const vec3 dir = vec3(z(g), z(g), z(g)).normalized();
        const bodyPose b((1 + u(g))*R*dir, randomRotation(g));
        const double gap = pairFilter::gapLowerBound(*ring, a, *ring, b, -1, 2*mm);
        if (gap > 0.05*mm && gap < 1*mm) out.emplace_back(a, b);
    }
    return out;
}

} // End anonymous namespace


int main(int argc, char** argv)
{
    int steps = 400;
    for (int i = 1; i < argc; ++i)
    {
        if (std::strncmp(argv[i], "--steps=", 8) == 0) steps = std::max(10, std::atoi(argv[i] + 8));
        else
        {
            std::fprintf(stderr, "Usage: nonConvexContactBenchmark [--steps=n]\n");
            return 1;
        }
    }
    try
    {
        const shapes pieces = make(convexDecomposition::defaultMaxPieces);
        const shapes octree = make(0);
        std::printf("ring: %s (%zu triangles); trilobe: %s (%zu triangles)\n",
            pieces.ring->piecesNote().c_str(), pieces.ring->nTriangles(),
            pieces.trilobe->piecesNote().c_str(), pieces.trilobe->nTriangles());

        struct pairCase
        {
            const char* name;
            std::shared_ptr<const triangleMeshShape> aP, bP, aO, bO;
        };
        const pairCase cases[] =
        {
            {"ring on ring", pieces.ring, pieces.ring, octree.ring, octree.ring},
            {"trilobe on trilobe", pieces.trilobe, pieces.trilobe, octree.trilobe, octree.trilobe},
            {"ring on a plane", nullptr, pieces.ring, nullptr, octree.ring}
        };
        std::vector<pressedState> states;
        for (const pairCase& c : cases) states.push_back(settle(c.aP, c.bP, 20*steps));
        for (const bool reuse : {true, false})
        {
            std::printf
            (
                "\n1%s. One lasting contact, %s, CPU per contact per sub-step [us] (%d sub-steps)\n",
                reuse ? "a" : "b",
                reuse ? "reused between sub-steps (the default)" : "measured in full every sub-step",
                steps
            );
            std::printf("  %-22s %12s %12s %9s %14s %14s %9s\n",
                "pair", "octree", "pieces", "ratio", "V octree", "V pieces", "contacts");
            for (size_t k = 0; k < states.size(); ++k)
            {
                const pairCase& c = cases[k];
                contactCost o, p;
                for (int round = 0; round < 2; ++round)
                {
                    const contactCost oo = lasting(c.aO, c.bO, states[k], steps, reuse);
                    const contactCost pp = lasting(c.aP, c.bP, states[k], steps, reuse);
                    if (round == 0 || oo.usPerContact < o.usPerContact) o = oo;
                    if (round == 0 || pp.usPerContact < p.usPerContact) p = pp;
                }
                std::printf("  %-22s %12.1f %12.2f %9.0f %14.4g %14.4g %9.2f\n",
                    c.name, o.usPerContact, p.usPerContact, o.usPerContact/p.usPerContact,
                    o.volume, p.volume, p.contactsPerStep);
                std::fflush(stdout);
            }
        }
        std::printf("  target: at most 20 us per non-convex contact per sub-step\n");

        std::printf("\n2. 27 rings apart, CPU per candidate pair per sub-step [us] (%d sub-steps)\n", steps);
        farCost o, p;
        for (int round = 0; round < 2; ++round)
        {
            const farCost oo = lattice(octree.ring, steps);
            const farCost pp = lattice(pieces.ring, steps);
            if (round == 0 || oo.usPerCandidate < o.usPerCandidate) o = oo;
            if (round == 0 || pp.usPerCandidate < p.usPerCandidate) p = pp;
        }
        std::printf("  %-22s %12s %12s %9s\n", "", "octree", "pieces", "ratio");
        std::printf("  %-22s %12.2f %12.2f %9.1f\n", "us per candidate pair",
            o.usPerCandidate, p.usPerCandidate, o.usPerCandidate/p.usPerCandidate);
        std::printf("  %-22s %12.1f %12.1f\n", "candidates per step", o.candidatesPerStep, p.candidatesPerStep);
        std::printf("  %-22s %12ld %12ld\n", "contacts (must be 0)", o.contacts, p.contacts);
        const auto poses = apartPoses(pieces.ring, 1000);
        double proofO = 0, proofP = 0, gapO = 0, gapP = 0;
        for (int round = 0; round < 2; ++round)
        {
            const double oo = proofCost(octree.ring, poses, gapO);
            const double pp = proofCost(pieces.ring, poses, gapP);
            if (round == 0 || oo < proofO) proofO = oo;
            if (round == 0 || pp < proofP) proofP = pp;
        }
        std::printf("  %-22s %12.2f %12.2f %9.1f\n", "us per proof (no reuse)",
            proofO, proofP, proofO/proofP);
        std::printf("  %-22s %12.4g %12.4g   (1000 poses 0.05-1 mm apart; the octree's proof\n"
                    "  %-22s %12s %12s    stops below 0.02 mm)\n",
            "mean gap bound [mm]", gapO/mm, gapP/mm, "", "", "");
        std::printf("  target: at most 1 us per candidate non-convex pair per sub-step\n");
    }
    catch (const coreError& e)
    {
        std::fprintf(stderr, "Error: %s\n", e.what());
        return 1;
    }
    return 0;
}
