#include "overlapEngine.H"
#include "coreError.H"
#include "cellsOverlap.H"
#include "convexOverlap.H"
#include "exactOverlap.H"
#include "sphereOverlap.H"
#include "uniformOverlap.H"
#include "virtualMeshOverlap.H"

#include <functional>
#include <map>

namespace immersedDEM
{

namespace
{

const std::map<std::string, std::function<std::unique_ptr<overlapEngine>()>>& table()
{
    static const std::map<std::string, std::function<std::unique_ptr<overlapEngine>()>> t
    {
        {"cells", []{ return std::unique_ptr<overlapEngine>(new cellsOverlap()); }},
        {"convex", []{ return std::unique_ptr<overlapEngine>(new convexOverlap()); }},
        {"exact", []{ return std::unique_ptr<overlapEngine>(new exactOverlap()); }},
        {"sphere", []{ return std::unique_ptr<overlapEngine>(new sphereOverlap()); }},
        {"uniform", []{ return std::unique_ptr<overlapEngine>(new uniformOverlap()); }},
        {"virtualMesh", []{ return std::unique_ptr<overlapEngine>(new virtualMeshOverlap()); }}
    };
    return t;
}

} // End anonymous namespace


std::vector<std::string> overlapEngine::types()
{
    std::vector<std::string> names;
    for (const auto& e : table()) names.push_back(e.first);
    return names;
}


std::unique_ptr<overlapEngine> overlapEngine::New(const std::string& type)
{
    const auto it = table().find(type);
    if (it == table().end())
    {
        std::string valid;
        for (const std::string& n : types()) valid += (valid.empty() ? "" : " ") + n;
        throw coreError
        (
            "Unknown overlap method '" + type + "'; valid methods are (" + valid + ")"
        );
    }
    return it->second();
}

} // End namespace immersedDEM
