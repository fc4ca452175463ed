/*---------------------------------------------------------------------------*\
Application
    projectionBenchmark

Description
    The projection's geometry for one body (issue 20, item 5), without
    OpenFOAM: a lumpy star (5,120 triangles; caseTemplates/
    arbitraryBodiesCollision) at random poses on a grid of cubic cells of
    d/n, the cells of its box grown by a cell (the sharp surface's ring).
    Side by side in one run:
      - per cell: a signed-distance query at every centre and boxFraction::of
        (its own centre query, 8 pieces where the surface cuts the cell) in
        the body's box, as the projection did;
      - narrow band: narrowBand::signedDistances (exact near the surface,
        far cells settled in groups) and boxFraction::fromQuery from the
        centre query (the surface's second-order model; pieces only near
        creases), as it does now.
    Prints milliseconds and queries per body and the error of the sum of
    lambda V against the exact volume; checks that the two give the same
    signs and distances and that the new volume is at least as accurate
    (exit 1 if not).

Usage
    projectionBenchmark [cellsPerDiameter=8] [poses=20]
\*---------------------------------------------------------------------------*/

#include "narrowBand.H"
#include "boxFraction.H"
#include "triangleMeshShape.H"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <random>
#include <string>

using namespace immersedDEM;

namespace
{


double seconds()
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

} // End anonymous namespace


int main(int argc, char* argv[])
{
    const double n = argc > 1 ? std::atof(argv[1]) : 8;
    const int poses = argc > 2 ? std::atoi(argv[2]) : 20;
    std::string f = std::string(__FILE__);
    f = f.substr(0, f.rfind("validation/benchmarks/"))
      + "caseTemplates/arbitraryBodiesCollision/constant/triSurface/lumpyStar.stl";
    const std::unique_ptr<triangleMeshShape> star(triangleMeshShape::fromFile(f));
    const double d = std::cbrt(6*star->volume()/M_PI);
    const double h = d/n;
    std::printf("# projectionBenchmark: lumpy star (%s), d = %.4g m, cells d/%g, %d poses\n", f.c_str(), d, n, poses);

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
        const axisAlignedBox b = star->worldBox(p);
        // The grid's cells meeting the box grown by a cell
        std::vector<vec3> lo, x;
        std::vector<bool> inBox;
        const vec3 g0 = ((b.min.array() - h)/h).floor()*h;
        for (double px = g0.x(); px < b.max.x() + h; px += h)
            for (double py = g0.y(); py < b.max.y() + h; py += h)
                for (double pz = g0.z(); pz < b.max.z() + h; pz += h)
                {
                    const vec3 l(px, py, pz);
                    lo.push_back(l);
                    x.push_back(l + vec3::Constant(0.5*h));
                    inBox.push_back
                    (
                        (l.array() + h >= b.min.array()).all() && (l.array() <= b.max.array()).all()
                    );
                }
        cells += long(x.size());
        const double V = h*h*h;

        // Per cell
        double t0 = seconds();
        std::vector<double> phiOld(x.size());
        for (size_t i = 0; i < x.size(); ++i)
        {
            phiOld[i] = star->signedDistance(p, x[i]);
            ++qOld;
            if (inBox[i])
            {
                vOld += V*boxFraction::of(*star, p, lo[i], lo[i] + vec3::Constant(h), 1, &qOld);
            }
        }
        tOld += seconds() - t0;

        // Narrow band
        t0 = seconds();
        const std::vector<double> reach(x.size(), 1.0000001*h);
        const auto band = narrowBand::signedDistances(*star, p, x, reach, &qNew);
        for (size_t i = 0; i < x.size(); ++i)
        {
            if (!inBox[i]) continue;
            double fr = band[i].phi < 0 ? 1 : 0;
            if (band[i].exact)
            {
                fr = boxFraction::fromQuery(*star, p, lo[i], lo[i] + vec3::Constant(h), x[i], band[i].sp, &qNew);
                if (fr > 0 && fr < 1) ++cut;
            }
            vNew += V*fr;
        }
        tNew += seconds() - t0;
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
    return agree ? 0 : 1;
}
