#include "closedSurfaceCheck.H"
#include "coreError.H"
#include "massProperties.H"
#include "floatingPointGuard.H"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>

#include <algorithm>
#include <numeric>
#include <queue>
#include <cmath>
#include <sstream>
#include <unordered_map>

namespace immersedDEM
{

namespace
{

using edgeKey = std::uint64_t;

edgeKey key(int a, int b)
{
    const auto lo = std::uint64_t(std::min(a, b));
    const auto hi = std::uint64_t(std::max(a, b));
    return (hi << 32) | lo;
}

// A face's use of an edge: which face, and whether it runs lo->hi
struct edgeUse
{
    int face;
    bool forward;
};

struct stopCounting {};

// Counts through an output iterator; stops the search when enough were seen
struct pairCounter
{
    long* n;
    long max;
    pairCounter& operator*() { return *this; }
    pairCounter& operator++() { return *this; }
    pairCounter operator++(int) { return *this; }
    template<class T> pairCounter& operator=(const T&)
    {
        if (++(*n) >= max) throw stopCounting();
        return *this;
    }
};

} // End anonymous namespace


void closedSurfaceCheck::checkCoordinateRange
(
    const triangleSoup& soup,
    const std::string& name
)
{
    for (size_t i = 0; i < soup.points.size(); ++i)
    {
        const vec3& p = soup.points[i];
        if (!(p.cwiseAbs().maxCoeff() <= maxCoordinate))
        {
            std::ostringstream os;
            os.precision(6);
            os  << "Surface \"" << name << "\": vertex " << i << " (" << p.x() << ' '
                << p.y() << ' ' << p.z() << ") has a coordinate out of range:"
                << " magnitudes above " << maxCoordinate << " m (after scale)"
                << " are not accepted";
            throw coreError(os.str());
        }
    }
}


std::vector<int> closedSurfaceCheck::enclosingShells
(
    const triangleSoup& soup,
    const std::vector<int>& shell,
    int nShells
)
{
    std::vector<int> inside(nShells, -1);
    if (nShells < 2)
    {
        return inside;
    }
    // Each shell's box, faces and corners
    std::vector<vec3> lo(nShells, vec3::Constant(HUGE_VAL));
    std::vector<vec3> hi(nShells, vec3::Constant(-HUGE_VAL));
    std::vector<std::vector<int>> facesOf(nShells), cornersOf(nShells);
    std::vector<int> shellOfPoint(soup.points.size(), -1);
    for (size_t fi = 0; fi < soup.faces.size(); ++fi)
    {
        const int s = shell[fi];
        facesOf[s].push_back(int(fi));
        for (int v : soup.faces[fi])
        {
            lo[s] = lo[s].cwiseMin(soup.points[v]);
            hi[s] = hi[s].cwiseMax(soup.points[v]);
            if (shellOfPoint[v] < 0)
            {
                shellOfPoint[v] = s;
                cornersOf[s].push_back(v);
            }
        }
    }

    // Winding number of shell t at p: the sum of the solid angles of its
    // triangles (van Oosterom and Strackee, IEEE Trans. Biomed. Eng. 30,
    // 1983) over 4 pi; +-1 inside a closed shell, 0 outside
    const double fourPi = 4*std::acos(-1.0);
    auto winding = [&](int t, const vec3& p)
    {
        double omega = 0;
        for (int fi : facesOf[t])
        {
            const triFace& f = soup.faces[fi];
            const vec3 a = soup.points[f[0]] - p;
            const vec3 b = soup.points[f[1]] - p;
            const vec3 c = soup.points[f[2]] - p;
            const double la = a.norm(), lb = b.norm(), lc = c.norm();
            const double num = a.dot(b.cross(c));
            const double den = la*lb*lc + a.dot(b)*lc + a.dot(c)*lb + b.dot(c)*la;
            omega += 2*std::atan2(num, den);
        }
        return omega/fourPi;
    };

    // Shell s is inside shell t when its box is inside t's and its corners
    // (up to 8, spread over the shell) are: shells that cross each other
    // (some corners in, some out) are left to the self-intersection check
    const size_t nSamples = 8;
    for (int s = 0; s < nShells; ++s)
    {
        const std::vector<int>& corners = cornersOf[s];
        for (int t = 0; t < nShells && inside[s] < 0; ++t)
        {
            if
            (
                t == s
             || (lo[s].array() < lo[t].array()).any()
             || (hi[s].array() > hi[t].array()).any()
            )
            {
                continue;
            }
            const size_t n = std::min(nSamples, corners.size());
            bool all = true;
            for (size_t k = 0; k < n && all; ++k)
            {
                all = std::abs(winding(t, soup.points[corners[k*corners.size()/n]])) > 0.5;
            }
            if (all)
            {
                inside[s] = t;
            }
        }
    }
    return inside;
}


long closedSurfaceCheck::countSelfIntersections(const triangleSoup& soup, long maxPairs)
{
    const floatingPointGuard noTraps;
    using K = CGAL::Exact_predicates_inexact_constructions_kernel;
    using mesh = CGAL::Surface_mesh<K::Point_3>;

    std::vector<K::Point_3> pts;
    pts.reserve(soup.points.size());
    for (const vec3& p : soup.points)
    {
        pts.emplace_back(p.x(), p.y(), p.z());
    }
    std::vector<std::vector<std::size_t>> polys;
    polys.reserve(soup.faces.size());
    for (const triFace& f : soup.faces)
    {
        polys.push_back({std::size_t(f[0]), std::size_t(f[1]), std::size_t(f[2])});
    }
    mesh m;
    CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(pts, polys, m);

    long n = 0;
    try
    {
        CGAL::Polygon_mesh_processing::self_intersections(m, pairCounter{&n, maxPairs});
    }
    catch (const stopCounting&)
    {}
    return n;
}


std::vector<std::string> closedSurfaceCheck::checkAndRepair
(
    triangleSoup& soup,
    const std::string& name,
    bool checkSelfIntersection
)
{
    std::vector<std::string> warnings;
    const std::string where = "Surface \"" + name + "\"";
    checkCoordinateRange(soup, name);

    // Triangles with a repeated corner (after merging) have no area
    {
        const size_t before = soup.faces.size();
        soup.faces.erase
        (
            std::remove_if
            (
                soup.faces.begin(), soup.faces.end(),
                [](const triFace& f){ return f[0] == f[1] || f[1] == f[2] || f[0] == f[2]; }
            ),
            soup.faces.end()
        );
        if (soup.faces.size() != before)
        {
            warnings.push_back
            (
                where + ": dropped " + std::to_string(before - soup.faces.size())
              + " degenerate triangles (a repeated corner)"
            );
        }
    }
    if (soup.faces.empty())
    {
        throw coreError(where + " contains no triangles");
    }

    // Edge -> uses
    const int nFaces = int(soup.faces.size());
    std::unordered_map<edgeKey, std::vector<edgeUse>> edges;
    edges.reserve(3*soup.faces.size());
    for (int fi = 0; fi < nFaces; ++fi)
    {
        const triFace& f = soup.faces[fi];
        for (int k = 0; k < 3; ++k)
        {
            const int a = f[k], b = f[(k + 1) % 3];
            edges[key(a, b)].push_back({fi, a < b});
        }
    }

    long nBorder = 0, nNonManifold = 0;
    for (const auto& e : edges)
    {
        if (e.second.size() == 1) ++nBorder;
        else if (e.second.size() > 2) ++nNonManifold;
    }
    if (nBorder)
    {
        throw coreError
        (
            where + " is not closed: " + std::to_string(nBorder)
          + " border edges (holes). Close the surface (e.g. with surfaceCheck"
            " and a mesh repair tool) before using it as a body"
        );
    }
    if (nNonManifold)
    {
        throw coreError
        (
            where + " is non-manifold: " + std::to_string(nNonManifold)
          + " edges are shared by more than two triangles"
        );
    }

    // Non-manifold vertices: the triangles around a vertex must form one fan
    {
        std::vector<std::vector<int>> vertexFaces(soup.points.size());
        for (int fi = 0; fi < nFaces; ++fi)
        {
            for (int v : soup.faces[fi]) vertexFaces[v].push_back(fi);
        }
        long nBadVertices = 0;
        for (size_t v = 0; v < vertexFaces.size(); ++v)
        {
            const auto& fs = vertexFaces[v];
            if (fs.size() < 2) { if (fs.size() == 1) ++nBadVertices; continue; }
            // Walk the fan across edges through v
            std::vector<char> seen(fs.size(), 0);
            std::vector<size_t> stack{0};
            seen[0] = 1;
            size_t nSeen = 1;
            while (!stack.empty())
            {
                const triFace& f = soup.faces[fs[stack.back()]];
                stack.pop_back();
                for (int o : f)
                {
                    if (o == int(v)) continue;
                    for (const edgeUse& u : edges[key(int(v), o)])
                    {
                        const size_t j = std::find(fs.begin(), fs.end(), u.face) - fs.begin();
                        if (j < fs.size() && !seen[j])
                        {
                            seen[j] = 1; ++nSeen; stack.push_back(j);
                        }
                    }
                }
            }
            if (nSeen != fs.size()) ++nBadVertices;
        }
        if (nBadVertices)
        {
            throw coreError
            (
                where + " is non-manifold: " + std::to_string(nBadVertices)
              + " vertices join surface sheets that share no edge"
            );
        }
    }

    // Consistent orientation by a walk over each connected shell
    std::vector<int> shell(nFaces, -1);
    std::vector<char> flip(nFaces, 0);
    int nShells = 0;
    long nFlipped = 0;
    for (int seed = 0; seed < nFaces; ++seed)
    {
        if (shell[seed] >= 0) continue;
        std::queue<int> q;
        q.push(seed);
        shell[seed] = nShells;
        while (!q.empty())
        {
            const int fi = q.front(); q.pop();
            const triFace& f = soup.faces[fi];
            for (int k = 0; k < 3; ++k)
            {
                const int a = f[k], b = f[(k + 1) % 3];
                const auto& uses = edges[key(a, b)];
                const edgeUse& me = uses[0].face == fi ? uses[0] : uses[1];
                const edgeUse& other = uses[0].face == fi ? uses[1] : uses[0];
                // Consistent neighbours run the shared edge in opposite directions
                const bool myDir = me.forward != bool(flip[fi]);
                const bool wantFlip = (other.forward == myDir);
                if (shell[other.face] < 0)
                {
                    shell[other.face] = nShells;
                    flip[other.face] = wantFlip;
                    q.push(other.face);
                }
                else if (bool(flip[other.face]) != wantFlip)
                {
                    throw coreError(where + " is not orientable (like a Moebius strip or Klein bottle)");
                }
            }
        }
        ++nShells;
    }
    for (int fi = 0; fi < nFaces; ++fi)
    {
        if (flip[fi])
        {
            std::swap(soup.faces[fi][1], soup.faces[fi][2]);
            ++nFlipped;
        }
    }
    // The walk keeps the seed's orientation: count the minority as repaired
    if (nFlipped)
    {
        warnings.push_back
        (
            where + ": inconsistent triangle orientation repaired ("
          + std::to_string(std::min<long>(nFlipped, nFaces - nFlipped)) + " triangles turned)"
        );
    }

    // Nested shells: a cavity (or a body inside a body) is not supported
    {
        const std::vector<int> inside = enclosingShells(soup, shell, nShells);
        int nNested = 0, first = -1;
        for (int s = 0; s < nShells; ++s)
        {
            if (inside[s] >= 0)
            {
                ++nNested;
                if (first < 0) first = s;
            }
        }
        if (nNested)
        {
            throw coreError
            (
                where + " has nested shells: " + std::to_string(nShells)
              + " closed shells, " + std::to_string(nNested) + " of them inside"
                " another (shell " + std::to_string(first) + " inside shell "
              + std::to_string(inside[first]) + "). A cavity is not supported:"
                " remove the inner shells (a hollow body) or give them as"
                " separate bodies"
            );
        }
    }

    // Each shell outwards
    {
        std::vector<double> sixV(nShells, 0);
        for (int fi = 0; fi < nFaces; ++fi)
        {
            const triFace& f = soup.faces[fi];
            const vec3& a = soup.points[f[0]];
            sixV[shell[fi]] += a.dot((soup.points[f[1]] - a).cross(soup.points[f[2]] - a));
        }
        int nInward = 0;
        for (int s = 0; s < nShells; ++s)
        {
            if (sixV[s] < 0) ++nInward;
        }
        if (nInward)
        {
            for (int fi = 0; fi < nFaces; ++fi)
            {
                if (sixV[shell[fi]] < 0) std::swap(soup.faces[fi][1], soup.faces[fi][2]);
            }
            warnings.push_back
            (
                where + ": inward orientation repaired (" + std::to_string(nInward)
              + " of " + std::to_string(nShells) + " shells turned outwards)"
            );
        }
    }

    // Zero volume (flat or collapsed surface)
    {
        vec3 lo = soup.points[0], hi = soup.points[0];
        for (const vec3& p : soup.points) { lo = lo.cwiseMin(p); hi = hi.cwiseMax(p); }
        const double diag = (hi - lo).norm();
        const double V = massProperties::signedVolume(soup);
        if (!(V > 1e-12*diag*diag*diag))
        {
            throw coreError(where + " encloses zero volume (flat or collapsed surface)");
        }
    }

    if (checkSelfIntersection)
    {
        const long n = countSelfIntersections(soup);
        if (n)
        {
            throw coreError
            (
                where + " is self-intersecting: " + (n >= 1000 ? "at least " : "")
              + std::to_string(n) + " pairs of triangles intersect"
            );
        }
    }

    return warnings;
}

} // End namespace immersedDEM
