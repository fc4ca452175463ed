#include "initialOverlaps.H"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

namespace immersedDEM
{

namespace
{

double smallerDiameter(const demSolver& dem, int a, int b)
{
    const auto& bodies = dem.bodies();
    double d = std::numeric_limits<double>::max();
    for (const int i : {a, b})
    {
        if (!dem.isWall(i)) d = std::min(d, 2*bodies[i].equivalentRadius());
    }
    return d < std::numeric_limits<double>::max() ? d : 0;
}


//- Equivalent depth of a region: its volume over its contact area
double depthOf(const contactRegion& r)
{
    return r.area > 0 ? r.volume/r.area : std::cbrt(r.volume);
}

} // End anonymous namespace


std::vector<initialOverlap> initialOverlaps::find(demSolver& dem)
{
    dem.computeContacts();
    std::map<std::pair<int, int>, initialOverlap> byPair;
    for (const contactRecord& c : dem.contacts())
    {
        if (!(c.region.volume > 0)) continue;
        initialOverlap& o = byPair[{c.a, c.b}];
        o.a = c.a;
        o.b = c.b;
        o.volume += c.region.volume;
        o.depth = std::max(o.depth, depthOf(c.region));
        o.diameter = smallerDiameter(dem, c.a, c.b);
    }
    std::vector<initialOverlap> list;
    for (const auto& e : byPair)
    {
        if (e.second.depth > depthTolerance*e.second.diameter) list.push_back(e.second);
    }
    return list;
}


overlapSeparation initialOverlaps::separate(demSolver& dem, int maxIterations)
{
    overlapSeparation result;
    auto& bodies = dem.bodies();
    std::vector<vec3> start(bodies.size());
    for (size_t i = 0; i < bodies.size(); ++i) start[i] = bodies[i].pose.position();

    for (; result.iterations < maxIterations; ++result.iterations)
    {
        dem.computeContacts();
        std::vector<vec3> move(bodies.size(), vec3::Zero());
        std::vector<int> count(bodies.size(), 0);
        bool deep = false;
        for (const contactRecord& c : dem.contacts())
        {
            const double d = depthOf(c.region);
            if (!(c.region.volume > 0) || d <= depthTolerance*smallerDiameter(dem, c.a, c.b))
            {
                continue;
            }
            const rigidBody& A = bodies[c.a];
            const rigidBody& B = bodies[c.b];
            if (!A.dynamic() && !B.dynamic()) continue;
            deep = true;
            // A little more than the depth: a lens's volume over its area
            // is half its depth, a face's is all of it
            const double shareA =
                !B.dynamic() ? 1 : (!A.dynamic() ? 0 : B.mass()/(A.mass() + B.mass()));
            const vec3 push = 1.01*d*c.region.normal;
            move[c.a] -= shareA*push;
            move[c.b] += (1 - shareA)*push;
            ++count[c.a];
            ++count[c.b];
        }
        if (!deep) break;
        for (size_t i = 0; i < bodies.size(); ++i)
        {
            if (count[i] > 0 && bodies[i].dynamic())
            {
                bodies[i].pose.setPosition(bodies[i].pose.position() + move[i]/count[i]);
            }
        }
        dem.bodiesChanged();
    }

    for (size_t i = 0; i < bodies.size(); ++i)
    {
        const double moved = (bodies[i].pose.position() - start[i]).norm();
        if (moved > 0) ++result.bodiesMoved;
        result.largestMove = std::max(result.largestMove, moved);
    }
    result.remaining = find(dem);
    // The moves were no collision: no spring or approach to remember
    dem.setHistories({});
    return result;
}


std::string initialOverlaps::text
(
    const demSolver& dem, std::vector<initialOverlap> overlaps, size_t maxLines
)
{
    std::sort
    (
        overlaps.begin(), overlaps.end(),
        [](const initialOverlap& x, const initialOverlap& y) { return x.depth > y.depth; }
    );
    std::ostringstream os;
    os.precision(4);
    for (size_t k = 0; k < overlaps.size() && k < maxLines; ++k)
    {
        const initialOverlap& o = overlaps[k];
        os  << "    " << dem.bodies()[o.a].name << " and " << dem.bodies()[o.b].name
            << ": volume " << o.volume << " m3, depth " << o.depth << " m";
        if (o.diameter > 0)
        {
            os  << " (" << 100*o.depth/o.diameter << "% of the diameter)";
        }
        os  << "\n";
    }
    if (overlaps.size() > maxLines)
    {
        os  << "    ... and " << overlaps.size() - maxLines << " more\n";
    }
    return os.str();
}

} // End namespace immersedDEM
