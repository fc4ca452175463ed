/*---------------------------------------------------------------------------*\
Application
    immersedDEMOverlap

Description
    Evaluates the contact geometry of one pair of bodies and prints one JSON
    object on stdout:
      {"method":..., "level":..., "h":..., "regions":[{"volume":...,
       "point":[x,y,z], "normal":[x,y,z], "area":...}, ...],
       "volume": <sum>, "queries": <count>, "seconds": <evaluation only>}

Usage
    immersedDEMOverlap -A <body> [-poseA tx ty tz ax ay az angle]
                       -B <body> [-poseB tx ty tz ax ay az angle]
                       [-method virtualMesh|sphere] [-h H] [-level L]
                       [-repeat N]

    <body> is an STL/OBJ file or sphere:<radius>. A pose is applied to the
    file's coordinates as x' = R x + t: translation t, then the rotation axis
    and angle [rad] of R (for a sphere, t is the centre). Defaults: no
    rotation or translation, method virtualMesh, and the solver's defaults
    (overlapSettings in contactGeometry.H): level 4, h = 1/20 of the smaller
    body's volume-equivalent diameter. -repeat N times N
    evaluations and reports the median.
    Bad input: a message on stderr and exit code 1.
\*---------------------------------------------------------------------------*/

#include "overlapEngine.H"
#include "sphereShape.H"
#include "triangleMeshShape.H"
#include "coreError.H"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <string>

using namespace immersedDEM;

namespace
{

[[noreturn]] void usage(const std::string& what)
{
    std::cerr
        << "immersedDEMOverlap: " << what << "\n"
        << "Usage: immersedDEMOverlap -A <file|sphere:R> [-poseA tx ty tz ax ay az angle]\n"
        << "         -B <file|sphere:R> [-poseB tx ty tz ax ay az angle]\n"
        << "         [-method NAME] [-h H] [-level L] [-repeat N]\n";
    std::exit(1);
}

double number(const char* s, const std::string& option)
{
    char* end = nullptr;
    const double v = std::strtod(s, &end);
    if (end == s || *end != '\0' || !std::isfinite(v))
    {
        usage(option + ": '" + s + "' is not a number");
    }
    return v;
}

std::unique_ptr<shape> readBody(const std::string& spec)
{
    if (spec.rfind("sphere:", 0) == 0)
    {
        return std::make_unique<sphereShape>(number(spec.c_str() + 7, "sphere radius"));
    }
    return triangleMeshShape::fromFile(spec);
}

void json(std::ostream& os, const vec3& v)
{
    os << '[' << v.x() << ", " << v.y() << ", " << v.z() << ']';
}

} // End anonymous namespace


int main(int argc, char* argv[])
{
    std::string specA, specB, method = "virtualMesh";
    double poseA[7] = {0, 0, 0, 0, 0, 1, 0}, poseB[7] = {0, 0, 0, 0, 0, 1, 0};
    double h = -1;
    int level = overlapSettings::defaultLevel, repeat = 1;

    for (int i = 1; i < argc; ++i)
    {
        const std::string a = argv[i];
        auto need = [&](int n)
        {
            if (i + n >= argc) usage(a + " needs " + std::to_string(n) + " value(s)");
        };
        if (a == "-A" || a == "-B")
        {
            need(1);
            (a == "-A" ? specA : specB) = argv[++i];
        }
        else if (a == "-poseA" || a == "-poseB")
        {
            need(7);
            double* p = a == "-poseA" ? poseA : poseB;
            for (int k = 0; k < 7; ++k) p[k] = number(argv[++i], a);
        }
        else if (a == "-method") { need(1); method = argv[++i]; }
        else if (a == "-h")
        {
            need(1);
            h = number(argv[++i], a);
            if (!(h > 0)) usage("-h must be positive");
        }
        else if (a == "-level")
        {
            need(1);
            level = int(number(argv[++i], a));
            if (level < 0 || level > overlapSettings::maxLevel)
            {
                usage("-level must be in [0, " + std::to_string(overlapSettings::maxLevel) + "]");
            }
        }
        else if (a == "-repeat")
        {
            need(1);
            repeat = int(number(argv[++i], a));
            if (repeat < 1) usage("-repeat must be at least 1");
        }
        else if (a == "-help" || a == "--help") usage("help");
        else usage("unknown option '" + a + "'");
    }
    if (specA.empty() || specB.empty()) usage("both -A and -B are needed");

    try
    {
        const auto engine = overlapEngine::New(method);
        const auto A = readBody(specA);
        const auto B = readBody(specB);
        auto place = [](const shape& s, const double* p)
        {
            return s.poseFromFilePlacement
            (
                bodyPose::axisAngle(vec3(p[3], p[4], p[5]), p[6]), vec3(p[0], p[1], p[2])
            );
        };
        const bodyPose pA = place(*A, poseA), pB = place(*B, poseB);
        if (h < 0)
        {
            // The solver's default: from the smaller volume-equivalent diameter
            const double d = std::cbrt(6/M_PI*std::min(A->volume(), B->volume()));
            h = overlapSettings::defaultCellSize(d);
        }
        const overlapSettings settings{h, level};

        contactGeometry g;
        std::vector<double> times;
        for (int r = 0; r < repeat; ++r)
        {
            const auto t0 = std::chrono::steady_clock::now();
            g = engine->evaluate(*A, pA, *B, pB, settings);
            times.push_back
            (
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()
            );
        }
        std::sort(times.begin(), times.end());

        std::cout.precision(12);
        std::cout << "{\"method\": \"" << method << "\", \"level\": " << level
            << ", \"h\": " << h << ", \"regions\": [";
        for (size_t k = 0; k < g.regions.size(); ++k)
        {
            const contactRegion& r = g.regions[k];
            std::cout << (k ? ", " : "") << "{\"volume\": " << r.volume << ", \"point\": ";
            json(std::cout, r.point);
            std::cout << ", \"normal\": ";
            json(std::cout, r.normal);
            std::cout << ", \"area\": " << r.area << '}';
        }
        std::cout << "], \"volume\": " << g.volume() << ", \"queries\": " << g.queries
            << ", \"seconds\": " << times[times.size()/2] << '}' << std::endl;
    }
    catch (const coreError& e)
    {
        std::cerr << "\n--> immersedDEM FATAL ERROR:\n    " << e.what() << "\n";
        return 1;
    }
    return 0;
}
