#include "triangleBVH.H"

#include <algorithm>
#include <cmath>

namespace immersedDEM
{

namespace
{

constexpr int leafSize = 4;

double boxDistSqr(const vec3& p, const vec3& lo, const vec3& hi)
{
    const vec3 d = (lo - p).cwiseMax(p - hi).cwiseMax(0.0);
    return d.squaredNorm();
}

} // End anonymous namespace


vec3 triangleBVH::closestOnTriangle
(
    const vec3& p, const vec3& a, const vec3& b, const vec3& c, int& feature
)
{
    // Voronoi regions of the triangle's features, tested in turn
    const vec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) { feature = 1; return a; }

    const vec3 bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) { feature = 2; return b; }

    const double vc = d1*d4 - d3*d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0)
    {
        feature = 4;
        return a + (d1/(d1 - d3))*ab;
    }

    const vec3 cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) { feature = 3; return c; }

    const double vb = d5*d2 - d1*d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0)
    {
        feature = 6;
        return a + (d2/(d2 - d6))*ac;
    }

    const double va = d3*d6 - d5*d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    {
        feature = 5;
        return b + ((d4 - d3)/((d4 - d3) + (d5 - d6)))*(c - b);
    }

    const double denom = 1.0/(va + vb + vc);
    feature = 0;
    return a + ab*(vb*denom) + ac*(vc*denom);
}


int triangleBVH::build
(
    std::vector<int>& order, int begin, int end, const std::vector<vec3>& centres
)
{
    const int id = int(nodes_.size());
    nodes_.push_back(node());
    vec3 lo = vec3::Constant(std::numeric_limits<double>::max()), hi = -lo;
    vec3 clo = lo, chi = hi;
    for (int i = begin; i < end; ++i)
    {
        for (const vec3& x : corners_[order[i]])
        {
            lo = lo.cwiseMin(x);
            hi = hi.cwiseMax(x);
        }
        clo = clo.cwiseMin(centres[order[i]]);
        chi = chi.cwiseMax(centres[order[i]]);
    }
    nodes_[id].lo = lo;
    nodes_[id].hi = hi;

    if (end - begin <= leafSize)
    {
        nodes_[id].first = begin;
        nodes_[id].count = end - begin;
        return id;
    }
    // Median split along the longest extent of the triangles' centres
    int axis = 0;
    (chi - clo).maxCoeff(&axis);
    const int mid = (begin + end)/2;
    std::nth_element
    (
        order.begin() + begin, order.begin() + mid, order.begin() + end,
        [&](int x, int y){ return centres[x][axis] < centres[y][axis]; }
    );
    const int left = build(order, begin, mid, centres);
    const int right = build(order, mid, end, centres);
    nodes_[id].first = left;
    nodes_[id].right = right;
    nodes_[id].count = 0;
    return id;
}


triangleBVH::triangleBVH(const triangleSoup& s)
{
    const int n = int(s.faces.size());
    std::vector<std::array<vec3, 3>> corners(n);
    std::vector<vec3> centres(n);
    for (int i = 0; i < n; ++i)
    {
        const triFace& f = s.faces[i];
        corners[i] = {s.points[f[0]], s.points[f[1]], s.points[f[2]]};
        centres[i] = (corners[i][0] + corners[i][1] + corners[i][2])/3.0;
    }
    corners_ = corners;
    std::vector<int> order(n);
    for (int i = 0; i < n; ++i) order[i] = i;
    nodes_.reserve(2*n/leafSize + 2);
    if (n > 0)
    {
        build(order, 0, n, centres);
    }
    // Store the triangles in leaf order for locality
    faceOfSlot_ = order;
    planeOfSlot_.resize(n);
    for (int i = 0; i < n; ++i)
    {
        corners_[i] = corners[order[i]];
        const auto& t = corners_[i];
        const vec3 a = (t[1] - t[0]).cross(t[2] - t[0]);
        const double an = a.norm();
        const vec3 nrm = an > 0 ? vec3(a/an) : vec3(vec3::Zero());
        planeOfSlot_[i] = {nrm.x(), nrm.y(), nrm.z(), nrm.dot(t[0])};
    }
}


triangleBVH::hit triangleBVH::closest(const vec3& p, double maxDistSqr) const
{
    hit best;
    best.distSqr = maxDistSqr;
    if (nodes_.empty())
    {
        return best;
    }

    // Each node with its box's squared distance, computed once: when its
    // parent chose the order of its children
    struct entry { int node; double d2; };
    entry stack[128];
    int top = 0;
    stack[top++] = {0, boxDistSqr(p, nodes_[0].lo, nodes_[0].hi)};
    // (the scale of the planes' round-off at p, below)
    const double pScale = p.cwiseAbs().sum();
    while (top)
    {
        const entry e = stack[--top];
        if (e.d2 >= best.distSqr)
        {
            continue;
        }
        const node& nd = nodes_[e.node];
        if (nd.count)
        {
            for (int s = nd.first; s < nd.first + nd.count; ++s)
            {
                // The distance to the triangle's plane bounds the one to
                // the triangle from below: a triangle whose plane is
                // farther than the best so far is passed over (less the
                // plane's round-off, so that the answer stays the one of
                // every triangle tried, ties included)
                const auto& pl = planeOfSlot_[s];
                const double h =
                    std::abs(pl[0]*p.x() + pl[1]*p.y() + pl[2]*p.z() - pl[3])
                  - 1e-12*(std::abs(pl[3]) + pScale);
                if (h > 0 && h*h > best.distSqr)
                {
                    continue;
                }
                int feature;
                const auto& t = corners_[s];
                const vec3 q = closestOnTriangle(p, t[0], t[1], t[2], feature);
                const double d2 = (q - p).squaredNorm();
                if (d2 < best.distSqr)
                {
                    best.distSqr = d2;
                    best.point = q;
                    best.feature = feature;
                    best.face = faceOfSlot_[s];
                }
            }
            continue;
        }
        // Visit the nearer child first: it shrinks the bound soonest
        const int left = nd.first;
        const int right = nd.right;
        const double dl = boxDistSqr(p, nodes_[left].lo, nodes_[left].hi);
        const double dr = boxDistSqr(p, nodes_[right].lo, nodes_[right].hi);
        if (dl <= dr)
        {
            stack[top++] = {right, dr};
            stack[top++] = {left, dl};
        }
        else
        {
            stack[top++] = {left, dl};
            stack[top++] = {right, dr};
        }
    }
    return best;
}

bool triangleBVH::facesWithin
(
    const vec3& p,
    double r,
    std::vector<int>& faces,
    size_t maxFaces
) const
{
    if (nodes_.empty())
    {
        return true;
    }
    const double r2 = r*r;
    int stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top)
    {
        const node& nd = nodes_[stack[--top]];
        if (boxDistSqr(p, nd.lo, nd.hi) > r2)
        {
            continue;
        }
        if (nd.count)
        {
            for (int s = nd.first; s < nd.first + nd.count; ++s)
            {
                int feature;
                const auto& t = corners_[s];
                if ((closestOnTriangle(p, t[0], t[1], t[2], feature) - p).squaredNorm() <= r2)
                {
                    faces.push_back(faceOfSlot_[s]);
                    if (faces.size() > maxFaces) return false;
                }
            }
            continue;
        }
        stack[top++] = nd.first;
        stack[top++] = nd.right;
    }
    return true;
}

} // End namespace immersedDEM
