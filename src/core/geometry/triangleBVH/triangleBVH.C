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


template<class Visit>
void triangleBVH::forSlotsBelow(const vec3& n, const double level, Visit visit) const
{
    const vec3 absN = n.cwiseAbs();
    std::vector<int> stack{0};
    while (!stack.empty())
    {
        const node& nd = nodes_[stack.back()];
        stack.pop_back();
        if (n.dot(0.5*(nd.lo + nd.hi)) - absN.dot(0.5*(nd.hi - nd.lo)) > level)
        {
            continue;
        }
        if (!nd.count)
        {
            stack.push_back(nd.first);
            stack.push_back(nd.right);
            continue;
        }
        for (int s = nd.first; s < nd.first + nd.count; ++s)
        {
            visit(s);
        }
    }
}


bool triangleBVH::meanCornerBelow
(
    const vec3& n, double low, double band, vec3& mean
) const
{
    if (nodes_.empty() || !(band > 0))
    {
        return false;
    }
    const double level = low + band;
    // A corner is stored once per triangle at it: each counted once
    std::vector<std::array<double, 3>> found;
    forSlotsBelow(n, level, [&](const int s)
    {
        for (const vec3& x : corners_[s])
        {
            if (n.dot(x) < level)
            {
                found.push_back({x.x(), x.y(), x.z()});
            }
        }
    });
    std::sort(found.begin(), found.end());
    found.erase(std::unique(found.begin(), found.end()), found.end());
    vec3 sum = vec3::Zero();
    double weight = 0;
    for (const auto& c : found)
    {
        const vec3 x(c[0], c[1], c[2]);
        const double w = std::max(0.0, 1 - (n.dot(x) - low)/band);
        sum += w*x;
        weight += w;
    }
    if (!(weight > 0))
    {
        return false;
    }
    mean = sum/weight;
    return true;
}


triangleBVH::footprint triangleBVH::footprintBelow
(
    const vec3& n, double low, double band
) const
{
    footprint f;
    if (nodes_.empty() || !(band > 0))
    {
        return f;
    }
    // Weighted sums of area, first and second moments (about the first
    // corner found, for round-off: the face is small against the body)
    double A = 0, H = 0;
    vec3 first = vec3::Zero();
    mat3 second = mat3::Zero();
    bool originSet = false;
    vec3 origin = vec3::Zero();
    forSlotsBelow(n, low + band, [&](const int s)
    {
        const auto& t = corners_[s];
        double w = 1;
        for (const vec3& x : t)
        {
            w = std::min(w, 1 - (n.dot(x) - low)/band);
        }
        if (!(w > 0))
        {
            return;
        }
        if (!originSet)
        {
            origin = t[0];
            originSet = true;
        }
        // Facing the other body: the outward normal within a few
        // degrees of -n, the weight fading to zero at 0.05 rad (a
        // curved surface's facets do not make a flat film)
        const vec3 normal = (t[1] - t[0]).cross(t[2] - t[0]);
        const double twiceArea = normal.norm();
        if (!(twiceArea > 0))
        {
            return;
        }
        const double cosine = -n.dot(normal)/twiceArea;
        w = std::min(w, 1 - (1 - cosine)/(1 - std::cos(0.05)));
        if (!(w > 0))
        {
            return;
        }
        const vec3 a = t[0] - origin, b = t[1] - origin, c = t[2] - origin;
        const double area = 0.5*twiceArea;
        const vec3 sum = a + b + c;
        // Int x x^T dA over a triangle = A/12 (sum of v v^T + s s^T)
        A += w*area;
        H += w*area*((n.dot(t[0]) + n.dot(t[1]) + n.dot(t[2]))/3 - low);
        first += w*area*sum/3;
        second += w*area/12*(a*a.transpose() + b*b.transpose() + c*c.transpose() + sum*sum.transpose());
    });
    if (!(A > 0))
    {
        return f;
    }
    const vec3 m = first/A;
    f.area = A;
    f.centroid = origin + m;
    f.spread = second/A - m*m.transpose();
    f.height = H/A;
    return f;
}


double triangleBVH::minAlong(const vec3& n) const
{
    double best = std::numeric_limits<double>::max();
    if (nodes_.empty())
    {
        return best;
    }
    const vec3 absN = n.cwiseAbs();
    auto lower = [&](const node& nd)
    {
        return n.dot(0.5*(nd.lo + nd.hi)) - absN.dot(0.5*(nd.hi - nd.lo));
    };
    int stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top)
    {
        const node& nd = nodes_[stack[--top]];
        if (lower(nd) >= best)
        {
            continue;
        }
        if (nd.count)
        {
            for (int s = nd.first; s < nd.first + nd.count; ++s)
            {
                for (const vec3& x : corners_[s])
                {
                    best = std::min(best, n.dot(x));
                }
            }
            continue;
        }
        const int l = nd.first, r = nd.right;
        if (lower(nodes_[l]) <= lower(nodes_[r]))
        {
            stack[top++] = r;
            stack[top++] = l;
        }
        else
        {
            stack[top++] = l;
            stack[top++] = r;
        }
    }
    return best;
}


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
