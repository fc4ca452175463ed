/*---------------------------------------------------------------------------*\
Application
    projectionBenchmark

Description
    The projection's geometry for one body, without OpenFOAM, at random
    poses on a grid of cubic cells of d/n (d the volume-equivalent
    diameter), the cells of its box grown by a cell (the sharp surface's
    ring). Side by side in one run, for each body:

    A lumpy star (5,120 triangles; caseTemplates/arbitraryBodiesCollision;
    issue 20, item 5):
      - per cell: a signed-distance query at every centre and boxFraction::of
        (its own centre query, 8 pieces where the surface cuts the cell) in
        the body's box, as the projection did before issue 20;
      - narrow band: narrowBand::signedDistances (exact near the surface,
        far cells settled in groups) and boxFraction::fromQuery from the
        centre query, as the projection does for mesh bodies.
    Exit 1 if the two give different signs or distances or the narrow
    band's volume is less accurate.

    A convex pellet (the packed bed's 12-sided prism, 3 mm across the
    corners, 3 mm long, as immersedDEMPrism writes it) and a body of
    convex pieces (the ring of packedBed -rings, 4 x 2 x 4 mm, 24
    segments; issue 46, item 3):
      - narrow band: as above (the projection before issue 46);
      - planes: convexCells (classify by the face planes, lambda of a cut
        cell by clipping its box), the projection's path for these bodies.
    Prints the cost per covered cell (lambda > 0) and per cell of the
    grown box, the ratio, and the error of the sum of lambda V against the
    exact volume. Exit 1 if the planes' signs differ from the narrow
    band's, an exact distance differs by more than 1e-9 of d (round-off
    of two exact methods), or the planes' volume is not exact to 1e-9
    (the cells tile the box, and a clipped box is exact).

Usage
    projectionBenchmark [cellsPerDiameter=8] [poses=20] [star|prism|ring]
    (the last: that body only, e.g. for perf)
\*---------------------------------------------------------------------------*/

#include "narrowBand.H"
#include "boxFraction.H"
#include "convexCells.H"
#include "triangleMeshShape.H"
#include "primitiveMeshes.H"
#include "benchmarkTools.H"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <random>
#include <string>

using namespace immersedDEM;

namespace
{

//- The grid's cells meeting the body's box grown by a cell: lower
//  corners, centres, whether a cell meets the box itself
struct grid
{
    std::vector<vec3> lo, x;
    std::vector<bool> inBox;
};

grid gridAround(const axisAlignedBox& b, double h)
{
    grid g;
    const vec3 g0 = ((b.min.array() - h)/h).floor()*h;
    for (double px = g0.x(); px < b.max.x() + h; px += h)
        for (double py = g0.y(); py < b.max.y() + h; py += h)
            for (double pz = g0.z(); pz < b.max.z() + h; pz += h)
            {
                const vec3 l(px, py, pz);
                g.lo.push_back(l);
                g.x.push_back(l + vec3::Constant(0.5*h));
                g.inBox.push_back
                (
                    (l.array() + h >= b.min.array()).all() && (l.array() <= b.max.array()).all()
                );
            }
    return g;
}


bool starBenchmark(double n, int poses)
{
    std::string f = std::string(__FILE__);
    f = f.substr(0, f.rfind("validation/benchmarks/"))
      + "caseTemplates/arbitraryBodiesCollision/constant/triSurface/lumpyStar.stl";
    const std::unique_ptr<triangleMeshShape> star(triangleMeshShape::fromFile(f));
    const double d = std::cbrt(6*star->volume()/M_PI);
    const double h = d/n;
    std::printf("# lumpy star (%s), d = %.4g m, cells d/%g, %d poses\n", f.c_str(), d, n, poses);

    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1, 1);
    double tOld = 0, tNew = 0, vOld = 0, vNew = 0;
    long qOld = 0, qNew = 0, cells = 0, cut = 0;
    bool same = true;
    for (int k = 0; k < poses; ++k)
    {
        const vec3 axis(u(rng), u(rng), u(rng));
        const vec3 shift(h*u(rng), h*u(rng), h*u(rng));
        const bodyPose p = star->poseFromFilePlacement(bodyPose::axisAngle(axis, 3*u(rng)), shift);
        const grid g = gridAround(star->worldBox(p), h);
        const std::vector<vec3>& x = g.x;
        cells += long(x.size());
        const double V = h*h*h;

        // Per cell
        double t0 = benchmark::cpuSeconds();
        std::vector<double> phiOld(x.size());
        for (size_t i = 0; i < x.size(); ++i)
        {
            phiOld[i] = star->signedDistance(p, x[i]);
            ++qOld;
            if (g.inBox[i])
            {
                vOld += V*boxFraction::of(*star, p, g.lo[i], g.lo[i] + vec3::Constant(h), 1, &qOld);
            }
        }
        tOld += benchmark::cpuSeconds() - t0;

        // Narrow band
        t0 = benchmark::cpuSeconds();
        const std::vector<double> reach(x.size(), 1.0000001*h);
        const auto band = narrowBand::signedDistances(*star, p, x, reach, &qNew);
        for (size_t i = 0; i < x.size(); ++i)
        {
            if (!g.inBox[i]) continue;
            double fr = band[i].phi < 0 ? 1 : 0;
            if (band[i].exact)
            {
                fr = boxFraction::fromQuery(*star, p, g.lo[i], g.lo[i] + vec3::Constant(h), x[i], band[i].sp, &qNew);
                if (fr > 0 && fr < 1) ++cut;
            }
            vNew += V*fr;
        }
        tNew += benchmark::cpuSeconds() - t0;
        for (size_t i = 0; i < x.size(); ++i)
        {
            if ((band[i].phi < 0) != (phiOld[i] < 0)) same = false;
            if (band[i].exact && band[i].phi != phiOld[i]) same = false;
        }
    }
    std::printf("  %ld cells per body, %ld cut by the surface\n", cells/poses, cut/poses);
    const double eOld = vOld/poses/star->volume() - 1, eNew = vNew/poses/star->volume() - 1;
    std::printf("  per cell:    %8.3f ms per body, %7ld queries, sum lambda V / volume - 1: %+.5f\n",
        1e3*tOld/poses, qOld/poses, eOld);
    std::printf("  narrow band: %8.3f ms per body, %7ld queries, sum lambda V / volume - 1: %+.5f\n",
        1e3*tNew/poses, qNew/poses, eNew);
    std::printf("  time ratio per cell / narrow band: %.2f\n", tOld/tNew);
    const bool agree = same && std::abs(eNew) <= std::abs(eOld);
    std::printf("  %s\n", agree ? "same signs and distances, volume at least as accurate" : "DIFFERENT signs or distances, or a less accurate volume");
    return agree;
}


//- Narrow band against planes for a body convexCells serves
bool planesBenchmark(const triangleMeshShape& s, const char* what, double n, int poses)
{
    const double d = std::cbrt(6*s.volume()/M_PI);
    const double h = d/n;
    std::printf("# %s: %zu triangles, %s, d = %.4g m, cells d/%g, %d poses\n",
        what, s.nTriangles(), s.piecesNote().c_str(), d, n, poses);
    if (!convexCells::handles(s))
    {
        std::printf("  NOT served by convexCells\n");
        return false;
    }

    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1, 1);
    double tBand = 0, tPlanes = 0, vBand = 0, vPlanes = 0;
    long cells = 0, covered = 0, cut = 0, exactCells = 0;
    double worstPhi = 0, worstLambda = 0;
    bool sameSigns = true;
    // Two rounds, each method's smaller CPU (the machine is shared)
    for (int round = 0; round < 2; ++round)
    {
        double tb = 0, tp = 0, vb = 0, vp = 0;
        long nc = 0, ncov = 0, ncut = 0, nex = 0;
        for (int k = 0; k < poses; ++k)
        {
            const bodyPose p(h*vec3(u(rng), u(rng), u(rng)), benchmark::randomRotation(rng));
            const grid g = gridAround(s.worldBox(p), h);
            const std::vector<vec3>& x = g.x;
            nc += long(x.size());
            const double V = h*h*h;
            const std::vector<double> reach(x.size(), 1.0000001*h);

            // Narrow band and fromQuery: the projection for mesh bodies
            double t0 = benchmark::cpuSeconds();
            const auto band = narrowBand::signedDistances(s, p, x, reach);
            std::vector<double> fBand(x.size(), 0);
            for (size_t i = 0; i < x.size(); ++i)
            {
                if (!g.inBox[i]) continue;
                double fr = band[i].phi < 0 ? 1 : 0;
                if (band[i].exact)
                {
                    fr = boxFraction::fromQuery(s, p, g.lo[i], g.lo[i] + vec3::Constant(h), x[i], band[i].sp);
                }
                fBand[i] = fr;
                vb += V*fr;
            }
            tb += benchmark::cpuSeconds() - t0;

            // Planes
            t0 = benchmark::cpuSeconds();
            const convexCells planes(s, p);
            std::vector<narrowBand::value> byPlanes(x.size());
            std::vector<double> fPlanes(x.size(), 0);
            for (size_t i = 0; i < x.size(); ++i)
            {
                byPlanes[i] = planes.classify(x[i], reach[i]);
                if (!g.inBox[i]) continue;
                double fr = byPlanes[i].phi < 0 ? 1 : 0;
                if (byPlanes[i].exact)
                {
                    fr = planes.fraction(g.lo[i], g.lo[i] + vec3::Constant(h));
                }
                fPlanes[i] = fr;
                vp += V*fr;
            }
            tp += benchmark::cpuSeconds() - t0;

            for (size_t i = 0; i < x.size(); ++i)
            {
                if ((band[i].phi < 0) != (byPlanes[i].phi < 0)) sameSigns = false;
                if (band[i].exact && byPlanes[i].exact)
                {
                    worstPhi = std::max(worstPhi, std::abs(band[i].phi - byPlanes[i].phi)/d);
                    ++nex;
                }
                else if (band[i].exact != byPlanes[i].exact)
                {
                    // Settled by one, exact by the other: the settled one's
                    // bound must hold against the other's exact value
                    const narrowBand::value& e = band[i].exact ? band[i] : byPlanes[i];
                    const narrowBand::value& b = band[i].exact ? byPlanes[i] : band[i];
                    if (std::abs(b.phi) > std::abs(e.phi) + 1e-9*d)
                    {
                        sameSigns = false;
                    }
                }
                worstLambda = std::max(worstLambda, std::abs(fPlanes[i] - fBand[i]));
                if (fPlanes[i] > 0) ++ncov;
                if (fPlanes[i] > 0 && fPlanes[i] < 1) ++ncut;
            }
        }
        if (round == 0 || tb < tBand) tBand = tb;
        if (round == 0 || tp < tPlanes) tPlanes = tp;
        vBand = vb; vPlanes = vp;
        cells = nc; covered = ncov; cut = ncut; exactCells = nex;
    }
    const double eBand = vBand/poses/s.volume() - 1, ePlanes = vPlanes/poses/s.volume() - 1;
    std::printf("  per body: %ld cells of the grown box, %ld covered (lambda > 0), %ld cut, %ld with exact phi both ways\n",
        cells/poses, covered/poses, cut/poses, exactCells/poses);
    std::printf("  %-12s %12s %14s %16s %26s\n", "", "ms per body", "us per cell", "us per covered", "sum lambda V / volume - 1");
    std::printf("  %-12s %12.4f %14.4f %16.4f %+26.2e\n", "narrow band",
        1e3*tBand/poses, 1e6*tBand/cells, 1e6*tBand/covered, eBand);
    std::printf("  %-12s %12.4f %14.4f %16.4f %+26.2e\n", "planes",
        1e3*tPlanes/poses, 1e6*tPlanes/cells, 1e6*tPlanes/covered, ePlanes);
    std::printf("  time ratio narrow band / planes: %.2f\n", tBand/tPlanes);
    const bool ok = sameSigns && worstPhi <= 1e-9 && std::abs(ePlanes) <= 1e-9;
    std::printf("  largest difference of a cell's lambda, narrow band against planes: %.4f\n", worstLambda);
    std::printf("  largest difference of exact phi: %.2e d; %s\n", worstPhi,
        ok ? "same signs, planes' volume exact" : "DIFFERENT signs or distances, or an inexact volume");
    return ok;
}

} // End anonymous namespace


int main(int argc, char* argv[])
{
    const double n = argc > 1 ? std::atof(argv[1]) : 8;
    const int poses = argc > 2 ? std::atoi(argv[2]) : 20;
    const std::string only = argc > 3 ? argv[3] : "";
    std::printf("# projectionBenchmark: CPU seconds of this thread\n");
    bool ok = true;
    if (only.empty() || only == "star") ok = starBenchmark(n, poses);

    // The packed bed's pellet (immersedDEMPrism pellet.stl 3 3 12, in m)
    // and ring (immersedDEMPrism ring.stl 4 4 24 2)
    std::vector<Eigen::Vector2d> dodecagon;
    for (int i = 0; i < 12; ++i)
    {
        dodecagon.emplace_back(1.5e-3*std::cos(2*M_PI*i/12), 1.5e-3*std::sin(2*M_PI*i/12));
    }
    triangleSoup pellet = primitiveMeshes::extrudedPolygon(dodecagon, 3e-3);
    const triangleMeshShape prism(pellet, "pellet");
    if (only.empty() || only == "prism")
    {
        ok = planesBenchmark(prism, "12-sided prism (convex pellet)", n, poses) && ok;
    }
    const triangleMeshShape ring(primitiveMeshes::hollowCylinder(2e-3, 1e-3, 4e-3, 24), "ring");
    if (only.empty() || only == "ring")
    {
        ok = planesBenchmark(ring, "Raschig ring (convex pieces)", n, poses) && ok;
    }
    return ok ? 0 : 1;
}
