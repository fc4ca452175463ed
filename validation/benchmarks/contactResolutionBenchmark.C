// The contact resolution chosen from a volume tolerance (issue 20, item
// 6): for each pair of the templates' non-convex shapes (and spheres, and
// a wall), the resolution contactResolution::calibrate chooses, the time
// it takes, its error on the calibration's six poses, and its error on
// eighteen other poses (contactResolution::posesOf sets 1-3, 0.7 and 0.4
// of the depth) against the same reference, with the former default
// (d/20, level 4) beside it. Each case is a tolerance and a depth over d
// (glass at 0.1 m/s goes about 1e-4 d deep, soft bodies or fast ones
// 1e-2 d).
//
//   contactResolutionBenchmark [tolerance depth/d ...]
//                                   (default 0.005 1e-4 0.005 1e-2 0.02 1e-2)

#include "contactResolution.H"
#include "triangleMeshShape.H"
#include "sphereShape.H"
#include "halfSpaceShape.H"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

using namespace immersedDEM;

namespace
{

std::string templateFile(const std::string& name)
{
    std::string f = std::string(__FILE__);
    f = f.substr(0, f.rfind("validation/benchmarks/"))
      + "caseTemplates/arbitraryBodiesCollision/constant/triSurface/" + name;
    return f;
}

double diameter(const shape& s)
{
    return 2*std::cbrt(3*s.volume()/(4*M_PI));
}

} // End namespace


int main(int argc, char** argv)
{
    std::vector<std::pair<double, double>> cases;
    for (int i = 1; i + 1 < argc; i += 2) cases.push_back({std::atof(argv[i]), std::atof(argv[i + 1])});
    if (cases.empty()) cases = {{0.005, 1e-4}, {0.005, 1e-2}, {0.02, 1e-2}};

    const std::shared_ptr<const shape> star(triangleMeshShape::fromFile(templateFile("lumpyStar.stl")));
    const std::shared_ptr<const shape> rod(triangleMeshShape::fromFile(templateFile("bentRod.stl")));
    const std::shared_ptr<const shape> ball = std::make_shared<sphereShape>(0.005);
    const std::shared_ptr<const shape> wall = std::make_shared<halfSpaceShape>();

    struct pair
    {
        const char* name;
        const shape* A;
        const shape* B;
    };
    const std::vector<pair> pairs =
    {
        {"star - star", star.get(), star.get()},
        {"wall - star", wall.get(), star.get()},
        {"star - sphere", star.get(), ball.get()},
        {"rod - rod", rod.get(), rod.get()},
        {"wall - rod", wall.get(), rod.get()},
        {"rod - star", rod.get(), star.get()},
        {"sphere - sphere", ball.get(), ball.get()},
        {"wall - sphere", wall.get(), ball.get()}
    };

    std::printf
    (
        "contactResolutionBenchmark: the resolution chosen per pair type from a volume\n"
        "tolerance; errors are the largest relative volume error against the reference\n"
        "(exact for two meshes, the lens for two spheres, else level 7) over the\n"
        "calibration's 6 poses (depth and depth/4 deep; calib) and 18 other poses\n"
        "(0.7 and 0.4 of the depth; check); 'former' is d/20, level 4, the default\n"
        "before; queries per calibration pose\n\n"
    );
    std::printf
    (
        "%-16s %7s %8s %6s %8s %9s %9s %9s %9s %9s %8s %9s\n",
        "pair", "tol %", "depth/d", "level", "leaf", "calib %", "check %", "former %", "queries",
        "former q", "ratio", "calib [s]"
    );
    for (const auto& c : cases)
    {
        const double tolerance = c.first;
        for (const pair& p : pairs)
        {
            const double d =
                p.A == wall.get() ? diameter(*p.B) : std::min(diameter(*p.A), diameter(*p.B));
            overlapSettings base;
            const auto t0 = std::chrono::steady_clock::now();
            const double depth = c.second*d;
            const contactResolution r =
                contactResolution::calibrate(*p.A, *p.B, d, depth, base, tolerance);
            const double seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

            std::vector<contactResolution::posePair> check;
            for (int set = 1; set <= 3; ++set)
            {
                for (const auto& q : contactResolution::posesOf(*p.A, *p.B, depth, set)) check.push_back(q);
            }
            const overlapSettings chosen = r.settingsFor(base, d);
            overlapSettings former = base;
            former.h = d/20;
            former.level = 4;
            const double checkError = contactResolution::largestError(*p.A, *p.B, d, check, chosen);
            const double formerError = contactResolution::largestError(*p.A, *p.B, d, check, former);
            std::printf
            (
                "%-16s %7.2f %8.0e %6d %8s %9.3f %9.3f %9.3f %9ld %9ld %8.2f %9.3f\n",
                p.name, 100*tolerance, c.second, r.level,
                ("d/" + std::to_string(int(r.cellsPerDiameter*double(1L << r.level)))).c_str(),
                100*r.error, 100*checkError, 100*formerError,
                r.queries/6, r.defaultQueries/6,
                r.queries > 0 ? double(r.defaultQueries)/double(r.queries) : 1.0, seconds
            );
        }
    }
    return 0;
}
