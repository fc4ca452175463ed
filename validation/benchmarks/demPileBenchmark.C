/*---------------------------------------------------------------------------*\
Application
    demPileBenchmark

Description
    N icosahedra read from an STL file (primitiveMeshes::icosphere(r, 0),
    20 triangles, r = 5 mm, written with surfaceFileIO and read back with
    triangleMeshShape::fromFile) are poured into an open box of 5 plane
    walls (floor and 4 sides) under gravity until they come to rest: the
    total kinetic energy below 1e-6 of its peak for 0.1 s running, or the
    maximum simulated time.

    Tuned to come to rest in few steps: soft grains (Y = 3e4 Pa, about a
    third of a millimetre of overlap at the bottom of the pile), strong
    damping (e = 0.2), friction 0.5, a fixed time step (16 steps per half
    period of two faces pressed flat together) and a virtual mesh just fine
    enough (h = edge/2, level 1: leaves of 1.3 mm). With leaves of 2.6 mm
    (level 0) the overlap's errors at edges and vertices keep the pile
    shivering at 1e-5 of the peak energy. Start: a closely packed square
    lattice (spacing 2r + 0.5 mm, 8 x 8 per layer for N = 200, 4 layers) a
    millimetre above the floor, each body at a random orientation and nudged
    sideways a little, at rest.

    Prints the setup, a kinetic-energy history (every 0.05 s) and a
    summary: bodies, DEM steps, wall-clock and CPU seconds, steps per
    second, pair evaluations, mean time per pair evaluation (overlap
    geometry and contact law), the kinetic energy's peak and final ratio,
    whether any body left the box (centroid outside the walls'
    half-spaces, checked at every history line and at the end), any NaN.

    With --check: PASS/FAIL lines for the acceptance criteria and a
    non-zero exit status unless all three hold:
        KE_final < 1e-6 KE_peak, no body outside the box, no NaN.

Usage
    demPileBenchmark [N [maxTime]] [--check] [--Y=Pa] [--e=restitution]
                     [--mu=friction] [--level=L] [--hEdge=h/edge]
                     [--seed=n] [--dt=s]

    N        number of icosahedra (default 200)
    maxTime  simulated seconds at most (default 3)
    dt       time step (default: 16 steps per half period of two faces
             pressed flat together)
\*---------------------------------------------------------------------------*/

#include "demSolver.H"
#include "halfSpaceShape.H"
#include "triangleMeshShape.H"
#include "primitiveMeshes.H"
#include "surfaceFileIO.H"
#include "coreError.H"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <random>
#include <string>
#include <vector>

using namespace immersedDEM;

namespace
{

struct options
{
    int N = 200;
    double maxTime = 3;
    bool check = false;
    double Y = 3e4;
    double e = 0.2;
    double mu = 0.5;
    int level = 1;
    double hEdge = 0.5;
    unsigned seed = 1;
    double dt = 0;          //!< 0: from the face-to-face contact
};


options parse(int argc, char* argv[])
{
    options o;
    int positional = 0;
    for (int i = 1; i < argc; ++i)
    {
        const std::string a = argv[i];
        auto value = [&](const char* key) -> const char*
        {
            const size_t n = std::strlen(key);
            return a.compare(0, n, key) == 0 ? a.c_str() + n : nullptr;
        };
        if (a == "--check") o.check = true;
        else if (const char* v = value("--Y=")) o.Y = std::atof(v);
        else if (const char* v = value("--e=")) o.e = std::atof(v);
        else if (const char* v = value("--mu=")) o.mu = std::atof(v);
        else if (const char* v = value("--level=")) o.level = std::atoi(v);
        else if (const char* v = value("--hEdge=")) o.hEdge = std::atof(v);
        else if (const char* v = value("--seed=")) o.seed = unsigned(std::atoi(v));
        else if (const char* v = value("--dt=")) o.dt = std::atof(v);
        else if (a.size() > 0 && a[0] != '-' && positional == 0)
        {
            o.N = std::atoi(a.c_str());
            ++positional;
        }
        else if (a.size() > 0 && a[0] != '-' && positional == 1)
        {
            o.maxTime = std::atof(a.c_str());
            ++positional;
        }
        else
        {
            throw coreError("Unknown argument '" + a + "'");
        }
    }
    if (o.N < 1 || !(o.maxTime > 0))
    {
        throw coreError("N must be >= 1 and maxTime > 0");
    }
    return o;
}


int run(const options& o)
{
    // The grain: an icosahedron of circumradius r, through an STL file
    const double r = 5e-3;
    const std::string stl =
    (
        std::filesystem::temp_directory_path()
      / ("demPileIcosahedron." + std::to_string(::getpid()) + ".stl")
    ).string();
    surfaceFileIO::write(stl, primitiveMeshes::icosphere(r, 0));
    const std::shared_ptr<const triangleMeshShape> grain(triangleMeshShape::fromFile(stl));
    std::remove(stl.c_str());
    const double edge = r/std::sin(2*M_PI/5);      // icosahedron edge length

    // Lattice and box
    const double spacing = 2*r + 0.5e-3;
    const int nSide = std::max(1, int(std::ceil(std::sqrt(o.N/4.0))));
    const double W = nSide*spacing + 2e-3;
    const int nLayers = (o.N + nSide*nSide - 1)/(nSide*nSide);

    contactMaterial m;
    m.name = "grain";
    m.youngsModulus = o.Y;
    m.poissonsRatio = 0.3;
    m.restitution = o.e;
    m.friction = o.mu;

    demSettings s;
    s.overlapMethod = "virtualMesh";
    s.contactLaw = "volume";
    s.overlap = overlapSettings{o.hEdge*edge, o.level};
    s.gravity = vec3(0, 0, -9.81);
    s.deltaT = o.dt;
    if (s.deltaT <= 0)
    {
        // The stiffest contact: two faces flat on each other, a linear
        // spring k = Y* A_face/l_c (l_c = R* = R/2 of like bodies) on m/2,
        // resolved by 16 steps per half period. The solver's own estimate
        // takes a face of the equivalent sphere's cross-section, pi R^2,
        // 4.7 times an icosahedron's face: 2.2 times shorter steps
        const double Ystar = pairMaterial::of(m, m).effectiveModulus;
        const double Rv = std::cbrt(3*grain->volume()/(4*M_PI));
        const double k = Ystar*(std::sqrt(3.0)/4*edge*edge)/(0.5*Rv);
        const double mass = 2500*grain->volume();
        s.deltaT = M_PI*std::sqrt(0.5*mass/k)/16;
    }
    demSolver dem({m}, s);

    auto addWall = [&](const std::string& name, const vec3& p, const vec3& n)
    {
        rigidBody w(name, std::make_shared<halfSpaceShape>(), 1.0, 0);
        w.pose = halfSpaceShape::poseOf(p, n);
        w.motion = motionType::fixed;
        dem.addBody(std::move(w), true);
    };
    addWall("floor", vec3::Zero(), vec3::UnitZ());
    addWall("xMin", vec3::Zero(), vec3::UnitX());
    addWall("xMax", vec3(W, 0, 0), -vec3::UnitX());
    addWall("yMin", vec3::Zero(), vec3::UnitY());
    addWall("yMax", vec3(0, W, 0), -vec3::UnitY());
    const int nWalls = int(dem.bodies().size());

    std::mt19937 gen(o.seed);
    std::normal_distribution<double> normal(0, 1);
    std::uniform_real_distribution<double> nudge(-0.2e-3, 0.2e-3);
    for (int i = 0; i < o.N; ++i)
    {
        const int layer = i/(nSide*nSide);
        const int k = i % (nSide*nSide);
        const vec3 c
        (
            1e-3 + (k % nSide + 0.5)*spacing + nudge(gen),
            1e-3 + (k/nSide + 0.5)*spacing + nudge(gen),
            r + 1e-3 + layer*spacing
        );
        quat q(normal(gen), normal(gen), normal(gen), normal(gen));
        q.normalize();
        rigidBody b("grain" + std::to_string(i), grain, 2500, 0);
        b.pose = grain->poseFromFilePlacement(q, c);
        dem.addBody(std::move(b));
    }

    std::printf("demPileBenchmark: %d icosahedra (STL, %zu triangles, r = %g mm, edge %.3g mm)\n",
        o.N, grain->nTriangles(), r*1e3, edge*1e3);
    std::printf("  box %.1f x %.1f mm, 5 plane walls; lattice %d x %d x %d\n",
        W*1e3, W*1e3, nSide, nSide, nLayers);
    std::printf("  Y = %g Pa, nu = 0.3, e = %g, mu = %g, density 2500; volume law;"
        " virtualMesh h = %.3g mm (edge/%g), level %d\n",
        o.Y, o.e, o.mu, s.overlap.h*1e3, 1/o.hEdge, o.level);
    std::printf("  time step %.3g s%s\n\n", s.deltaT, o.dt > 0 ? "" : " (16 per half period of a face-to-face contact)");
    std::printf("%9s %12s %12s %9s %10s %9s\n", "t [s]", "KE [J]", "KE/KEpeak", "steps", "contacts", "wall [s]");

    // KE below the threshold this long: longer than half the period of the
    // slowest swing seen (a grain perched on two contacts rocking about
    // them, ~0.2 s), whose KE dips through zero at its turning points
    const double restFor = 0.1;
    // At rest: 1e-6 of the peak, the grains' elastic vibration in their
    // contacts once settled; a pile still settling is orders of magnitude
    // above it (the history lines show the drop)
    const double ratioRest = 1e-6;
    double kePeak = 0, restSince = -1, nextPrint = 0;
    bool nan = false;
    // The bodies whose centre left the box, at any time checked (every
    // history line and the end)
    std::vector<bool> left(dem.bodies().size(), false);
    auto checkInside = [&]
    {
        for (size_t i = nWalls; i < dem.bodies().size(); ++i)
        {
            const vec3& x = dem.bodies()[i].pose.position();
            if (!(x.x() > 0 && x.x() < W && x.y() > 0 && x.y() < W && x.z() > 0))
            {
                left[i] = true;
            }
        }
    };
    const auto t0 = std::chrono::steady_clock::now();
    const std::clock_t c0 = std::clock();
    auto wall = [&]
    {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    };

    while (dem.time() < o.maxTime)
    {
        dem.step(s.deltaT);
        const double ke = dem.kineticEnergy();
        if (!std::isfinite(ke))
        {
            nan = true;
            break;
        }
        kePeak = std::max(kePeak, ke);
        const bool quiet = kePeak > 0 && ke < ratioRest*kePeak;
        if (!quiet)
        {
            restSince = -1;
        }
        else if (restSince < 0)
        {
            restSince = dem.time();
        }
        const bool atRest = quiet && dem.time() - restSince >= restFor;
        if (dem.time() >= nextPrint - 1e-12 || atRest)
        {
            std::printf("%9.4f %12.4e %12.4e %9ld %10zu %9.1f\n",
                dem.time(), ke, kePeak > 0 ? ke/kePeak : 0.0, dem.work().steps,
                dem.contacts().size(), wall());
            std::fflush(stdout);
            nextPrint += 0.05;
            checkInside();
        }
        if (atRest) break;
    }
    const double seconds = wall();
    const double cpu = double(std::clock() - c0)/CLOCKS_PER_SEC;

    // Final state
    const double keFinal = dem.kineticEnergy();
    checkInside();
    int outside = 0;
    for (size_t i = nWalls; i < dem.bodies().size(); ++i)
    {
        const rigidBody& b = dem.bodies()[i];
        const vec3& x = b.pose.position();
        if (!x.allFinite() || !b.velocity.allFinite() || !b.angularVelocity.allFinite())
        {
            nan = true;
        }
        if (left[i])
        {
            ++outside;
        }
    }
    if (!std::isfinite(keFinal)) nan = true;
    const double ratio = kePeak > 0 ? keFinal/kePeak : 0;

    const demSolver::counters& w = dem.work();
    std::printf("\nSummary\n");
    std::printf("  bodies                  %d (+ %d walls)\n", o.N, nWalls);
    std::printf("  simulated time          %.4f s\n", dem.time());
    std::printf("  DEM steps               %ld\n", w.steps);
    std::printf("  wall-clock              %.2f s (CPU %.2f s)\n", seconds, cpu);
    std::printf("  steps per second        %.1f (per CPU second %.1f)\n", w.steps/seconds, w.steps/cpu);
    std::printf("  pair evaluations        %ld (%.1f per step)\n",
        w.pairEvaluations, double(w.pairEvaluations)/std::max(1L, w.steps));
    std::printf("  contact time            %.2f s (%.0f %% of the run)\n",
        w.contactSeconds, 100*w.contactSeconds/seconds);
    std::printf("  per pair evaluation     %.2f us (%.1f queries)\n",
        1e6*w.contactSeconds/std::max(1L, w.pairEvaluations),
        double(w.queries)/std::max(1L, w.pairEvaluations));
    std::printf("  kinetic energy          peak %.4e J, final %.4e J, ratio %.3e\n",
        kePeak, keFinal, ratio);
    std::printf("  bodies outside the box  %d (at any history time or the end)\n", outside);
    std::printf("  NaN                     %s\n", nan ? "yes" : "no");

    if (!o.check)
    {
        return 0;
    }
    const bool rest = kePeak > 0 && keFinal < ratioRest*kePeak;
    std::printf("\n%s: at rest (KE_final/KE_peak = %.3e < %.0e)\n",
        rest ? "PASS" : "FAIL", ratio, ratioRest);
    std::printf("%s: no body left the box at any history time (%d did)\n", outside == 0 ? "PASS" : "FAIL", outside);
    std::printf("%s: no NaN\n", nan ? "FAIL" : "PASS");
    return rest && outside == 0 && !nan ? 0 : 1;
}

} // End anonymous namespace


int main(int argc, char* argv[])
{
    try
    {
        return run(parse(argc, argv));
    }
    catch (const std::exception& e)
    {
        std::fprintf(stderr, "demPileBenchmark: %s\n", e.what());
        return 2;
    }
}


// ************************************************************************* //
