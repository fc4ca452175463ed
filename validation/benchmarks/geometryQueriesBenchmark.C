/*---------------------------------------------------------------------------*\
Application
    geometryQueriesBenchmark

Description
    Prints inside-queries and signed-distance queries per second for a
    10,000-triangle closed body (a torus, 100 x 50 quads) at random points
    of its (10% inflated) bounding box, and for the analytic sphere. A
    benchmark, not a test: it prints figures and checks nothing but that the
    two ways of classifying a point agree.

Usage
    geometryQueriesBenchmark [nPoints]      (default 200000)
\*---------------------------------------------------------------------------*/

#include "triangleMeshShape.H"
#include "sphereShape.H"
#include "primitiveMeshes.H"

#include <chrono>
#include <cstdlib>
#include <iostream>
#include <random>

using namespace immersedDEM;

namespace
{

template<class F>
double seconds(F&& f)
{
    const auto t0 = std::chrono::steady_clock::now();
    f();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::vector<vec3> randomPoints(const axisAlignedBox& b, size_t n)
{
    std::mt19937_64 rng(12345);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<vec3> pts(n);
    for (vec3& p : pts)
    {
        p = b.min + vec3(u(rng), u(rng), u(rng)).cwiseProduct(b.span());
    }
    return pts;
}

void run(const shape& s, const std::string& label, size_t n)
{
    const auto pts = randomPoints(s.localBox().inflated(0.1*s.boundingRadius()), n);
    size_t nIn = 0, nNeg = 0;
    const double tIn = seconds([&]{ for (const vec3& p : pts) nIn += s.inside(p); });
    const double tSd = seconds([&]{ for (const vec3& p : pts) nNeg += (s.signedDistance(p) < 0); });
    std::cout
        << label << ": " << n << " points, inside fraction " << double(nIn)/n << '\n'
        << "    inside queries/s           " << n/tIn << '\n'
        << "    signed-distance queries/s  " << n/tSd << '\n'
        << "    inside and sign agree      " << (nIn == nNeg ? "yes" : "NO") << '\n';
}

} // End anonymous namespace


int main(int argc, char* argv[])
{
    const size_t n = argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 200000;

    double tBuild = 0;
    std::unique_ptr<triangleMeshShape> torus;
    tBuild = seconds([&]
    {
        torus = std::make_unique<triangleMeshShape>
        (
            primitiveMeshes::torus(0.02, 0.008, 100, 50), "torus"
        );
    });
    std::cout << "torus: " << torus->nTriangles() << " triangles, checked and built in "
        << tBuild << " s\n";
    run(*torus, "triangleMesh torus (10k triangles)", n);
    run(sphereShape(0.01), "analytic sphere", n);
    return 0;
}
