#include "pairResolutions.H"
#include "convexOverlap.H"
#include "pieceOverlap.H"
#include "sphereOverlap.H"
#include "triangleMeshShape.H"

#include <algorithm>
#include <cstdio>

namespace immersedDEM
{

namespace
{
    std::pair<std::string, std::string> ordered(const std::string& a, const std::string& b)
    {
        return a <= b ? std::make_pair(a, b) : std::make_pair(b, a);
    }

    // The name for the log: a mesh's file without its folders
    std::string shown(const std::string& type)
    {
        const size_t slash = type.find_last_of('/');
        return slash == std::string::npos ? type : type.substr(slash + 1);
    }
}


std::string pairResolutions::typeOf(const shape& s, bool wall)
{
    if (wall) return "wall";
    if (s.shapeKind() == shape::kind::sphere) return "sphere";
    if (const auto* m = shapeAs<triangleMeshShape>(s))
    {
        if (!m->name().empty()) return "mesh " + m->name();
    }
    return s.type();
}


void pairResolutions::update
(
    const std::vector<rigidBody>& bodies, const std::vector<char>& isWall,
    const overlapSettings& base,
    const std::function<double(size_t, size_t)>& depthOf
)
{
    if (!active()) return;

    // One body of each type (the first), and how many there are
    struct representative
    {
        size_t index = 0;
        int count = 0;
    };
    std::map<std::string, representative> types;
    std::vector<std::string> typeOfBody(bodies.size());
    for (size_t i = 0; i < bodies.size(); ++i)
    {
        typeOfBody[i] = typeOf(*bodies[i].geometry, isWall[i]);
        representative& r = types[typeOfBody[i]];
        if (r.count++ == 0) r.index = i;
    }

    for (auto a = types.begin(); a != types.end(); ++a)
    {
        for (auto b = a; b != types.end(); ++b)
        {
            const bool self = a == b;
            if (self && (a->second.count < 2 || a->first == "wall")) continue;
            const auto key = ordered(a->first, b->first);
            if (chosen_.count(key)) continue;

            // A the wall, if any
            const bool wallB = b->first == "wall";
            const size_t ia = (wallB ? b : a)->second.index;
            const size_t ib = (wallB ? a : b)->second.index;
            const rigidBody& A = bodies[ia];
            const rigidBody& B = bodies[ib];
            const bool wall = wallB || a->first == "wall";
            const shape& sa = *A.geometry;
            const shape& sb = *B.geometry;

            // Exact paths need no resolution: convex bodies, and bodies
            // of convex pieces, against each other and walls; two spheres
            // (the lens)
            const auto* mb = shapeAs<triangleMeshShape>(sb);
            if (wall)
            {
                if (mb && (mb->convex() || (base.convexExact && !mb->pieces().empty()))) continue;
            }
            else if
            (
                base.convexExact
             && (sphereOverlap::handles(sa, sb) || convexOverlap::handles(sa, sb) || pieceOverlap::handles(sa, sb))
            )
            {
                continue;
            }
            const double d =
                wall
              ? 2*B.equivalentRadius()
              : 2*std::min(A.equivalentRadius(), B.equivalentRadius());

            const double depth = std::min(0.05*d, std::max(1e-6*d, depthOf(ia, ib)));
            const contactResolution r =
                contactResolution::calibrate(sa, sb, d, depth, base, tolerance_);
            chosen_[key] = r;
            char tol[32];
            std::snprintf(tol, sizeof(tol), "%g%%", 100*tolerance_);
            messages_.push_back
            (
                "Contact resolution, " + shown(key.first) + " against " + shown(key.second)
              + " (volumeTolerance " + tol + "): " + r.describe()
            );
        }
    }

    // The table for settingsFor
    std::map<std::string, int> index;
    for (const auto& t : types)
    {
        const int k = int(index.size());
        index[t.first] = k;
    }
    nTypes_ = int(index.size());
    typeIndex_.clear();
    for (size_t i = 0; i < bodies.size(); ++i)
    {
        typeIndex_[bodies[i].geometry.get()] = index[typeOfBody[i]];
    }
    table_.assign(size_t(nTypes_)*size_t(nTypes_), nullptr);
    for (const auto& a : index)
    {
        for (const auto& b : index)
        {
            const auto it = chosen_.find(ordered(a.first, b.first));
            if (it != chosen_.end())
            {
                table_[size_t(a.second)*size_t(nTypes_) + size_t(b.second)] = &it->second;
            }
        }
    }
}


overlapSettings pairResolutions::settingsFor
(
    const rigidBody& A, bool wallA, const rigidBody& B, bool wallB,
    const overlapSettings& base
) const
{
    if (!active() || chosen_.empty()) return base;
    const auto ia = typeIndex_.find(A.geometry.get());
    const auto ib = typeIndex_.find(B.geometry.get());
    if (ia == typeIndex_.end() || ib == typeIndex_.end()) return base;
    const contactResolution* r =
        table_[size_t(ia->second)*size_t(nTypes_) + size_t(ib->second)];
    if (!r) return base;
    const double d =
        wallA ? 2*B.equivalentRadius()
      : wallB ? 2*A.equivalentRadius()
      : 2*std::min(A.equivalentRadius(), B.equivalentRadius());
    return r->settingsFor(base, d);
}


double pairResolutions::largestLeaf(double dMax) const
{
    double leaf = 0;
    for (const auto& c : chosen_)
    {
        leaf = std::max(leaf, dMax/c.second.cellsPerDiameter/double(1L << c.second.level));
    }
    return leaf;
}


std::vector<std::string> pairResolutions::takeMessages()
{
    std::vector<std::string> m;
    m.swap(messages_);
    return m;
}

} // End namespace immersedDEM
