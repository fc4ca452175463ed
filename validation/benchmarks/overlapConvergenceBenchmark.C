/*---------------------------------------------------------------------------*\
Application
    overlapConvergenceBenchmark

Description
    Convergence and cost of the contact-geometry engines with the level L of
    the virtual mesh (L = 0..5, base cell h): the adaptive "virtualMesh",
    the paper's Algorithm 1 "uniform" (n^3 sub-volumes per contact cell) and
    the paper's original model "cells" (volume fractions on the cells; it
    ignores L). For each: the overlap-volume error in %, the normal error in
    degrees (per region, against the reference region nearest in contact
    point; the largest), the number of regions, the queries (inside or
    distance, one per body per point) and the seconds per evaluation
    (median of 3 runs). The virtual mesh is measured without its exact
    shortcuts (convexExact off), which would answer the spheres with the
    lens itself.

    Pairs:
      (a) two spheres R = 5 mm, h = d/20 = 0.5 mm, overlapping by 2% of d
          along a skew line; reference: the analytic lens;
      (b) a non-convex pair: two triangle-mesh tori (R = 4 mm, r = 1.5 mm,
          64 x 32 quads) in perpendicular planes, linked, whose tubes cross
          at two places (one through the other's hole), 0.4 mm deep, the
          pair turned and moved off the lattice;
          reference: the "exact" engine (CGAL corefinement of the same
          meshes) when it is available and succeeds, else virtualMesh at
          L = 6 (the output says which).

    Then the query ratio uniform/virtualMesh at L = 4 and the growth factor
    of virtualMesh's queries from one level to the next. A uniform run
    expected to take more than 30 s (8 times the previous level) is skipped
    with a note, and run once instead of 3 times when 3 runs would take
    more than 30 s. A benchmark, not a test: it checks nothing.

Usage
    overlapConvergenceBenchmark
\*---------------------------------------------------------------------------*/

#include "overlapEngine.H"
#include "sphereOverlap.H"
#include "sphereShape.H"
#include "triangleMeshShape.H"
#include "primitiveMeshes.H"
#include "coreError.H"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <vector>

using namespace immersedDEM;

namespace
{

const int maxLevel = 5;
const double timeLimit = 30;    // seconds, for all runs of one uniform level

struct pairCase
{
    std::string title;
    const shape* A;
    bodyPose pA;
    const shape* B;
    bodyPose pB;
    double h;
    contactGeometry reference;
    std::string referenceName;
};


double angleDeg(const vec3& a, const vec3& b)
{
    return std::acos(std::max(-1.0, std::min(1.0, a.normalized().dot(b.normalized()))))*180/M_PI;
}


// Largest normal error over the reference regions, each against the
// engine's region nearest in contact point
double normalError(const contactGeometry& g, const contactGeometry& ref)
{
    if (g.regions.empty()) return NAN;
    double worst = 0;
    for (const contactRegion& r : ref.regions)
    {
        const contactRegion* best = &g.regions[0];
        for (const contactRegion& x : g.regions)
        {
            if ((x.point - r.point).norm() < (best->point - r.point).norm()) best = &x;
        }
        worst = std::max(worst, angleDeg(best->normal, r.normal));
    }
    return worst;
}


struct timed
{
    contactGeometry g;
    double seconds = 0;
    int runs = 0;
};


timed run(const overlapEngine& e, const pairCase& c, int L, int runs)
{
    timed t;
    std::vector<double> s;
    for (int i = 0; i < runs; ++i)
    {
        const auto t0 = std::chrono::steady_clock::now();
        // the octree itself (virtualMesh answers two spheres with the
        // lens unless its exact shortcuts are off)
        overlapSettings o;
        o.h = c.h;
        o.level = L;
        o.convexExact = false;
        t.g = e.evaluate(*c.A, c.pA, *c.B, c.pB, o);
        s.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    std::sort(s.begin(), s.end());
    t.seconds = s[s.size()/2];
    t.runs = runs;
    return t;
}


void table(const pairCase& c)
{
    std::printf("\n%s\n", c.title.c_str());
    std::printf
    (
        "reference: %s, volume %.6g mm^3, %zu region(s)\n",
        c.referenceName.c_str(), c.reference.volume()*1e9, c.reference.regions.size()
    );
    std::printf
    (
        "%-12s %2s %12s %12s %8s %12s %12s  %s\n",
        "method", "L", "volume err %", "normal deg", "regions", "queries", "seconds", "note"
    );

    std::map<std::string, std::map<int, long>> queries;
    for (const std::string method : {"virtualMesh", "uniform", "cells"})
    {
        const auto engine = overlapEngine::New(method);
        double previous = 0;
        for (int L = 0; L <= maxLevel; ++L)
        {
            int runs = 3;
            std::string note;
            if (method == "uniform" && L > 0)
            {
                const double expected = 8*previous;
                if (expected > timeLimit)
                {
                    std::printf
                    (
                        "%-12s %2d   skipped: expected %.0f s per run (8 x level %d)\n",
                        method.c_str(), L, expected, L - 1
                    );
                    break;
                }
                if (3*expected > timeLimit)
                {
                    runs = 1;
                    note = "1 run";
                }
            }
            const timed t = run(*engine, c, L, runs);
            previous = t.seconds;
            queries[method][L] = t.g.queries;
            std::printf
            (
                "%-12s %2d %12.4f %12.4f %8zu %12ld %12.6f  %s\n",
                method.c_str(), L,
                100*(t.g.volume()/c.reference.volume() - 1),
                normalError(t.g, c.reference),
                t.g.regions.size(), t.g.queries, t.seconds, note.c_str()
            );
        }
    }

    const auto& vm = queries["virtualMesh"];
    const auto& un = queries["uniform"];
    if (un.count(4) && vm.count(4) && vm.at(4) > 0)
    {
        std::printf
        (
            "queries(uniform)/queries(virtualMesh) at L = 4: %.2f (%ld / %ld)\n",
            double(un.at(4))/vm.at(4), un.at(4), vm.at(4)
        );
    }
    std::printf("virtualMesh query growth per level:");
    for (int L = 1; L <= maxLevel; ++L)
    {
        if (vm.count(L) && vm.count(L - 1) && vm.at(L - 1) > 0)
        {
            std::printf("  %d->%d: %.2f", L - 1, L, double(vm.at(L))/vm.at(L - 1));
        }
    }
    std::printf("\n");
}

} // End anonymous namespace


int main()
{
    std::cout << "overlapConvergenceBenchmark: error and cost against the level L"
        << " (h fixed; seconds are the median of 3 runs)\n";

    // (a) sphere-sphere, 2% of d along a skew line (as the unit tests)
    const double R = 0.005, d = 2*R, h = d/20;
    const sphereShape sphere(R);
    const vec3 c2(0.0013, 0.0021, 0.0007);
    const vec3 c1 = c2 - (d - 0.02*d)*vec3(1, 2, 3).normalized();
    pairCase a
    {
        "(a) sphere-sphere, R = 5 mm, h = d/20 = 0.5 mm, overlap 2% of d",
        &sphere, bodyPose(c1, quat::Identity()), &sphere, bodyPose(c2, quat::Identity()), h,
        sphereOverlap::lens(c1, R, c2, R), "analytic lens"
    };
    table(a);

    // (b) two tori in perpendicular planes: A about z at the origin, B about
    // y centred at (c, 0, 0). B's centre line passes A's at the distance c
    // where it crosses z = 0 (at x = c + Rt, outside A's ring, and at
    // x = c - Rt, through A's hole) and farther elsewhere: two crossings of
    // the tubes, 2 rt - c = depth deep. The pair is turned and moved as a
    // whole, off the lattice.
    const double Rt = 0.004, rt = 0.0015, depth = 0.0004;
    const triangleMeshShape torusA(primitiveMeshes::torus(Rt, rt, 64, 32), "torusA");
    const triangleMeshShape torusB(primitiveMeshes::torus(Rt, rt, 64, 32), "torusB");
    const bodyPose M(vec3(0.0011, -0.0007, 0.0003), bodyPose::axisAngle(vec3(1, -2, 0.5), 1.1));
    pairCase b
    {
        "(b) two crossing tori (non-convex, two regions), R = 4 mm, r = 1.5 mm, "
        "depth 0.4 mm, h = 0.5 mm",
        &torusA, M*torusA.poseFromFilePlacement(quat::Identity(), vec3::Zero()),
        &torusB,
        M*torusB.poseFromFilePlacement
        (
            bodyPose::axisAngle(vec3(1, 0, 0), M_PI/2), vec3(2*rt - depth, 0, 0)
        ),
        h, contactGeometry(), ""
    };
    try
    {
        const auto t0 = std::chrono::steady_clock::now();
        b.reference = overlapEngine::New("exact")->evaluate(*b.A, b.pA, *b.B, b.pB, {h, 0});
        const double s =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        b.referenceName = "exact engine (CGAL corefinement), " + std::to_string(s) + " s";
    }
    catch (const coreError& e)
    {
        std::cout << "exact engine not usable (" << e.what() << ")\n";
    }
    if (b.reference.regions.empty())
    {
        b.reference = overlapEngine::New("virtualMesh")->evaluate(*b.A, b.pA, *b.B, b.pB, {h, 6});
        b.referenceName = "virtualMesh at L = 6 (no exact engine)";
    }
    table(b);
    return 0;
}
