#include "convexDecomposition.H"
#include "axisAlignedBox.H"
#include "convexPolyhedron.H"
#include "floatingPointGuard.H"
#include "massProperties.H"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/convex_hull_3.h>
#include <CGAL/Nef_polyhedron_3.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_decomposition_3.h>
#include <CGAL/boost/graph/convert_nef_polyhedron_to_polygon_mesh.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <tuple>

namespace immersedDEM
{

namespace
{

using exactKernel = CGAL::Exact_predicates_exact_constructions_kernel;
using exactMesh = CGAL::Surface_mesh<exactKernel::Point_3>;
using exactPolyhedron = CGAL::Polyhedron_3<exactKernel>;
using nef = CGAL::Nef_polyhedron_3<exactKernel>;


// A coordinate as a double. An exact (lazy) number is converted from its
// exact value: its interval approximation is tighter or looser depending
// on whether CGAL happened to compute the exact value before, and that
// follows the order CGAL visits its cells in, which follows the heap's
// addresses (different from run to run)
double nearest(const exactKernel::FT& v)
{
    return CGAL::to_double(CGAL::exact(v));
}

double nearest(double v)
{
    return v;
}


// A triangulated surface mesh in doubles: points closer than weld
// (rounding made them one, or a cut passed within round-off of a corner)
// are one point, and triangles that lose a corner so are dropped
template<class Mesh>
triangleSoup soupOf(const Mesh& m, double weld)
{
    triangleSoup s;
    std::map<typename Mesh::Vertex_index, int> index;
    for (const auto v : m.vertices())
    {
        const auto& p = m.point(v);
        const vec3 x(nearest(p.x()), nearest(p.y()), nearest(p.z()));
        int same = -1;
        for (size_t i = 0; i < s.points.size() && same < 0; ++i)
        {
            if ((s.points[i] - x).norm() <= weld) same = int(i);
        }
        index[v] = same >= 0 ? same : int(s.points.size());
        if (same < 0) s.points.push_back(x);
    }
    for (const auto f : m.faces())
    {
        triFace t;
        int k = 0;
        for (const auto v : CGAL::vertices_around_face(m.halfedge(f), m))
        {
            if (k < 3) t[k] = index[v];
            ++k;
        }
        if (k == 3 && t[0] != t[1] && t[1] != t[2] && t[2] != t[0])
        {
            s.faces.push_back(t);
        }
    }
    return s;
}


// The surface in a canonical order: its points sorted, each face
// starting at its smallest point (orientation kept), the faces sorted.
// CGAL's hull and Nef conversions list points and faces in an order that
// follows the heap's addresses, which differ from run to run: ordered so,
// every sum over a piece has the same round-off in every run
triangleSoup canonical(const triangleSoup& s)
{
    const int n = int(s.points.size());
    std::vector<int> order(n);
    std::iota(order.begin(), order.end(), 0);
    auto key = [&](int i) { const vec3& p = s.points[i]; return std::make_tuple(p.x(), p.y(), p.z()); };
    std::sort(order.begin(), order.end(), [&](int i, int j) { return key(i) < key(j); });
    std::vector<int> to(n);
    triangleSoup c;
    for (int k = 0; k < n; ++k)
    {
        to[order[k]] = k;
        c.points.push_back(s.points[order[k]]);
    }
    for (const triFace& f : s.faces)
    {
        triFace g{to[f[0]], to[f[1]], to[f[2]]};
        while (g[0] > g[1] || g[0] > g[2]) g = triFace{g[1], g[2], g[0]};
        c.faces.push_back(g);
    }
    std::sort(c.faces.begin(), c.faces.end());
    return c;
}


using hullKernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using hullPoint = hullKernel::Point_3;

// The convex hull of points (exact predicates), triangulated
triangleSoup hullOf(const std::vector<hullPoint>& points)
{
    CGAL::Surface_mesh<hullPoint> m;
    CGAL::convex_hull_3(points.begin(), points.end(), m);
    return canonical(soupOf(m, 0));
}


// Pieces sharing part of a face: coplanar faces of opposite normals whose
// boxes meet
std::vector<std::vector<int>> neighboursOf
(
    const std::vector<std::unique_ptr<convexPolyhedron>>& P, double tol
)
{
    const size_t n = P.size();
    std::vector<axisAlignedBox> box(n);
    std::vector<std::vector<axisAlignedBox>> faceBox(n);
    for (size_t i = 0; i < n; ++i)
    {
        for (const vec3& v : P[i]->vertices()) box[i].add(v);
        for (const convexPolyhedron::face& f : P[i]->faces())
        {
            axisAlignedBox b;
            for (const int c : f.corners) b.add(P[i]->vertices()[c]);
            faceBox[i].push_back(b.inflated(tol));
        }
    }
    std::vector<std::vector<int>> nb(n);
    for (size_t i = 0; i < n; ++i)
    {
        for (size_t j = i + 1; j < n; ++j)
        {
            if (!box[i].inflated(tol).overlaps(box[j])) continue;
            bool shared = false;
            const auto& Fi = P[i]->faces();
            const auto& Fj = P[j]->faces();
            for (size_t a = 0; a < Fi.size() && !shared; ++a)
            {
                for (size_t b = 0; b < Fj.size() && !shared; ++b)
                {
                    shared =
                        Fi[a].normal.dot(Fj[b].normal) < -(1 - 1e-9)
                     && std::abs(Fi[a].offset + Fj[b].offset) < tol
                     && faceBox[i][a].overlaps(faceBox[j][b]);
                }
            }
            if (shared)
            {
                nb[i].push_back(int(j));
                nb[j].push_back(int(i));
            }
        }
    }
    return nb;
}


// The pieces checked convex and adding up to the body's volume; their
// neighbours
void finish(convexDecomposition& d, double volume, double radius)
{
    std::vector<std::unique_ptr<convexPolyhedron>> P;
    double sum = 0;
    for (size_t i = 0; i < d.pieces.size(); ++i)
    {
        P.push_back(convexPolyhedron::of(d.pieces[i]));
        if (!P.back())
        {
            d.why =
                "piece " + std::to_string(i) + " is not convex once rounded to"
                " doubles (a face meant flat that is not flat to round-off in this"
                " frame, as in a single-precision STL turned from its design frame,"
                " makes slivers)";
            break;
        }
        sum += massProperties::of(d.pieces[i]).volume;
    }
    if (d.why.empty() && !(std::abs(sum - volume) <= 1e-9*std::abs(volume)))
    {
        d.why =
            "the pieces' volumes add up to " + std::to_string(sum)
          + ", not the body's " + std::to_string(volume);
    }
    if (!d.why.empty())
    {
        d.pieces.clear();
        d.neighbours.clear();
        return;
    }
    d.neighbours = neighboursOf(P, convexPolyhedron::relativeTolerance*radius);
}


double radiusOf(const triangleSoup& s)
{
    double r = 0;
    for (const vec3& p : s.points) r = std::max(r, p.norm());
    return r;
}

} // End anonymous namespace


int convexDecomposition::countReflexEdges(const triangleSoup& s)
{
    // Each directed edge (i, j) of a face, and the face's third corner
    std::map<std::pair<int, int>, int> third;
    for (const triFace& f : s.faces)
    {
        for (int k = 0; k < 3; ++k)
        {
            third[{f[k], f[(k + 1) % 3]}] = f[(k + 2) % 3];
        }
    }
    // (a fold within the convexity test's tolerance is round-off)
    const double tol = convexPolyhedron::relativeTolerance*radiusOf(s);
    int reflex = 0;
    for (const triFace& f : s.faces)
    {
        const vec3& a = s.points[f[0]];
        const vec3 n = (s.points[f[1]] - a).cross(s.points[f[2]] - a).normalized();
        for (int k = 0; k < 3; ++k)
        {
            const int i = f[k], j = f[(k + 1) % 3];
            if (i > j) continue;    // each edge once
            const auto it = third.find({j, i});
            if (it == third.end()) continue;
            // The neighbour's third corner in front of this face's plane:
            // the edge folds inwards
            const vec3 c = s.points[it->second] - s.points[i];
            if (n.dot(c) > tol) ++reflex;
        }
    }
    return reflex;
}


convexDecomposition convexDecomposition::of(const triangleSoup& surface, int maxPieces)
{
    convexDecomposition d;
    d.reflexEdges = countReflexEdges(surface);
    if (d.reflexEdges == 0)
    {
        d.why = "no fold beyond round-off, yet not flat-faceted to 1e-8 (a curved surface)";
        return d;
    }
    if (d.reflexEdges > 2*maxPieces)
    {
        d.why =
            std::to_string(d.reflexEdges) + " reflex edges, more than twice the "
            + std::to_string(maxPieces) + " pieces allowed (a curved non-convex surface)";
        return d;
    }

    // The points snapped to a grid of 2^-45 (3e-14) of the surface's
    // radius: coordinates that are zero but for round-off (cos(pi/2))
    // become zero, and the exact cuts do not leave slivers of that size
    const double radius = radiusOf(surface);
    const double grid = std::ldexp(1.0, std::ilogb(radius) - 45);
    const floatingPointGuard noTraps;
    try
    {
        exactMesh m;
        std::vector<exactMesh::Vertex_index> v;
        for (const vec3& p : surface.points)
        {
            const vec3 q = (p/grid).array().round()*grid;
            v.push_back(m.add_vertex(exactKernel::Point_3(q.x(), q.y(), q.z())));
        }
        for (const triFace& f : surface.faces)
        {
            if (m.add_face(v[f[0]], v[f[1]], v[f[2]]) == exactMesh::null_face())
            {
                d.why = "the surface is not a closed manifold for CGAL";
                return d;
            }
        }
        nef N(m);
        if (!N.is_simple())
        {
            d.why = "the surface is not a simple solid for CGAL";
            return d;
        }
        CGAL::convex_decomposition_3(N);

        // Each piece with its sorted corners, the key that orders them
        std::vector<std::pair<std::vector<hullPoint>, triangleSoup>> keyed;

        // The first volume is the outer space; marked volumes are pieces
        auto c = N.volumes_begin();
        for (++c; c != N.volumes_end(); ++c)
        {
            if (!c->mark()) continue;
            if (int(keyed.size()) >= maxPieces)
            {
                d.pieces.clear();
                d.why = "more than " + std::to_string(maxPieces) + " convex pieces";
                return d;
            }
            exactPolyhedron P;
            N.convert_inner_shell_to_polyhedron(c->shells_begin(), P);
            // The hull of its corners rounded to doubles: exactly convex
            // and closed whatever the rounding did to nearly coincident
            // corners (the exact piece's own faces, rounded, can fold)
            std::vector<hullPoint> corners;
            for (auto v = P.vertices_begin(); v != P.vertices_end(); ++v)
            {
                const auto& x = v->point();
                corners.emplace_back
                (
                    nearest(x.x()), nearest(x.y()), nearest(x.z())
                );
            }
            // (in sorted order: CGAL lists a piece's corners, and the
            // pieces, in an order that follows the heap's addresses,
            // which differ from run to run; sorted, the hulls and the
            // pieces' order are the same in every run, and so are the
            // round-off of every sum over them)
            std::sort(corners.begin(), corners.end());
            corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
            triangleSoup piece = hullOf(corners);
            if (piece.faces.size() >= 4)
            {
                keyed.push_back({std::move(corners), std::move(piece)});
            }
        }
        std::sort
        (
            keyed.begin(), keyed.end(),
            [](const auto& x, const auto& y) { return x.first < y.first; }
        );
        for (auto& k : keyed) d.pieces.push_back(std::move(k.second));
    }
    catch (const std::exception& e)
    {
        d.pieces.clear();
        d.why = std::string("CGAL's convex decomposition failed: ") + e.what();
        return d;
    }
    if (d.pieces.empty())
    {
        d.why = "CGAL's convex decomposition gave no piece";
        return d;
    }
    finish(d, massProperties::of(surface).volume, radius);
    return d;
}


convexDecomposition convexDecomposition::ofParts
(
    std::vector<triangleSoup> parts, triangleSoup& union_
)
{
    convexDecomposition d;
    union_ = triangleSoup();
    if (parts.empty())
    {
        d.why = "no parts";
        return d;
    }
    double radius = 0, sum = 0;
    for (size_t i = 0; i < parts.size(); ++i)
    {
        radius = std::max(radius, radiusOf(parts[i]));
        if (!convexPolyhedron::of(parts[i]))
        {
            d.why = "part " + std::to_string(i + 1) + " is not convex";
            return d;
        }
        sum += massProperties::of(parts[i]).volume;
    }
    const floatingPointGuard noTraps;
    try
    {
        nef N;
        for (const triangleSoup& p : parts)
        {
            exactMesh m;
            std::vector<exactMesh::Vertex_index> v;
            for (const vec3& x : p.points)
            {
                v.push_back(m.add_vertex(exactKernel::Point_3(x.x(), x.y(), x.z())));
            }
            for (const triFace& f : p.faces)
            {
                m.add_face(v[f[0]], v[f[1]], v[f[2]]);
            }
            N += nef(m);
        }
        exactMesh u;
        CGAL::convert_nef_polyhedron_to_polygon_mesh(N, u, true);
        union_ = canonical(soupOf(u, 1e-12*radius));
    }
    catch (const std::exception& e)
    {
        d.why = std::string("CGAL's union of the parts failed: ") + e.what();
        return d;
    }
    const double V = massProperties::of(union_).volume;
    if (!(std::abs(V - sum) <= 1e-9*V))
    {
        d.why =
            "the parts overlap: their volumes add up to " + std::to_string(sum)
          + ", their union's is " + std::to_string(V);
        return d;
    }
    d.pieces = std::move(parts);
    finish(d, V, radius);
    return d;
}

} // End namespace immersedDEM

