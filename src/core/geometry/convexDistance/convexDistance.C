#include "convexDistance.H"
#include "wallMeshShape.H"
#include "triangleMeshShape.H"
#include "convexPolyhedron.H"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace immersedDEM
{

namespace
{

// A point of the Minkowski difference and the corners it came from
struct point
{
    vec3 w, a, b;
};

// The simplex: up to four points and their weights in the nearest point
struct simplex
{
    std::array<point, 4> p;
    std::array<double, 4> weight{};
    int n = 0;

    // Keep the points listed (indices into p), with their weights
    void keep(std::initializer_list<std::pair<int, double>> kept)
    {
        std::array<point, 4> q;
        std::array<double, 4> w{};
        int m = 0;
        for (const auto& k : kept)
        {
            q[m] = p[k.first];
            w[m] = k.second;
            ++m;
        }
        p = q;
        weight = w;
        n = m;
    }

    vec3 nearest() const
    {
        vec3 v = vec3::Zero();
        for (int i = 0; i < n; ++i) v += weight[i]*p[i].w;
        return v;
    }
};


// The point of the segment p[i]p[j] nearest the origin, as weights
void segment(simplex& s, int i, int j)
{
    const vec3& A = s.p[i].w;
    const vec3 AB = s.p[j].w - A;
    const double L2 = AB.squaredNorm();
    const double u = L2 > 0 ? -A.dot(AB)/L2 : 0;
    if (u <= 0)
    {
        s.keep({{i, 1.0}});
    }
    else if (u >= 1)
    {
        s.keep({{j, 1.0}});
    }
    else
    {
        s.keep({{i, 1 - u}, {j, u}});
    }
}


// The point of the triangle p[i]p[j]p[k] nearest the origin: the Voronoi
// regions of its corners, edges and inside, in barycentric terms
void triangle(simplex& s, int i, int j, int k)
{
    const vec3& A = s.p[i].w;
    const vec3& B = s.p[j].w;
    const vec3& C = s.p[k].w;
    const vec3 AB = B - A, AC = C - A;
    const double d1 = -AB.dot(A), d2 = -AC.dot(A);
    if (d1 <= 0 && d2 <= 0)
    {
        s.keep({{i, 1.0}});
        return;
    }
    const double d3 = -AB.dot(B), d4 = -AC.dot(B);
    if (d3 >= 0 && d4 <= d3)
    {
        s.keep({{j, 1.0}});
        return;
    }
    const double vc = d1*d4 - d3*d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0)
    {
        const double u = d1/(d1 - d3);
        s.keep({{i, 1 - u}, {j, u}});
        return;
    }
    const double d5 = -AB.dot(C), d6 = -AC.dot(C);
    if (d6 >= 0 && d5 <= d6)
    {
        s.keep({{k, 1.0}});
        return;
    }
    const double vb = d5*d2 - d1*d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0)
    {
        const double u = d2/(d2 - d6);
        s.keep({{i, 1 - u}, {k, u}});
        return;
    }
    const double va = d3*d6 - d5*d4;
    if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
    {
        const double u = (d4 - d3)/((d4 - d3) + (d5 - d6));
        s.keep({{j, 1 - u}, {k, u}});
        return;
    }
    const double sum = va + vb + vc;
    if (!(sum > 0))
    {
        // Degenerate (collinear corners): the nearest of its edges
        simplex e1 = s, e2 = s, e3 = s;
        segment(e1, i, j);
        segment(e2, j, k);
        segment(e3, i, k);
        const double n1 = e1.nearest().squaredNorm();
        const double n2 = e2.nearest().squaredNorm();
        const double n3 = e3.nearest().squaredNorm();
        s = n1 <= n2 && n1 <= n3 ? e1 : n2 <= n3 ? e2 : e3;
        return;
    }
    const double v = vb/sum, w = vc/sum;
    s.keep({{i, 1 - v - w}, {j, v}, {k, w}});
}


// The tetrahedron: the origin inside it (returns true), or the nearest of
// the faces it lies outside of
bool tetrahedron(simplex& s)
{
    static const int face[4][4] =
        {{0, 1, 2, 3}, {0, 1, 3, 2}, {0, 2, 3, 1}, {1, 2, 3, 0}};
    bool outside = false;
    simplex best;
    double bestD2 = std::numeric_limits<double>::max();
    for (const auto& f : face)
    {
        const vec3& A = s.p[f[0]].w;
        const vec3 n = (s.p[f[1]].w - A).cross(s.p[f[2]].w - A);
        const double sideOrigin = -A.dot(n);
        const double sideOther = (s.p[f[3]].w - A).dot(n);
        // The origin beyond this face (or the tetrahedron flat there)
        if (sideOrigin*sideOther < 0 || sideOther == 0)
        {
            outside = true;
            simplex t = s;
            triangle(t, f[0], f[1], f[2]);
            const double d2 = t.nearest().squaredNorm();
            if (d2 < bestD2)
            {
                bestD2 = d2;
                best = t;
            }
        }
    }
    if (!outside)
    {
        return true;
    }
    s = best;
    return false;
}


// The corner of the set farthest along d (x = R c + t)
vec3 support(const std::vector<vec3>& c, const mat3& R, const vec3& t, const vec3& d)
{
    const vec3 local = R.transpose()*d;
    size_t best = 0;
    double far = -std::numeric_limits<double>::max();
    for (size_t i = 0; i < c.size(); ++i)
    {
        const double h = c[i].dot(local);
        if (h > far)
        {
            far = h;
            best = i;
        }
    }
    return R*c[best] + t;
}

} // End anonymous namespace


convexClosest convexDistance
(
    const std::vector<vec3>& a,
    const std::vector<vec3>& b,
    const mat3& R,
    const vec3& t
)
{
    convexClosest r;
    if (a.empty() || b.empty())
    {
        return r;
    }
    const mat3 I = mat3::Identity();
    const vec3 zero = vec3::Zero();
    double size = 0;
    vec3 ca = vec3::Zero(), cb = vec3::Zero();
    for (const vec3& x : a) { size = std::max(size, x.norm()); ca += x; }
    for (const vec3& x : b) { size = std::max(size, x.norm()); cb += x; }
    ca /= double(a.size());
    cb = R*(cb/double(b.size())) + t;
    const double tiny = 1e-12*size;

    auto supportPoint = [&](const vec3& d)
    {
        point p;
        p.a = support(a, I, zero, d);
        p.b = support(b, R, t, -d);
        p.w = p.a - p.b;
        return p;
    };

    simplex s;
    vec3 d = ca - cb;
    if (d.squaredNorm() == 0) d = vec3::UnitX();
    s.p[0] = supportPoint(-d);
    s.weight[0] = 1;
    s.n = 1;
    vec3 v = s.p[0].w;
    for (int iter = 0; iter < 64; ++iter)
    {
        const double v2 = v.squaredNorm();
        if (v2 <= tiny*tiny)
        {
            r.intersecting = true;
            return r;
        }
        const point w = supportPoint(-v);
        // No point of the difference is nearer the origin along v than v
        // itself (to round-off): v is the nearest
        if (v2 - v.dot(w.w) <= 1e-12*v2)
        {
            break;
        }
        bool known = false;
        for (int i = 0; i < s.n; ++i)
        {
            known = known || (s.p[i].w - w.w).squaredNorm() <= tiny*tiny;
        }
        if (known)
        {
            break;
        }
        const simplex before = s;
        s.p[s.n] = w;
        ++s.n;
        if (s.n == 2)
        {
            segment(s, 0, 1);
        }
        else if (s.n == 3)
        {
            triangle(s, 0, 1, 2);
        }
        else if (tetrahedron(s))
        {
            r.intersecting = true;
            return r;
        }
        const vec3 next = s.nearest();
        // The distance must shrink; where round-off stops it, v is it
        if (!(next.squaredNorm() < v2))
        {
            s = before;
            break;
        }
        v = next;
    }
    r.distance = v.norm();
    if (!(r.distance > tiny))
    {
        r.intersecting = true;
        r.distance = 0;
        return r;
    }
    r.pointA = vec3::Zero();
    r.pointB = vec3::Zero();
    for (int i = 0; i < s.n; ++i)
    {
        r.pointA += s.weight[i]*s.p[i].a;
        r.pointB += s.weight[i]*s.p[i].b;
    }
    return r;
}


convexWallGap convexWallDistance
(
    const wallMeshShape& wall, const bodyPose& pW,
    const std::vector<vec3>& corners, double radius, const bodyPose& pM,
    double reach
)
{
    convexWallGap r;
    const vec3 centre = pW.toBody(pM.position());
    if (wall.clearOf(centre, radius + reach))
    {
        r.known = true;
        r.beyondReach = true;
        r.gap = reach;
        return r;
    }
    std::vector<wallMeshShape::plane> planes;
    if (!wall.convexFluidNear(centre, radius + reach, planes, 4096) || planes.empty())
    {
        return r;
    }
    r.known = true;
    r.gap = std::numeric_limits<double>::max();
    for (const vec3& c : corners)
    {
        const vec3 x = pW.toBody(pM.toWorld(c));
        for (const wallMeshShape::plane& q : planes)
        {
            const double h = q.normal.dot(x) - q.offset;
            if (h < r.gap)
            {
                r.gap = h;
                r.pointBody = x;
                r.normal = q.normal;
            }
        }
    }
    // Faces further than reach from the body were not looked at: beyond
    // reach the gap is only known to exceed it
    if (r.gap > reach)
    {
        r.gap = reach;
        r.beyondReach = true;
    }
    r.pointWall = pW.toWorld(r.pointBody - r.gap*r.normal);
    r.pointBody = pW.toWorld(r.pointBody);
    r.normal = pW.vectorToWorld(r.normal);
    return r;
}


convexWallGap convexWallDistance
(
    const shape& A, const bodyPose& pA,
    const shape& B, const bodyPose& pB,
    double reach, bool& wallFirst
)
{
    const auto* wA = shapeAs<wallMeshShape>(A);
    const auto* wB = shapeAs<wallMeshShape>(B);
    const auto* mA = shapeAs<triangleMeshShape>(A);
    const auto* mB = shapeAs<triangleMeshShape>(B);
    wallFirst = wA != nullptr;
    // A body of convex pieces: the least height over the planes of its
    // pieces' corners is that of its own points (a height is least at a
    // corner of its hull)
    auto corners = [](const triangleMeshShape& m) -> const std::vector<vec3>*
    {
        if (m.convex()) return &m.convex()->vertices();
        if (!m.pieces().empty()) return &m.points();
        return nullptr;
    };
    if (wA && mB && corners(*mB))
    {
        return convexWallDistance(*wA, pA, *corners(*mB), B.boundingRadius(), pB, reach);
    }
    if (wB && mA && corners(*mA))
    {
        return convexWallDistance(*wB, pB, *corners(*mA), A.boundingRadius(), pA, reach);
    }
    return convexWallGap();
}

bool madeOfConvexParts(const triangleMeshShape& m)
{
    return m.convex() || !m.pieces().empty();
}


convexClosest closestParts
(
    const triangleMeshShape& A, const bodyPose& pA,
    const triangleMeshShape& B, const bodyPose& pB,
    double cap, double stopBelow, bool lowerBoundEnough
)
{
    const mat3 RaT = pA.rotation().transpose();
    // 1. The hulls
    {
        const mat3 R = RaT*pB.rotation();
        const vec3 t = RaT*(pB.position() - pA.position());
        convexClosest h = convexDistance(A.points(), B.points(), R, t);
        if (!h.intersecting)
        {
            if (h.distance >= cap || (lowerBoundEnough && h.distance > stopBelow))
            {
                h.distance = std::min(h.distance, cap);
                return h;
            }
            // On both surfaces (B's point back in B's frame)
            const double tol = 1e-9*std::max(A.boundingRadius(), B.boundingRadius());
            if
            (
                std::abs(A.signedDistance(h.pointA)) <= tol
             && std::abs(B.signedDistance(R.transpose()*(h.pointB - t))) <= tol
            )
            {
                return h;
            }
        }
    }

    // 2. The parts
    struct part
    {
        const std::vector<vec3>* corners;
        bodyPose pose;
        double radius;
    };
    // The parts of M whose balls come nearer than cap to the other body's
    auto partsOf = [cap](const triangleMeshShape& M, const bodyPose& p, const vec3& c, double r)
    {
        std::vector<part> out;
        if (M.convex())
        {
            out.push_back({&M.convex()->vertices(), p, M.boundingRadius()});
            return out;
        }
        for (const auto& q : M.pieces())
        {
            const bodyPose pq = p*q->bodyInFile();
            if ((pq.position() - c).norm() - q->boundingRadius() - r < cap)
            {
                out.push_back({&q->convex()->vertices(), pq, q->boundingRadius()});
            }
        }
        return out;
    };
    const std::vector<part> a = partsOf(A, pA, pB.position(), B.boundingRadius());
    const std::vector<part> b = partsOf(B, pB, pA.position(), A.boundingRadius());
    static thread_local std::vector<std::pair<double, std::pair<int, int>>> order;
    order.clear();
    for (size_t i = 0; i < a.size(); ++i)
    {
        for (size_t j = 0; j < b.size(); ++j)
        {
            const double balls =
                (a[i].pose.position() - b[j].pose.position()).norm() - a[i].radius - b[j].radius;
            if (balls < cap) order.push_back({balls, {int(i), int(j)}});
        }
    }
    std::sort(order.begin(), order.end());
    convexClosest best;
    best.distance = cap;
    for (const auto& o : order)
    {
        if (o.first >= best.distance) break;
        const part& x = a[o.second.first];
        const part& y = b[o.second.second];
        const mat3 RxT = x.pose.rotation().transpose();
        const convexClosest c = convexDistance
        (
            *x.corners, *y.corners,
            RxT*y.pose.rotation(), RxT*(y.pose.position() - x.pose.position())
        );
        if (c.intersecting)
        {
            best = c;
            best.distance = 0;
            return best;
        }
        if (c.distance < best.distance)
        {
            // The points from x's frame to A's
            best = c;
            best.pointA = RaT*(x.pose.toWorld(c.pointA) - pA.position());
            best.pointB = RaT*(x.pose.toWorld(c.pointB) - pA.position());
            if (best.distance < stopBelow) return best;
        }
    }
    return best;
}

} // End namespace immersedDEM
