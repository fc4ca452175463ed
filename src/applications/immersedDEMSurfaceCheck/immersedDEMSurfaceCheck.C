/*---------------------------------------------------------------------------*\
Application
    immersedDEMSurfaceCheck

Description
    Checks that an STL or OBJ surface can be a body (closed, manifold,
    orientable, not self-intersecting, non-zero volume) and prints, as one
    JSON object on stdout, its exact mass properties for a given density:
    volume, centroid, mass, inertia about the centroid, principal moments and
    axes (in the file's frame), and the repairs made.

Usage
    immersedDEMSurfaceCheck <file.stl|file.obj> [-scale S] [-rho RHO]
        [-noSelfIntersection]

    Exits 1 with a message naming the file and what is wrong.
\*---------------------------------------------------------------------------*/

#include "triangleMeshShape.H"
#include "coreError.H"

#include <cstdlib>
#include <iostream>
#include <string>

using namespace immersedDEM;

namespace
{

void usage(const char* what)
{
    std::cerr
        << "immersedDEMSurfaceCheck: " << what << "\n"
        << "Usage: immersedDEMSurfaceCheck <file.stl|file.obj> [-scale S] [-rho RHO]"
           " [-noSelfIntersection]\n";
    std::exit(1);
}

void json(std::ostream& os, const vec3& v)
{
    os << '[' << v.x() << ", " << v.y() << ", " << v.z() << ']';
}

} // End anonymous namespace


int main(int argc, char* argv[])
{
    std::string file;
    double scale = 1, rho = 1;
    bool selfIntersection = true;
    for (int i = 1; i < argc; ++i)
    {
        const std::string a = argv[i];
        auto number = [&](const char* name)
        {
            if (i + 1 >= argc) usage((std::string(name) + " needs a value").c_str());
            char* end = nullptr;
            const double v = std::strtod(argv[++i], &end);
            if (*end != '\0' || !(v > 0)) usage((std::string(name) + " needs a positive number").c_str());
            return v;
        };
        if (a == "-scale") scale = number("-scale");
        else if (a == "-rho") rho = number("-rho");
        else if (a == "-noSelfIntersection") selfIntersection = false;
        else if (a == "-help" || a == "--help") usage("help");
        else if (!a.empty() && a[0] == '-') usage(("unknown option " + a).c_str());
        else if (file.empty()) file = a;
        else usage("only one file");
    }
    if (file.empty()) usage("no file given");

    try
    {
        const auto s = triangleMeshShape::fromFile(file, scale, selfIntersection);
        const massProperties& mp = s->fileMassProperties();
        std::cout.precision(12);
        std::cout << "{\"file\": \"" << file << "\", \"triangles\": " << s->nTriangles()
            << ", \"volume\": " << mp.volume << ", \"mass\": " << rho*mp.volume
            << ", \"centroid\": ";
        json(std::cout, mp.centroid);
        std::cout << ", \"inertia\": [";
        for (int r = 0; r < 3; ++r)
        {
            json(std::cout, vec3(rho*mp.inertia.row(r).transpose()));
            std::cout << (r < 2 ? ", " : "]");
        }
        std::cout << ", \"principalMoments\": ";
        json(std::cout, vec3(rho*mp.principalMoments));
        std::cout << ", \"principalAxes\": [";
        for (int c = 0; c < 3; ++c)
        {
            json(std::cout, vec3(mp.principalAxes.col(c)));
            std::cout << (c < 2 ? ", " : "]");
        }
        std::cout << ", \"boundingRadius\": " << s->boundingRadius() << ", \"warnings\": [";
        for (size_t i = 0; i < s->warnings().size(); ++i)
        {
            std::cout << (i ? ", " : "") << '"' << s->warnings()[i] << '"';
        }
        std::cout << "]}" << std::endl;
        for (const std::string& w : s->warnings())
        {
            std::cerr << "--> immersedDEM Warning: " << w << '\n';
        }
    }
    catch (const coreError& e)
    {
        std::cerr << "\n--> immersedDEM FATAL ERROR:\n    " << e.what() << "\n";
        return 1;
    }
    return 0;
}
