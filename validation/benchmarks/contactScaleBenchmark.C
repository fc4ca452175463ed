/*---------------------------------------------------------------------------*\
Application
    contactScaleBenchmark

Description
    The DEM's cost at scale (issue 20), measured side by side in one run:

    1. No contact: N lumpy stars (5,120 triangles, the arbitraryBodiesCollision
       template's lumpyStar.stl) on a cubic lattice, at random orientations,
       spaced so that their boxes and bounding spheres overlap (spacing
       1.94 R) but no two come within 0.15 d (the
       engine's reach is 0.087 d), inside an open box wall (a wallMeshShape of 2 x 20 x 20
       triangles per side, whose box holds every body, 0.3 R from the
       nearest, its rim 7 R above the top layer) and above a plane
       floor; bodies drift slowly (1 mm/s, 1 rad/s) with no gravity. The
       DEM's contact CPU per body per sub-step with the pair filter off
       (every candidate pair to the overlap engine: the code before issue 20)
       and on. virtualMesh at cellSize d/10, level 1 (the runs).
    2. One contact per sub-step: two 20-face icosahedra (circumradius 5 mm)
       0.1 mm deep (virtualMesh level 3, h = d/10), and two lumpy stars
       pressed to an overlap of about 2e-9 m^3 (cellSize d/10, level 1):
       the DEM's contact CPU per sub-step, filter off and on (the filter
       must not slow a contact down).
    3. Memory per body: the heap in use (mallinfo2) per body for N bodies
       of one shared surface (each body a pose), and for bodies each
       reading its own copy of the surface (the reader before issue 20).
    4. Reuse between sub-steps (demSettings::reuseContacts): lasting
       contacts run by the DEM (automatic step, glass), with reuse off and
       on side by side: the contact CPU per contact per sub-step, the
       fraction of sub-steps that evaluate the pair in full, and the
       largest volume error of the reused contacts against a full
       evaluation at the same poses (a third run, checked every sub-step):
         - the new user's block: a glass cube (10 mm) resting face down on
           the floor of a mesh wall (an open box patch) under gravity,
           placed at the depth that carries its weight, default resolution
           (h = d/20, level 4); the same rocking (1e-3 rad/s at the start);
         - the same cube at rest on a plane;
         - two icosahedra (h = d/10, level 3), B pressed onto fixed A
           (a load of 1000 g along the centre line, placed at the depth
           that carries it) and sliding across at 5 mm/s;
         - two lumpy stars (h = d/10, level 1), likewise.

Usage
    contactScaleBenchmark [N] [--stl=file] [--steps=n] [--reuse-only]
        [--reuse-case=word] [--reuse-tolerance=x] [--reuse-fraction=x]
        [--compare-laws] [--reuse-tolerance-potential=x]

    N       bodies of the no-contact lattice (default 27 = 3^3)
    steps   sub-steps with the filter on (default 200; off: steps/10);
            part 4 runs 10 steps with reuse (1 without) per step here
    reuse-only  part 4 only
    reuse-case  part 4: only the contacts whose name holds the word
    reuse-tolerance  demSettings::reuseTolerance (default 0.0025)
    reuse-fraction   demSettings::reuseFraction, the first (default 0.02)
    compare-laws     part 4 with reuse on, the volume and potential laws
                     side by side (issue 19: the cost per contact of the
                     potential law against the default, volume)
    reuse-tolerance-potential  demSettings::reuseTolerancePotential
                     (default 5e-6)
\*---------------------------------------------------------------------------*/

#include "benchmarkTools.H"
#include "demSolver.H"
#include "halfSpaceShape.H"
#include "triangleMeshShape.H"
#include "wallMeshShape.H"
#include "primitiveMeshes.H"
#include "coreError.H"
#include "overlapEngine.H"

#include <malloc.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <time.h>
#include <random>
#include <string>

using namespace immersedDEM;

namespace
{

using benchmark::cpuSeconds;
using benchmark::randomRotation;

size_t heapInUse()
{
    malloc_trim(0);
    return mallinfo2().uordblks + mallinfo2().hblkhd;
}

struct result
{
    double usPerBody = 0;       //!< contact CPU per body per sub-step
    double usPerStep = 0;       //!< contact CPU per sub-step
    long evaluations = 0;
    long contacts = 0;
    pairFilter::counters filter;
};

// 1. The lattice without contact
result lattice
(
    const std::shared_ptr<const triangleMeshShape>& star, int N, int steps, bool filter,
    double& d, double speed = 1e-3, double spin = 1.0
)
{
    const double R = star->boundingRadius();
    d = 2*std::cbrt(3*star->volume()/(4*M_PI));
    contactMaterial glass{"glass", 1e7, 0.3, 0.5, 0.4};
    demSettings s;
    s.overlap = {d/10, 1};
    s.rejectSeparated = filter;
    s.reuseContacts = false;
    s.deltaT = 1e-5;
    demSolver dem({glass}, s);

    const int n = std::max(1, int(std::round(std::cbrt(double(N)))));
    // Spacing: the bounding spheres overlap (1.94 R < 2 R), orientations
    // drawn until no two neighbours touch
    const double a = 1.94*R;
    std::mt19937 g(1);
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<rigidBody> placed;
    for (int k = 0; k < N; ++k)
    {
        const vec3 x(a*(k % n), a*((k / n) % n), a*(k/(n*n)) + R);
        rigidBody b("star" + std::to_string(k), star, 2500);
        for (int tries = 0; tries < 2000; ++tries)
        {
            b.pose = bodyPose(x, randomRotation(g));
            bool touches = false;
            for (const rigidBody& o : placed)
            {
                if ((o.pose.position() - x).norm() > 2*R) continue;
                // Apart by 1.5 virtual-mesh cells: beyond the engine's reach
                if (pairFilter::gapLowerBound(*star, o.pose, *star, b.pose, 0.15*d, d) < 0.15*d)
                {
                    touches = true;
                    break;
                }
            }
            if (!touches) break;
        }
        b.velocity = speed*vec3(u(g), u(g), u(g));
        b.angularVelocity = spin*vec3(u(g), u(g), u(g));
        placed.push_back(b);
        dem.addBody(b);
    }
    // Floor just below the lowest bodies, an open box around all
    rigidBody floor("floor", std::make_shared<halfSpaceShape>(), 1);
    floor.motion = motionType::fixed;
    floor.pose = halfSpaceShape::poseOf(vec3(0, 0, -0.3*R), vec3::UnitZ());
    dem.addBody(floor, true);
    const vec3 lo = vec3::Constant(-1.3*R) + vec3(0, 0, 1.3*R);
    // The rim 6 R above the top layer (see pairFilter: the sign behind an
    // open rim)
    const vec3 hi = vec3::Constant(a*(n - 1) + 1.3*R) + vec3(0, 0, 6*R);
    rigidBody box("box", std::make_shared<wallMeshShape>(primitiveMeshes::openBox(lo - vec3(0, 0, 1.0*R), hi, 20), "box", 2*R), 1);
    box.motion = motionType::fixed;
    dem.addBody(box, true);

    dem.computeContacts();
    const long e0 = dem.work().pairEvaluations;
    long contacts = 0;
    const double c0 = cpuSeconds();
    for (int i = 0; i < steps; ++i)
    {
        dem.step(s.deltaT);
        contacts += long(dem.contacts().size());
    }
    result r;
    r.usPerStep = 1e6*(cpuSeconds() - c0)/steps;
    r.usPerBody = r.usPerStep/N;
    r.evaluations = dem.work().pairEvaluations - e0;
    r.contacts = contacts;
    r.filter = dem.filterWork();
    return r;
}

// 2. One pair in contact, at rest, pressed to a given depth
result onePair
(
    const std::shared_ptr<const triangleMeshShape>& shape, const overlapSettings& o,
    double depth, int steps, bool filter, double& volume, bool reuse = false
)
{
    contactMaterial glass{"glass", 1e7, 0.3, 0.5, 0.4};
    demSettings s;
    s.overlap = o;
    s.rejectSeparated = filter;
    s.reuseContacts = reuse;
    s.deltaT = 1e-9;      // bodies hardly move: the same contact every step
    demSolver dem({glass}, s);
    // Along x: the support of each body from its bounding box in the
    // body frame is not the contact gap, so find the touching distance by
    // bisection on the exact overlap volume
    const quat qa = quat::Identity();
    const quat qb = bodyPose::axisAngle(vec3(0.3, 1, 0.2), 0.7);
    const double x = benchmark::touchingDistance(*shape, *shape, qb) - depth;
    rigidBody A("a", shape, 2500), B("b", shape, 2500);
    A.pose = bodyPose(vec3::Zero(), qa);
    B.pose = bodyPose(vec3(x, 0, 0), qb);
    dem.addBody(A);
    dem.addBody(B);
    dem.computeContacts();
    volume = 0;
    for (const contactRecord& c : dem.contacts()) volume += c.region.volume;
    long contacts = 0;
    const double c0 = cpuSeconds();
    for (int i = 0; i < steps; ++i)
    {
        dem.step(s.deltaT);
        contacts += long(dem.contacts().size());
    }
    result r;
    r.usPerStep = 1e6*(cpuSeconds() - c0)/steps;
    r.contacts = contacts;
    r.filter = dem.filterWork();
    return r;
}


// 4. A lasting contact run by the DEM, reuse off or on
struct reuseResult
{
    double usPerContact = 0;    //!< contact CPU per contact per sub-step
    double fullFraction = 0;    //!< engine calls per sub-step
    double contactFraction = 0; //!< sub-steps with a contact
    double maxFullJump = 0;     //!< of the full volume from one sub-step to the next
    double maxVolumeError = 0;  //!< reused against full, relative
    double meanVolume = 0;
    double dt = 0;
    long steps = 0;
};

struct reuseCase
{
    std::string name;
    std::shared_ptr<const shape> A, B;
    bool wallA = false;
    bodyPose pA, pB;
    vec3 velocityB = vec3::Zero();
    vec3 omegaB = vec3::Zero();
    vec3 load = vec3::Zero();      //!< acceleration of B (gravity)
    //- B placed at the depth (along -z) where the contact carries its
    //  weight (a flat face: the force is proportional to the depth)
    bool atRest = false;
    bool flat = false;
    overlapSettings o;             //!< h = 0: the default resolution
    //- Sub-steps reuse off, on; check: a third run, checked every step
    int nOff = 0, nOn = 0;
    bool check = true;
};

double reuseToleranceOption = -1;
double reuseTolerancePotentialOption = -1;
double reuseFractionOption = -1;
std::string reuseCaseOption;
bool compareLaws = false;

reuseResult runReuse
(
    const reuseCase& c, bool reuse, int steps, bool check, const std::string& law = ""
)
{
    contactMaterial glass{"glass", 6e10, 0.24, 0.9, 0.3};
    demSettings s;
    if (!law.empty()) s.contactLaw = law;
    if (reuseToleranceOption > 0) s.reuseTolerance = reuseToleranceOption;
    if (reuseTolerancePotentialOption > 0) s.reuseTolerancePotential = reuseTolerancePotentialOption;
    if (reuseFractionOption > 0) s.reuseFraction = reuseFractionOption;
    s.overlap = c.o;
    s.gravity = c.load;
    s.reuseContacts = reuse;
    demSolver dem({glass}, s);
    rigidBody A("A", c.A, 2500);
    A.motion = motionType::fixed;
    A.pose = c.pA;
    dem.addBody(A, c.wallA);
    rigidBody B("B", c.B, 2500);
    B.pose = c.pB;
    B.velocity = c.velocityB;
    B.angularVelocity = c.omegaB;
    dem.addBody(B);
    if (c.atRest)
    {
        // Along the load: a flat face (the force proportional to the
        // depth) from one trial; otherwise by bisection on the force
        const vec3 dir = c.load.normalized();
        rigidBody& b = dem.bodies()[1];
        const vec3 x = b.pose.position();
        const double weight = b.mass()*c.load.norm();
        auto force = [&](double depth)
        {
            b.pose.setPosition(x + depth*dir);
            dem.computeContacts();
            return -b.contactForce.dot(dir);
        };
        double depth = 0;
        if (c.flat)
        {
            const double trial = 1e-10;
            depth = trial*weight/force(trial);
        }
        else
        {
            double lo = 0, hi = 0.1*c.B->boundingRadius();
            for (int i = 0; i < 40; ++i)
            {
                const double m = 0.5*(lo + hi);
                (force(m) < weight ? lo : hi) = m;
            }
            depth = 0.5*(lo + hi);
        }
        b.pose.setPosition(x + depth*dir);
        dem.bodiesChanged();
    }
    const auto engine = overlapEngine::New(s.overlapMethod);
    reuseResult r;
    r.dt = dem.timeStep();
    dem.computeContacts();
    const long e0 = dem.work().pairEvaluations;
    long contacts = 0;
    double cpu = 0;
    double vSum = 0;
    double lastFull = 0;
    for (int i = 0; i < steps; ++i)
    {
        const double c0 = cpuSeconds();
        dem.step(r.dt);
        cpu += cpuSeconds() - c0;
        double V = 0;
        for (const contactRecord& k : dem.contacts()) V += k.region.volume;
        contacts += dem.contacts().empty() ? 0 : 1;
        vSum += V;
        if (check)
        {
            const rigidBody& a = dem.bodies()[0];
            const rigidBody& b = dem.bodies()[1];
            const double Vfull =
                engine->evaluate(*a.geometry, a.pose, *b.geometry, b.pose, dem.settings().overlap).volume();
            if (Vfull > 0 || V > 0)
            {
                const double e = std::abs(V - Vfull)/std::max(V, Vfull);
                if (std::getenv("REUSE_DEBUG") && e > 0.005)
                {
                    std::printf("step %d error %.4f V %.6e full %.6e evaluations %ld regions %zu\n",
                        i, e, V, Vfull, dem.work().pairEvaluations, dem.contacts().size());
                }
                r.maxVolumeError = std::max(r.maxVolumeError, e);
            }
            if (i > 0 && Vfull > 0 && lastFull > 0)
            {
                r.maxFullJump = std::max(r.maxFullJump, std::abs(Vfull - lastFull)/Vfull);
            }
            lastFull = Vfull;
        }
    }
    r.steps = steps;
    r.usPerContact = 1e6*cpu/std::max(1L, contacts);
    r.fullFraction = double(dem.work().pairEvaluations - e0)/steps;
    r.contactFraction = double(contacts)/steps;
    r.meanVolume = vSum/steps;
    return r;
}

} // End anonymous namespace


int main(int argc, char* argv[])
{
    int N = 27;
    int steps = 200;
    bool reuseOnly = false;
    std::string stl = std::string(__FILE__);
    stl = stl.substr(0, stl.rfind("validation/benchmarks/"))
        + "caseTemplates/arbitraryBodiesCollision/constant/triSurface/lumpyStar.stl";
    for (int i = 1; i < argc; ++i)
    {
        const std::string a = argv[i];
        if (a.rfind("--stl=", 0) == 0) stl = a.substr(6);
        else if (a == "--reuse-only") reuseOnly = true;
        else if (a.rfind("--reuse-tolerance=", 0) == 0) reuseToleranceOption = std::atof(a.c_str() + 18);
        else if (a.rfind("--reuse-tolerance-potential=", 0) == 0) reuseTolerancePotentialOption = std::atof(a.c_str() + 28);
        else if (a.rfind("--reuse-fraction=", 0) == 0) reuseFractionOption = std::atof(a.c_str() + 17);
        else if (a.rfind("--reuse-case=", 0) == 0) reuseCaseOption = a.substr(13);
        else if (a == "--compare-laws") { compareLaws = true; reuseOnly = true; }
        else if (a.rfind("--steps=", 0) == 0) steps = std::max(10, std::atoi(a.c_str() + 8));
        else if (a[0] != '-') N = std::max(1, std::atoi(a.c_str()));
        else
        {
            std::fprintf(stderr, "Unknown option %s\n", a.c_str());
            return 1;
        }
    }

    try
    {
        std::shared_ptr<const triangleMeshShape> star(triangleMeshShape::fromFile(stl));
        double d = 2*std::cbrt(3*star->volume()/(4*M_PI));
        if (!reuseOnly)
        {
        // 3. Memory: a second copy of the surface
        const size_t h0 = heapInUse();
        std::unique_ptr<triangleMeshShape> copy(triangleMeshShape::fromFile(stl));
        const size_t h1 = heapInUse();
        const double perSurface = double(h1 - h0);
        copy.reset();
        const int M = 64;
        double perSharedBody = 0;
        {
            contactMaterial glass{"glass", 1e7, 0.3, 0.5, 0.4};
            demSettings s;
            s.deltaT = 1e-6;
            s.overlap = {0.001, 1};
            const size_t m0 = heapInUse();
            demSolver dem({glass}, s);
            for (int k = 0; k < M; ++k)
            {
                rigidBody b("b" + std::to_string(k), star, 2500);
                b.pose = bodyPose(vec3(0.1*k, 0, 0), quat::Identity());
                dem.addBody(b);
            }
            dem.step(1e-6);
            perSharedBody = double(heapInUse() - m0)/M;
        }
        std::printf("# contactScaleBenchmark: lumpy star %s\n", stl.c_str());
        std::printf("#   %zu triangles, bounding radius %.4g m\n", star->nTriangles(), star->boundingRadius());
        std::printf("\nMemory per body (heap in use, mallinfo2)\n");
        std::printf("  own copy of the surface (before)      %10.1f kB\n", perSurface/1024);
        std::printf("  shared surface, per extra body (after) %9.2f kB   (target <= 100 kB)\n", perSharedBody/1024);

        // 1. No contact
        const int stepsOff = std::max(2, steps/10);
        const double t0 = cpuSeconds();
        const result off = lattice(star, N, stepsOff, false, d);
        const double t1 = cpuSeconds();
        const result on = lattice(star, N, steps, true, d);
        const double t2 = cpuSeconds();
        std::printf("\nNo contact: %d lumpy stars (d = %.4g m), open box wall (4000 triangles) and a plane\n", N, d);
        std::printf("  virtualMesh cellSize d/10 level 1; %d sub-steps off, %d on\n", stepsOff, steps);
        std::printf("  contacts seen: off %ld, on %ld (must be 0)\n", off.contacts, on.contacts);
        std::printf("  DEM CPU (whole step) per body per sub-step: filter off %9.1f us, on %7.2f us   (target <= 10 us)   ratio %.0f\n",
            off.usPerBody, on.usPerBody, off.usPerBody/on.usPerBody);
        std::printf("  engine calls per sub-step: off %.1f, on %.2f\n",
            double(off.evaluations)/stepsOff, double(on.evaluations)/steps);
        std::printf("  filter: %ld pair tests, rejected by spheres %ld, by reuse %ld, by new proof %ld (proofs %ld), to the engine %ld\n",
            on.filter.tested, on.filter.rejectedBySpheres, on.filter.rejectedByReuse,
            on.filter.rejectedByProof, on.filter.proofs, on.filter.passed);
        std::printf("  whole run CPU (setup included): off %.2f s, on %.2f s\n", t1 - t0, t2 - t1);
        // Faster bodies (0.1 m/s, 20 rad/s: about d/500 per 10 sub-steps),
        // so the proofs must be renewed
        const result fast = lattice(star, N, steps, true, d, 0.1, 20);
        std::printf("  bodies at 0.1 m/s and 20 rad/s, filter on: %7.2f us per body per sub-step; contacts %ld; %ld proofs (%.3f per pair test)\n",
            fast.usPerBody, fast.contacts, fast.filter.proofs, double(fast.filter.proofs)/fast.filter.tested);

        // 2. One contact per sub-step
        std::printf("\nOne contact per sub-step (DEM CPU per sub-step)\n");
        {
            std::shared_ptr<const triangleMeshShape> ico
            (
                new triangleMeshShape(primitiveMeshes::icosphere(0.005, 0), "icosahedron")
            );
            const double di = 2*std::cbrt(3*ico->volume()/(4*M_PI));
            double v0 = 0, v1 = 0;
            const int n = std::max(10, steps/10);
            const result a0 = onePair(ico, {di/10, 3}, 1e-4, n, false, v0);
            const result a1 = onePair(ico, {di/10, 3}, 1e-4, n, true, v1);
            const result a2 = onePair(ico, {di/10, 3}, 1e-4, n, true, v1, true);
            std::printf("  icosahedra (20 faces), 0.1 mm deep, h = d/10 level 3, V = %.4g m3: off %8.1f us, on %8.1f us, on with reuse %8.1f us (target <= 100 us)\n",
                v0, a0.usPerStep, a1.usPerStep, a2.usPerStep);
            const result b0 = onePair(star, {d/10, 1}, 2e-5, n, false, v0);
            const result b1 = onePair(star, {d/10, 1}, 2e-5, n, true, v1);
            const result b2 = onePair(star, {d/10, 1}, 2e-5, n, true, v1, true);
            std::printf("  lumpy stars (5120 faces), h = d/10 level 1, V = %.4g m3:           off %8.1f us, on %8.1f us, on with reuse %8.1f us (target <= 300 us)\n",
                v0, b0.usPerStep, b1.usPerStep, b2.usPerStep);
            std::printf("  (filter off / on: reuse off; at 1e-9 s per sub-step the pair is at rest: reuse is bounded by its count, %d)\n",
                demSettings().reuseMaxSteps);
        }

        }
        // 4. Reuse between sub-steps
        {
            std::printf("\nReuse between sub-steps: a lasting contact run by the DEM (glass, automatic step);\n");
            std::printf("  contact CPU per contact per sub-step, reuse off / on, the fraction of sub-steps evaluated in full,\n");
            std::printf("  and the largest volume error of the run with reuse against a full evaluation at the same poses\n");
            if (compareLaws)
            {
                std::printf("  laws side by side, reuse on: volume (the default) against potential\n");
                std::printf("  %-34s %9s %9s %6s %11s %11s %7s %9s %9s\n",
                    "contact", "dt vol", "dt pot", "steps", "volume [us]", "potent [us]", "pot/vol", "fullV [%]", "fullP [%]");
            }
            else
            {
            std::printf("  %-34s %9s %6s %6s %11s %11s %7s %9s %9s %10s %11s\n",
                "contact", "dt [s]", "off", "on", "off [us]", "on [us]", "ratio", "full [%]", "touch [%]", "maxErr [%]", "fullJump[%]");
            }
            std::shared_ptr<const triangleMeshShape> cube
            (
                new triangleMeshShape(primitiveMeshes::box(vec3::Constant(0.005)), "cube")
            );
            std::shared_ptr<const triangleMeshShape> ico
            (
                new triangleMeshShape(primitiveMeshes::icosphere(0.005, 0), "icosahedron")
            );
            const double dIco = 2*std::cbrt(3*ico->volume()/(4*M_PI));
            const double g = 9.81;
            const quat qb = bodyPose::axisAngle(vec3(0.3, 1, 0.2), 0.7);
            std::vector<reuseCase> cases;
            {
                reuseCase c;
                c.name = "cube face down on a mesh wall";
                c.A = std::make_shared<wallMeshShape>
                (
                    primitiveMeshes::openBox(vec3(-0.03, -0.03, 0), vec3(0.03, 0.03, 0.06), 4), "tank", 0.01
                );
                c.wallA = true;
                c.B = cube;
                c.pB = bodyPose(vec3(0, 0, 0.005), quat::Identity());
                c.load = vec3(0, 0, -g);
                c.atRest = true;
                c.flat = true;
                c.nOff = 4;
                c.nOn = 300;
                c.check = false;
                cases.push_back(c);
                c.name = "cube as above, rocking 1e-3 rad/s";
                c.omegaB = vec3(1e-3, 0, 0);
                cases.push_back(c);
                c.name = "cube face down on a plane";
                c.omegaB = vec3::Zero();
                c.A = std::make_shared<halfSpaceShape>();
                c.pA = halfSpaceShape::poseOf(vec3::Zero(), vec3::UnitZ());
                cases.push_back(c);
            }
            auto pressed = [&](const std::string& name, std::shared_ptr<const triangleMeshShape> sh, const overlapSettings& o)
            {
                const double lo = benchmark::touchingDistance(*sh, *sh, qb);
                reuseCase c;
                c.name = name;
                c.A = sh;
                c.B = sh;
                c.o = o;
                c.pB = bodyPose(vec3(lo, 0, 0), qb);
                c.velocityB = vec3(0, 0.005, 0);
                c.load = vec3(-1000*g, 0, 0);
                c.atRest = true;
                return c;
            };
            cases.push_back(pressed("icosahedra pressed, sliding", ico, {dIco/10, 3}));
            cases.push_back(pressed("lumpy stars pressed, sliding", star, {d/10, 1}));
            for (reuseCase& c : cases)
            {
                if (!reuseCaseOption.empty() && c.name.find(reuseCaseOption) == std::string::npos) continue;
                if (c.nOn == 0)
                {
                    c.nOn = steps*10;
                    c.nOff = std::max(10, steps);
                }
                if (compareLaws)
                {
                    // Both with reuse, alternating, the smaller CPU of two runs each
                    reuseResult vol, pot;
                    for (int k = 0; k < 2; ++k)
                    {
                        const reuseResult v = runReuse(c, true, c.nOn, false, "volume");
                        const reuseResult p = runReuse(c, true, c.nOn, false, "potential");
                        if (k == 0 || v.usPerContact < vol.usPerContact) vol = v;
                        if (k == 0 || p.usPerContact < pot.usPerContact) pot = p;
                    }
                    std::printf("  %-34s %9.3g %9.3g %6d %11.1f %11.1f %7.3f %9.2f %9.2f\n",
                        c.name.c_str(), vol.dt, pot.dt, c.nOn, vol.usPerContact, pot.usPerContact,
                        pot.usPerContact/vol.usPerContact, 100*vol.fullFraction, 100*pot.fullFraction);
                    std::fflush(stdout);
                    continue;
                }
                const reuseResult off = runReuse(c, false, c.nOff, false);
                const reuseResult on = runReuse(c, true, c.nOn, false);
                double err = -1, jump = -1;
                if (c.check)
                {
                    const reuseResult chk = runReuse(c, true, c.nOn, true);
                    err = chk.maxVolumeError;
                    jump = chk.maxFullJump;
                }
                std::printf("  %-34s %9.3g %6d %6d %11.1f %11.1f %7.1f %9.2f %9.1f ",
                    c.name.c_str(), on.dt, c.nOff, c.nOn, off.usPerContact, on.usPerContact,
                    off.usPerContact/on.usPerContact, 100*on.fullFraction, 100*on.contactFraction);
                if (err >= 0) std::printf("%10.4f %11.4f\n", 100*err, 100*jump);
                else std::printf("%10s %11s\n", "-", "-");
                std::fflush(stdout);
            }
            std::printf("  (-: not checked; a full evaluation of the cube at the default resolution takes seconds:\n"
                        "   its error is that of the unit test contactReuse.cubeRockingOnPlane)\n");
            std::printf("  targets: icosahedra <= 100 us, lumpy stars <= 300 us per contact per sub-step at <= 0.5%% volume error\n");
        }
    }
    catch (const coreError& e)
    {
        std::fprintf(stderr, "Error: %s\n", e.what());
        return 1;
    }
    return 0;
}
