#include "convexPolyhedron.H"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>

namespace immersedDEM
{

namespace
{

int findRoot(std::vector<int>& parent, int i)
{
    while (parent[i] != i)
    {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    return i;
}


} // End anonymous namespace


std::vector<int> convexPolyhedron::planarHull
(
    const std::vector<Eigen::Vector2d>& p, std::vector<int> idx
)
{
    std::sort
    (
        idx.begin(), idx.end(),
        [&](int a, int b)
        {
            return p[a].x() < p[b].x() || (p[a].x() == p[b].x() && p[a].y() < p[b].y());
        }
    );
    if (idx.size() < 3) return idx;
    auto turn = [&](int o, int a, int b)
    {
        const Eigen::Vector2d oa = p[a] - p[o], ob = p[b] - p[o];
        return oa.x()*ob.y() - oa.y()*ob.x();
    };
    std::vector<int> h(2*idx.size());
    size_t k = 0;
    for (size_t i = 0; i < idx.size(); ++i)
    {
        while (k >= 2 && turn(h[k - 2], h[k - 1], idx[i]) <= 0) --k;
        h[k++] = idx[i];
    }
    for (size_t i = idx.size() - 1, t = k + 1; i > 0; --i)
    {
        while (k >= t && turn(h[k - 2], h[k - 1], idx[i - 1]) <= 0) --k;
        h[k++] = idx[i - 1];
    }
    h.resize(k - 1);
    return h;
}


std::unique_ptr<convexPolyhedron> convexPolyhedron::of(const triangleSoup& s)
{
    std::unique_ptr<convexPolyhedron> P(new convexPolyhedron());

    // The vertices the faces use
    std::vector<int> newIndex(s.points.size(), -1);
    for (const triFace& f : s.faces)
    {
        for (int k = 0; k < 3; ++k)
        {
            if (newIndex[f[k]] < 0)
            {
                newIndex[f[k]] = int(P->vertices_.size());
                P->vertices_.push_back(s.points[f[k]]);
            }
        }
    }
    const std::vector<vec3>& x = P->vertices_;
    for (const vec3& p : x) P->radius_ = std::max(P->radius_, p.norm());
    const double tol = P->tolerance();
    if (x.size() < 4 || !(P->radius_ > 0)) return nullptr;

    const int nT = int(s.faces.size());
    std::vector<triFace> t(nT);
    std::vector<vec3> n2(nT), n(nT);
    std::vector<char> flat(nT, 0);
    for (int i = 0; i < nT; ++i)
    {
        for (int k = 0; k < 3; ++k) t[i][k] = newIndex[s.faces[i][k]];
        n2[i] = (x[t[i][1]] - x[t[i][0]]).cross(x[t[i][2]] - x[t[i][0]]);
        const double a = n2[i].norm();
        const double longest = std::max
        (
            {
                (x[t[i][1]] - x[t[i][0]]).squaredNorm(),
                (x[t[i][2]] - x[t[i][1]]).squaredNorm(),
                (x[t[i][0]] - x[t[i][2]]).squaredNorm()
            }
        );
        // (a triangle of no area has no plane: it lies on its neighbours';
        // nor has a sliver narrower than 1e-8 of its length, whose normal
        // round-off would tilt by more than the tolerance: a convex piece
        // cut exactly and rounded to doubles has such slivers)
        flat[i] = a > 1e-20*P->radius_*P->radius_ && a > 1e-8*longest;
        n[i] = flat[i] ? vec3(n2[i]/a) : vec3::Zero();
    }

    // Edges: (smaller, larger vertex) -> triangle, sorted so that the two
    // triangles of an edge are neighbours in the list
    std::vector<std::pair<std::uint64_t, int>> edges;
    edges.reserve(3*nT);
    for (int i = 0; i < nT; ++i)
    {
        for (int k = 0; k < 3; ++k)
        {
            const std::uint64_t a = std::uint64_t(t[i][k]), b = std::uint64_t(t[i][(k + 1)%3]);
            edges.emplace_back(std::min(a, b) << 32 | std::max(a, b), i);
        }
    }
    std::sort(edges.begin(), edges.end());

    // Every edge convex (the cheap test, failing at the first dent), and
    // coplanar neighbours joined into faces
    std::vector<int> parent(nT);
    std::iota(parent.begin(), parent.end(), 0);
    for (size_t e = 0; e + 1 < edges.size(); ++e)
    {
        if (edges[e].first != edges[e + 1].first) continue;
        const int i = edges[e].second, j = edges[e + 1].second;
        if (!flat[i] || !flat[j]) continue;
        int w = -1;
        for (int k = 0; k < 3; ++k)
        {
            const int v = t[j][k];
            if (v != t[i][0] && v != t[i][1] && v != t[i][2]) w = v;
        }
        if (w < 0) continue;
        const double side = n[i].dot(x[w] - x[t[i][0]]);
        if (side > tol) return nullptr;
        if (side >= -tol && n[i].dot(n[j]) > 0)
        {
            parent[findRoot(parent, i)] = findRoot(parent, j);
        }
    }

    // The faces: plane and polygon of each set of coplanar triangles
    std::vector<int> faceOf(nT, -1);
    std::vector<vec3> sumN;
    std::vector<std::vector<int>> cornersOf;
    for (int i = 0; i < nT; ++i)
    {
        if (!flat[i]) continue;
        const int r = findRoot(parent, i);
        if (faceOf[r] < 0)
        {
            faceOf[r] = int(sumN.size());
            sumN.push_back(vec3::Zero());
            cornersOf.emplace_back();
        }
        const int f = faceOf[r];
        sumN[f] += n2[i];
        for (int k = 0; k < 3; ++k) cornersOf[f].push_back(t[i][k]);
    }
    for (size_t f = 0; f < sumN.size(); ++f)
    {
        face F;
        F.normal = sumN[f].normalized();
        std::vector<int>& c = cornersOf[f];
        std::sort(c.begin(), c.end());
        c.erase(std::unique(c.begin(), c.end()), c.end());
        double lo = std::numeric_limits<double>::max();
        F.offset = -std::numeric_limits<double>::max();
        for (int v : c)
        {
            const double d = F.normal.dot(x[v]);
            lo = std::min(lo, d);
            F.offset = std::max(F.offset, d);
        }
        // (a chain of nearly coplanar triangles drifting away from one
        // plane is a curved surface, not a face)
        if (F.offset - lo > 2*tol) return nullptr;

        // Every vertex behind the plane: convex
        for (const vec3& p : x)
        {
            if (F.normal.dot(p) > F.offset + tol) return nullptr;
        }

        // The polygon: hull of the corners in the plane (u, v, normal
        // right-handed)
        const vec3 u = F.normal.unitOrthogonal();
        const vec3 v = F.normal.cross(u);
        std::vector<Eigen::Vector2d> uv(x.size());
        for (int k : c) uv[k] = Eigen::Vector2d(u.dot(x[k]), v.dot(x[k]));
        F.corners = planarHull(uv, c);
        if (F.corners.size() >= 3)
        {
            P->faces_.push_back(std::move(F));
        }
    }
    if (P->faces_.size() < 4) return nullptr;
    return P;
}

} // End namespace immersedDEM
