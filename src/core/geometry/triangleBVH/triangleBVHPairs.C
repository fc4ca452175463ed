#include "triangleBVH.H"

#include <algorithm>
#include <cmath>
#include <limits>

namespace immersedDEM
{

namespace
{

//- The closest points x on pq and y on uv of the segments pq and uv:
//  minimise |p + s d1 - u - t d2|^2 over [0, 1]^2, the unconstrained s
//  clamped, t from it, clamped, and s again from the clamped t
void segmentClosestPoints
(
    const vec3& p, const vec3& q, const vec3& u, const vec3& v, vec3& x, vec3& y
)
{
    const vec3 d1 = q - p, d2 = v - u, r = p - u;
    const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
    double s = 0, t = 0;
    if (a > 0 || e > 0)
    {
        if (a <= 0)
        {
            t = std::clamp(f/e, 0.0, 1.0);
        }
        else
        {
            const double c = d1.dot(r);
            if (e <= 0)
            {
                s = std::clamp(-c/a, 0.0, 1.0);
            }
            else
            {
                const double b = d1.dot(d2);
                const double den = a*e - b*b;
                s = den > 0 ? std::clamp((b*f - c*e)/den, 0.0, 1.0) : 0.0;
                t = (b*s + f)/e;
                if (t < 0)
                {
                    t = 0;
                    s = std::clamp(-c/a, 0.0, 1.0);
                }
                else if (t > 1)
                {
                    t = 1;
                    s = std::clamp((b - c)/a, 0.0, 1.0);
                }
            }
        }
    }
    x = p + s*d1;
    y = u + t*d2;
}


//- Squared distance of the segments pq and uv
double segmentDistSqr(const vec3& p, const vec3& q, const vec3& u, const vec3& v)
{
    vec3 x, y;
    segmentClosestPoints(p, q, u, v, x, y);
    return (x - y).squaredNorm();
}


//- Whether segment pq crosses the plane of triangle abc inside it
//  (inclusive, with a round-off margin). A segment in the triangle's plane
//  is left to the edge and corner distances, which decide that case.
bool segmentCrossesTriangle
(
    const vec3& p, const vec3& q, const vec3& a, const vec3& b, const vec3& c
)
{
    const vec3 n = (b - a).cross(c - a);
    const double dp = n.dot(p - a), dq = n.dot(q - a);
    if ((dp > 0 && dq > 0) || (dp < 0 && dq < 0) || dp == dq)
    {
        return false;
    }
    const vec3 x = p + (dp/(dp - dq))*(q - p);
    const double tol = -1e-9*n.squaredNorm();
    return n.dot((b - a).cross(x - a)) >= tol
        && n.dot((c - b).cross(x - b)) >= tol
        && n.dot((a - c).cross(x - c)) >= tol;
}


double boxDistSqr(const vec3& loA, const vec3& hiA, const vec3& cB, const vec3& hB)
{
    const vec3 d = (loA - cB - hB).cwiseMax(cB - hB - hiA).cwiseMax(0.0);
    return d.squaredNorm();
}

} // End anonymous namespace


double triangleBVH::segmentDistance
(
    const vec3& p, const vec3& q, const vec3& u, const vec3& v
)
{
    return std::sqrt(segmentDistSqr(p, q, u, v));
}


double triangleBVH::triangleDistance
(
    const std::array<vec3, 3>& a, const std::array<vec3, 3>& b
)
{
    // Two triangles that do not meet are nearest at a corner of one and
    // the other triangle, or at two edges; they meet where an edge of one
    // crosses the other (or, in one plane, where edges cross or a corner
    // lies inside: distance 0 from those features already)
    for (int i = 0; i < 3; ++i)
    {
        const int j = (i + 1) % 3;
        if
        (
            segmentCrossesTriangle(a[i], a[j], b[0], b[1], b[2])
         || segmentCrossesTriangle(b[i], b[j], a[0], a[1], a[2])
        )
        {
            return 0;
        }
    }
    double d2 = std::numeric_limits<double>::max();
    int feature;
    for (int i = 0; i < 3; ++i)
    {
        d2 = std::min(d2, (closestOnTriangle(a[i], b[0], b[1], b[2], feature) - a[i]).squaredNorm());
        d2 = std::min(d2, (closestOnTriangle(b[i], a[0], a[1], a[2], feature) - b[i]).squaredNorm());
        for (int k = 0; k < 3; ++k)
        {
            d2 = std::min(d2, segmentDistSqr(a[i], a[(i + 1) % 3], b[k], b[(k + 1) % 3]));
        }
    }
    return std::sqrt(d2);
}


template<class Visit>
void triangleBVH::walkNearPairs
(
    const triangleBVH& A, const triangleBVH& B,
    const mat3& R, const vec3& t, double& best2, Visit visit
)
{
    const mat3 absR = R.cwiseAbs();
    auto distSqr = [&](int ia, int ib)
    {
        const node& na = A.nodes_[ia];
        const node& nb = B.nodes_[ib];
        const vec3 c = R*(0.5*(nb.lo + nb.hi)) + t;
        const vec3 h = absR*(0.5*(nb.hi - nb.lo));
        return boxDistSqr(na.lo, na.hi, c, h);
    };

    struct pairOfNodes { int a, b; };
    std::vector<pairOfNodes> stack;
    stack.reserve(128);
    stack.push_back({0, 0});
    std::array<vec3, 3> tb;
    while (!stack.empty())
    {
        const pairOfNodes pr = stack.back();
        stack.pop_back();
        if (distSqr(pr.a, pr.b) >= best2)
        {
            continue;
        }
        const node& na = A.nodes_[pr.a];
        const node& nb = B.nodes_[pr.b];
        if (na.count && nb.count)
        {
            for (int sb = nb.first; sb < nb.first + nb.count; ++sb)
            {
                for (int k = 0; k < 3; ++k)
                {
                    tb[k] = R*B.corners_[sb][k] + t;
                }
                for (int sa = na.first; sa < na.first + na.count; ++sa)
                {
                    if (visit(sa, sb, tb))
                    {
                        return;
                    }
                }
            }
            continue;
        }
        // Split the larger node (an inner one), nearer child on top
        const bool splitA =
            !na.count
         && (nb.count || (na.hi - na.lo).squaredNorm() >= (nb.hi - nb.lo).squaredNorm());
        const pairOfNodes p1 = splitA ? pairOfNodes{na.first, pr.b} : pairOfNodes{pr.a, nb.first};
        const pairOfNodes p2 = splitA ? pairOfNodes{na.right, pr.b} : pairOfNodes{pr.a, nb.right};
        const double d1 = distSqr(p1.a, p1.b), d2 = distSqr(p2.a, p2.b);
        if (d1 <= d2)
        {
            if (d2 < best2) stack.push_back(p2);
            if (d1 < best2) stack.push_back(p1);
        }
        else
        {
            if (d1 < best2) stack.push_back(p1);
            if (d2 < best2) stack.push_back(p2);
        }
    }
}


double triangleBVH::separation
(
    const triangleBVH& A, const triangleBVH& B,
    const mat3& R, const vec3& t, double cap, double stopBelow
)
{
    if (A.nodes_.empty() || B.nodes_.empty())
    {
        return cap;
    }
    // Round-off of the distances: relative to the sizes and the offset
    const double slack =
        1e-12*
        (
            (A.nodes_[0].hi - A.nodes_[0].lo).norm()
          + (B.nodes_[0].hi - B.nodes_[0].lo).norm() + t.norm()
        );

    double best = cap + slack;
    double best2 = best*best;
    bool stopped = false;
    walkNearPairs
    (
        A, B, R, t, best2,
        [&](int sa, int, const std::array<vec3, 3>& tb)
        {
            const double d = triangleDistance(A.corners_[sa], tb);
            if (d < best)
            {
                best = d;
                best2 = d*d;
                if (best < stopBelow)
                {
                    stopped = true;
                    return true;
                }
            }
            return false;
        }
    );
    return stopped ? best - slack : std::min(best, cap) - slack;
}


double triangleBVH::triangleClosestPoints
(
    const std::array<vec3, 3>& a, const std::array<vec3, 3>& b,
    vec3& pa, vec3& pb
)
{
    for (int i = 0; i < 3; ++i)
    {
        const int j = (i + 1) % 3;
        if
        (
            segmentCrossesTriangle(a[i], a[j], b[0], b[1], b[2])
         || segmentCrossesTriangle(b[i], b[j], a[0], a[1], a[2])
        )
        {
            pa = (a[0] + a[1] + a[2])/3;
            pb = (b[0] + b[1] + b[2])/3;
            return 0;
        }
    }
    double d2 = std::numeric_limits<double>::max();
    int feature;
    auto keep = [&](const vec3& x, const vec3& y)
    {
        const double e = (x - y).squaredNorm();
        if (e < d2)
        {
            d2 = e;
            pa = x;
            pb = y;
        }
    };
    vec3 x, y;
    for (int i = 0; i < 3; ++i)
    {
        keep(a[i], closestOnTriangle(a[i], b[0], b[1], b[2], feature));
        keep(closestOnTriangle(b[i], a[0], a[1], a[2], feature), b[i]);
        for (int k = 0; k < 3; ++k)
        {
            segmentClosestPoints(a[i], a[(i + 1) % 3], b[k], b[(k + 1) % 3], x, y);
            keep(x, y);
        }
    }
    return std::sqrt(d2);
}


triangleBVH::pairHit triangleBVH::closestPair
(
    const triangleBVH& A, const triangleBVH& B,
    const mat3& R, const vec3& t, double cap
)
{
    pairHit best;
    best.distance = cap;
    if (A.nodes_.empty() || B.nodes_.empty())
    {
        return best;
    }
    double best2 = cap*cap;
    vec3 pa, pb;
    walkNearPairs
    (
        A, B, R, t, best2,
        [&](int sa, int sb, const std::array<vec3, 3>& tb)
        {
            const double d = triangleClosestPoints(A.corners_[sa], tb, pa, pb);
            if (d < best.distance)
            {
                best.distance = d;
                best2 = d*d;
                best.pointA = pa;
                best.pointB = pb;
                best.faceA = A.faceOfSlot_[sa];
                best.faceB = B.faceOfSlot_[sb];
                return d == 0;
            }
            return false;
        }
    );
    return best;
}

} // End namespace immersedDEM
