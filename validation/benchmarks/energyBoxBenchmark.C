/*---------------------------------------------------------------------------*\
Application
    energyBoxBenchmark

Description
    Elastic energy of a 20-body gas (issue 19): 10 lumpy stars (the
    arbitraryBodiesCollision template's lumpyStar.stl, 5,120 triangles,
    scaled to a 10 mm volume-equivalent diameter) and 10 cubes (8 mm) in a
    closed box of six planes (60 mm), restitution 1, friction 0, no
    gravity, rubber (Y 1e6), virtualMesh at h = d/10, level 2, automatic
    step at stepsPerContact 30, random positions, velocities (0.5 m/s) and
    spins. Runs the given laws one after the other from the same start and
    writes, per law, the total kinetic energy over its start value at every
    contact-free sub-step (energyBox_<law>.dat: step, time, E/E0 - 1), and
    prints the worst and final drift. With 20 bodies some pair is nearly
    always touching, so for the potential law the total energy (kinetic +
    the contacts' stored w(V)) is written at every sub-step; the volume law
    has no stored energy and only its contact-free sub-steps are written. validation/studies/energyBox plots
    them. A benchmark, not a test.

Usage
    energyBoxBenchmark [--steps=n] [--laws=potential,volume] [--stl=file]
                       [--stepsPerContact=n] (default 30) [--octreeOnly]
                       [--level=n] (default 2)
                       [--reuseTolerancePotential=x] (demSettings' default)
                       [--check]
    --check: exit 1 unless the potential law's total energy stays within
    0.1% of its start at every step and at least half the steps have a
    contact (the suite's dem.energyBox, 1e4 steps)
    --octreeOnly: convex pairs on the octree too (overlapSettings::
    convexExact off), as before the exact convex path
\*---------------------------------------------------------------------------*/

#include "benchmarkTools.H"
#include "demSolver.H"
#include "halfSpaceShape.H"
#include "triangleMeshShape.H"
#include "primitiveMeshes.H"
#include "pairFilter.H"
#include "coreError.H"

#include <map>
#include "potentialContactLaw.H"

#include <cmath>
#include <cstdio>
#include <random>
#include <sstream>
#include <string>
#include <time.h>

using namespace immersedDEM;

namespace
{

using benchmark::cpuSeconds;
using benchmark::randomRotation;

} // End anonymous namespace


int main(int argc, char* argv[])
{
    long steps = 100000;
    std::string laws = "potential,volume";
    double stepsPerContact = 30;
    bool convexExact = true;
    double reuseTolerancePotential = demSettings().reuseTolerancePotential;
    int level = 2;
    bool check = false;
    bool failed = false;
    std::string stl = std::string(__FILE__);
    stl = stl.substr(0, stl.rfind("validation/benchmarks/"))
        + "caseTemplates/arbitraryBodiesCollision/constant/triSurface/lumpyStar.stl";
    for (int i = 1; i < argc; ++i)
    {
        const std::string a = argv[i];
        if (a.rfind("--steps=", 0) == 0) steps = std::atol(a.c_str() + 8);
        else if (a.rfind("--stepsPerContact=", 0) == 0) stepsPerContact = std::atof(a.c_str() + 18);
        else if (a == "--octreeOnly") convexExact = false;
        else if (a.rfind("--laws=", 0) == 0) laws = a.substr(7);
        else if (a.rfind("--stl=", 0) == 0) stl = a.substr(6);
        else if (a.rfind("--reuseTolerancePotential=", 0) == 0) reuseTolerancePotential = std::atof(a.c_str() + 26);
        else if (a.rfind("--level=", 0) == 0) level = std::atoi(a.c_str() + 8);
        else if (a == "--check") check = true;
        else
        {
            std::fprintf(stderr, "Unknown argument %s\n", a.c_str());
            return 1;
        }
    }
    try
    {
        // Read again at the scale that makes it 10 mm across (in the
        // file's frame, where a non-convex pellet is decomposed into
        // convex pieces)
        const double d0 = 2*std::cbrt(3*triangleMeshShape::fromFile(stl)->volume()/(4*M_PI));
        std::shared_ptr<const triangleMeshShape> star = triangleMeshShape::fromFile(stl, 0.01/d0);
        std::printf("%s: %s\n", stl.c_str(), star->piecesNote().c_str());
        auto cube = std::make_shared<triangleMeshShape>(primitiveMeshes::box(vec3::Constant(0.004)), "cube");
        const double d = 0.01, L = 0.03;

        std::stringstream ls(laws);
        std::string law;
        while (std::getline(ls, law, ','))
        {
            contactMaterial rubber{"rubber", 1e6, 0.45, 1.0, 0};
            demSettings s;
            s.contactLaw = law;
            s.overlap = {d/10, level};
            s.reuseTolerancePotential = reuseTolerancePotential;
            s.stepsPerContact = stepsPerContact;
            s.overlap.convexExact = convexExact;
            s.referenceSpeed = 1;
            demSolver dem({rubber}, s);
            for (int k = 0; k < 6; ++k)
            {
                const vec3 n = (k%2 ? 1.0 : -1.0)*vec3::Unit(k/2);
                rigidBody w("wall" + std::to_string(k), std::make_shared<halfSpaceShape>(), 1);
                w.pose = halfSpaceShape::poseOf(-L*n, n);
                w.motion = motionType::fixed;
                dem.addBody(w, true);
            }
            // On a 3 x 3 x 3 lattice (20 of its 27 sites), 18 mm apart:
            // no two bodies (bounding radius < 8 mm) touch at the start
            std::mt19937 g(19);
            std::uniform_real_distribution<double> u(-1, 1);
            int placed = 0;
            for (int i = 0; i < 27 && placed < 20; ++i)
            {
                if (i%4 == 3 && 27 - i > 20 - placed) continue;
                const vec3 x(-0.018 + 0.018*(i%3), -0.018 + 0.018*((i/3)%3), -0.018 + 0.018*(i/9));
                const bool isStar = placed%2 == 0;
                rigidBody b((isStar ? "star" : "cube") + std::to_string(placed), isStar ? star : cube, 1000);
                b.pose = bodyPose(x, randomRotation(g));
                b.velocity = 0.5*vec3(u(g), u(g), u(g)).normalized();
                b.angularVelocity = 30*vec3(u(g), u(g), u(g));
                dem.addBody(b);
                ++placed;
            }
            // The stored energy of the potential law's contacts: w of each
            // pair's whole overlap volume (all its regions)
            const pairMaterial pm = pairMaterial::of(rubber, rubber);
            auto stored = [&]
            {
                double W = 0;
                if (law != "potential") return W;
                std::map<std::pair<int, int>, double> pairV;
                for (const contactRecord& c : dem.contacts()) pairV[{c.a, c.b}] += c.region.volume;
                for (const auto& e : pairV)
                {
                    const rigidBody& A = dem.bodies()[e.first.first];
                    const rigidBody& B = dem.bodies()[e.first.second];
                    const bool wall = A.geometry->shapeKind() == shape::kind::halfSpace;
                    const double Ra = A.equivalentRadius(), Rb = B.equivalentRadius();
                    const double Rs = wall ? Rb : Ra*Rb/(Ra + Rb);
                    const double Af = std::min(A.geometry->largestFlatFace(), B.geometry->largestFlatFace());
                    W += potentialContactLaw::energy
                    (
                        e.second, pm.effectiveModulus, Rs, Rs,
                        potentialContactLaw::referenceVolume(Af, Rs)
                    );
                }
                return W;
            };
            const double E0 = dem.kineticEnergy();
            const double dt = dem.timeStep();
            FILE* out = std::fopen(("energyBox_" + law + ".dat").c_str(), "w");
            std::fprintf(out, "# %s law, 10 lumpy stars + 10 cubes, e = 1, dt %g s\n# step time E/E0-1\n", law.c_str(), dt);
            double worst = 0, last = 0;
            long contactSteps = 0;
            const double c0 = cpuSeconds();
            for (long n = 0; n < steps; ++n)
            {
                dem.step(dt);
                if (!dem.contacts().empty())
                {
                    ++contactSteps;
                    if (law != "potential") continue;
                }
                // Potential law: kinetic + stored energy at every step
                last = (dem.kineticEnergy() + stored())/E0 - 1;
                worst = std::max(worst, std::abs(last));
                if (n%20 == 0) { std::fprintf(out, "%ld %.6e %.6e\n", n, dem.time(), last); std::fflush(out); }
            }
            std::fclose(out);
            std::printf("%-10s dt %.3g s, %ld steps (%ld with contact), worst drift %.3e, final %.3e, CPU %.0f s\n",
                law.c_str(), dt, steps, contactSteps, worst, last, cpuSeconds() - c0);
            std::fflush(stdout);
            // The potential law's total energy within 0.1% (issue 19's
            // target; measured 0.086% worst over 1e5 steps, and the
            // integrator's in-contact swing about the conserved energy is
            // +-2e-4: studies/energyBox), with contacts at most steps (a
            // box where little touches tests nothing)
            if (check && law == "potential" && (!(worst < 1e-3) || contactSteps < steps/2))
            {
                std::printf("FAIL: potential law, worst drift %.3e (limit 1e-3), %ld of %ld steps with contact (at least half)\n",
                    worst, contactSteps, steps);
                failed = true;
            }
        }
    }
    catch (const coreError& e)
    {
        std::fprintf(stderr, "Error: %s\n", e.what());
        return 1;
    }
    return failed ? 1 : 0;
}
