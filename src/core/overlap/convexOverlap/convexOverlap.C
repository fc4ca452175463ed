#include "convexOverlap.H"
#include "convexPolyhedron.H"
#include "coreError.H"
#include "halfSpaceShape.H"
#include "overlapTools.H"
#include "triangleMeshShape.H"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace immersedDEM
{

namespace
{

const convexPolyhedron* convexOf(const shape& s)
{
    const triangleMeshShape* m = shapeAs<triangleMeshShape>(s);
    return m ? m->convex() : nullptr;
}


// A polygon of the polyhedron being clipped: its corners are
// points[start .. start + count), counter-clockwise seen from outside;
// rim[i] says whether the edge from corner i to the next is where A's
// surface meets B's
struct polygon
{
    int start;
    int count;
    bool fromA;
};


struct polyhedron
{
    std::vector<vec3> points;
    std::vector<char> rim;
    std::vector<polygon> polygons;

    void clear()
    {
        points.clear();
        rim.clear();
        polygons.clear();
    }
};


// A plane n.x <= d bounding the clipping body (n its outward normal)
struct plane
{
    vec3 n;
    double d;
};


// The work space of one evaluation (per thread: evaluate may run
// concurrently)
struct workspace
{
    polyhedron current, next;
    std::vector<double> dist;
    std::vector<vec3> cap;
    std::vector<Eigen::Vector2d> capUV;
    std::vector<int> capIndex;
    std::vector<plane> planes;
    std::vector<double> facing;
    std::vector<int> order;
    //- The vertices of the polyhedron being loaded, placed
    std::vector<vec3> placed;
};


//- Where the edge between points a and b (heights da and db over the
//  plane, of opposite signs) crosses the plane, computed from the
//  lexicographically smaller end: the two faces sharing the edge get the
//  same point to the last bit. (From either end, the two copies differ
//  by round-off; the cap's hull then met near-duplicates whose turns have
//  random signs, and lost its convexity: a ring's thin pieces gave
//  overlaps 9% off.)
inline vec3 crossing(const vec3& a, double da, const vec3& b, double db)
{
    const bool aFirst =
        a.x() < b.x()
     || (a.x() == b.x() && (a.y() < b.y() || (a.y() == b.y() && a.z() <= b.z())));
    return aFirst
        ? vec3(a + (da/(da - db))*(b - a))
        : vec3(b + (db/(db - da))*(a - b));
}


//- Clip the polyhedron by the plane; false when nothing of it is left
//  strictly behind the plane (no volume)
bool clip
(
    workspace& w, const plane& P, bool clipperIsA, double eps
)
{
    polyhedron& cur = w.current;
    const size_t nP = cur.points.size();
    w.dist.resize(nP);
    double hi = -std::numeric_limits<double>::max();
    double lo = std::numeric_limits<double>::max();
    for (size_t i = 0; i < nP; ++i)
    {
        const double d = P.n.dot(cur.points[i]) - P.d;
        w.dist[i] = d;
        hi = std::max(hi, d);
        lo = std::min(lo, d);
    }
    if (hi <= eps) return true;         // wholly behind: not cut
    if (lo >= -eps) return false;       // wholly beyond, or touching

    polyhedron& nxt = w.next;
    nxt.clear();
    w.cap.clear();
    for (const polygon& p : cur.polygons)
    {
        const int start = int(nxt.points.size());
        // An edge cut along the plane is rim where A's face meets B's
        const char cut = p.fromA && !clipperIsA;
        for (int i = 0; i < p.count; ++i)
        {
            const int a = p.start + i, b = p.start + (i + 1)%p.count;
            const double da = w.dist[a], db = w.dist[b];
            const char flag = cur.rim[a];
            if (da <= eps)
            {
                const bool bIn = db <= eps;
                nxt.points.push_back(cur.points[a]);
                nxt.rim.push_back(bIn || da < -eps ? flag : cut);
                if (da >= -eps) w.cap.push_back(cur.points[a]);
                if (!bIn && da < -eps)
                {
                    const vec3 x = crossing(cur.points[a], da, cur.points[b], db);
                    nxt.points.push_back(x);
                    nxt.rim.push_back(cut);
                    w.cap.push_back(x);
                }
            }
            else if (db < -eps)
            {
                const vec3 x = crossing(cur.points[a], da, cur.points[b], db);
                nxt.points.push_back(x);
                nxt.rim.push_back(flag);
                w.cap.push_back(x);
            }
        }
        const int count = int(nxt.points.size()) - start;
        if (count >= 3)
        {
            nxt.polygons.push_back({start, count, p.fromA});
        }
        else
        {
            nxt.points.resize(start);
            nxt.rim.resize(start);
        }
    }

    // The new face on the plane: the hull of the points on it,
    // counter-clockwise about the plane's normal (outward of the result)
    const vec3 u = P.n.unitOrthogonal();
    const vec3 v = P.n.cross(u);
    w.capUV.resize(w.cap.size());
    w.capIndex.resize(w.cap.size());
    for (size_t i = 0; i < w.cap.size(); ++i)
    {
        w.capUV[i] = Eigen::Vector2d(u.dot(w.cap[i]), v.dot(w.cap[i]));
        w.capIndex[i] = int(i);
    }
    const std::vector<int> hull = convexPolyhedron::planarHull(w.capUV, w.capIndex);
    if (hull.size() >= 3)
    {
        const int start = int(nxt.points.size());
        for (int i : hull)
        {
            nxt.points.push_back(w.cap[i]);
            // (the cap's edges meet the clipped body's faces: rim when
            // the cap is A's, i.e. A is the half-space)
            nxt.rim.push_back(clipperIsA);
        }
        nxt.polygons.push_back({start, int(hull.size()), clipperIsA});
    }
    std::swap(w.current, w.next);
    return !w.current.polygons.empty();
}

// Load a polyhedron's faces (pose p, coordinates about o) as the one
// being clipped; fromA: its faces are A's surface
void loadFaces
(
    workspace& w, const convexPolyhedron& poly, const bodyPose& p,
    const vec3& o, bool fromA
)
{
    w.current.clear();
    const mat3& R = p.rotation();
    const vec3 t = p.position() - o;
    // Each vertex placed once (it is a corner of three faces or more)
    w.placed.resize(poly.vertices().size());
    for (size_t k = 0; k < w.placed.size(); ++k)
    {
        w.placed[k] = R*poly.vertices()[k] + t;
    }
    for (const convexPolyhedron::face& f : poly.faces())
    {
        const int start = int(w.current.points.size());
        for (int k : f.corners)
        {
            w.current.points.push_back(w.placed[k]);
            w.current.rim.push_back(0);
        }
        w.current.polygons.push_back({start, int(f.corners.size()), fromA});
    }
}


// The integrals of a polyhedron over its faces: volume, centroid, and
// over the faces from A the vector area S, its moment M about the
// centroid, the absolute area, and the rim's length and moments
struct integrals
{
    double volume = 0;
    vec3 centroid = vec3::Zero();
    vec3 S = vec3::Zero();
    vec3 M = vec3::Zero();
    double absArea = 0;
    double rimLength = 0;
    vec3 rimFirst = vec3::Zero();       //!< about the centroid
    mat3 rimSecond = mat3::Zero();      //!< about the centroid
};


integrals integrate(const polyhedron& X)
{
    // About the mean of the corners
    vec3 ref = vec3::Zero();
    for (const vec3& x : X.points) ref += x;
    ref /= double(X.points.size());
    double sixV = 0;
    vec3 first = vec3::Zero();
    vec3 Mref = vec3::Zero();
    integrals r;
    for (const polygon& p : X.polygons)
    {
        const vec3 a = X.points[p.start] - ref;
        for (int i = 1; i + 1 < p.count; ++i)
        {
            const vec3 b = X.points[p.start + i] - ref;
            const vec3 c = X.points[p.start + i + 1] - ref;
            const double six = a.dot(b.cross(c));
            sixV += six;
            first += six*(a + b + c);
            if (p.fromA)
            {
                const vec3 va = 0.5*(b - a).cross(c - a);
                r.S += va;
                Mref += ((a + b + c)/3).cross(va);
                r.absArea += va.norm();
            }
        }
        if (p.fromA)
        {
            for (int i = 0; i < p.count; ++i)
            {
                if (!X.rim[p.start + i]) continue;
                const vec3 e0 = X.points[p.start + i] - ref;
                const vec3 e1 = X.points[p.start + (i + 1)%p.count] - ref;
                const double L = (e1 - e0).norm();
                r.rimLength += L;
                r.rimFirst += 0.5*L*(e0 + e1);
                r.rimSecond +=
                    L/3*(e0*e0.transpose() + e1*e1.transpose())
                  + L/6*(e0*e1.transpose() + e1*e0.transpose());
            }
        }
    }
    r.volume = sixV/6;
    const vec3 c = sixV != 0 ? vec3(first/(4*sixV)) : vec3::Zero();
    r.centroid = c + ref;
    r.M = Mref - c.cross(r.S);
    // The rim's moments about the centroid
    r.rimSecond += -c*r.rimFirst.transpose() - r.rimFirst*c.transpose() + r.rimLength*c*c.transpose();
    r.rimFirst -= r.rimLength*c;
    return r;
}

} // End anonymous namespace


bool convexOverlap::handles(const shape& A, const shape& B)
{
    const bool a = convexOf(A) != nullptr, b = convexOf(B) != nullptr;
    const bool ha = A.shapeKind() == shape::kind::halfSpace;
    const bool hb = B.shapeKind() == shape::kind::halfSpace;
    return (a && b) || (a && hb) || (ha && b);
}


contactGeometry convexOverlap::evaluate
(
    const shape& A, const bodyPose& pA,
    const shape& B, const bodyPose& pB,
    const overlapSettings& settings
) const
{
    if (!handles(A, B))
    {
        throw coreError
        (
            "Overlap method 'convex' needs two convex triangle-mesh bodies, or"
            " a convex triangle mesh and a plane, not " + A.type() + " and "
          + B.type() + "; use virtualMesh"
        );
    }
    contactGeometry g;
    const convexPolyhedron* cA = convexOf(A);
    const convexPolyhedron* cB = convexOf(B);

    // The clipped body (P) and the clipping one (C): A's faces are
    // clipped by B's planes, unless A is the half-space
    const bool clipperIsA = cA == nullptr;
    const convexPolyhedron& poly = clipperIsA ? *cB : *cA;
    const bodyPose& pP = clipperIsA ? pB : pA;
    const bodyPose& pC = clipperIsA ? pA : pB;
    const convexPolyhedron* cC = clipperIsA ? nullptr : cB;

    // Apart by the bounding spheres
    const double rP = poly.radius();
    const double rC = cC ? cC->radius() : 0;
    if (cC)
    {
        if ((pP.position() - pC.position()).norm() > rP + rC) return g;
    }
    else
    {
        const vec3 n = pC.vectorToWorld(vec3::UnitZ());
        if (n.dot(pP.position() - pC.position()) > rP) return g;
    }

    // Coordinates about a point near both bodies: of the size of the
    // bodies, whatever their distance from the world origin
    const vec3 o = cC ? vec3(0.5*(pP.position() + pC.position())) : pP.position();
    const double eps = 1e-12*std::max(rP, rC);

    static thread_local workspace w;
    loadFaces(w, poly, pP, o, !clipperIsA);

    // The clipping planes, those facing the clipped body first
    w.planes.clear();
    if (cC)
    {
        const mat3& R = pC.rotation();
        const vec3 t = pC.position() - o;
        for (const convexPolyhedron::face& f : cC->faces())
        {
            const vec3 n = R*f.normal;
            w.planes.push_back({n, f.offset + n.dot(t)});
        }
    }
    else
    {
        const vec3 n = pC.vectorToWorld(vec3::UnitZ());
        w.planes.push_back({n, n.dot(pC.position() - o)});
    }
    const vec3 towardP = pP.position() - pC.position();
    w.facing.resize(w.planes.size());
    w.order.resize(w.planes.size());
    for (size_t i = 0; i < w.planes.size(); ++i)
    {
        w.facing[i] = w.planes[i].n.dot(towardP);
        w.order[i] = int(i);
    }
    std::sort
    (
        w.order.begin(), w.order.end(),
        [&](int i, int j) { return w.facing[i] > w.facing[j] || (w.facing[i] == w.facing[j] && i < j); }
    );
    for (int i : w.order)
    {
        if (!clip(w, w.planes[i], clipperIsA, eps)) return g;
    }

    const integrals X = integrate(w.current);
    const double volume = X.volume;
    const double Vmin = std::min(cA ? A.volume() : B.volume(), cB ? B.volume() : A.volume());
    if (!(volume > 1e-12*Vmin)) return g;

    contactRegion r;
    r.volume = volume;
    r.point = X.centroid + o;
    for (const vec3& x : w.current.points) r.box.add(x + o);
    const vec3 centreLine = pB.position() - pA.position();
    const vec3& S = X.S;
    if (S.norm() > 1e-9*X.absArea)
    {
        r.area = S.norm();
        r.areaVector = S;
        r.areaMoment = X.M;
        r.normal = S/r.area;
        if (!settings.areaVectorNormal && X.rimLength > 0)
        {
            // The least-squares plane through the rim (a curve of
            // segments, uniform along its length)
            const vec3 m = X.rimFirst/X.rimLength;
            const mat3 cov = X.rimSecond/X.rimLength - m*m.transpose();
            const Eigen::SelfAdjointEigenSolver<mat3> eig(cov);
            const vec3 l = eig.eigenvalues();
            if (l[2] > 0 && l[1] > 1e-6*l[2] && l[0] < 0.25*l[1])
            {
                vec3 n = eig.eigenvectors().col(0);
                if (n.dot(S) < 0) n = -n;
                r.normal = n.normalized();
            }
        }
    }
    else
    {
        // S vanishes: A wholly inside B (A's closed surface: S and M
        // zero), or A's faces inside B in balanced opposite pairs (a slab
        // passing through B: translation leaves V unchanged, rotation not,
        // so M is kept)
        // (S itself is then round-off: zero, not a direction)
        r.normal = overlapTools::firstDirection({centreLine});
        r.areaMoment = X.M;
    }
    g.regions.push_back(r);
    return g;
}


bool convexOverlap::againstWall
(
    const shape& M, const bodyPose& pM,
    const std::vector<std::pair<vec3, double>>& wallPlanes,
    bool meshFirst,
    contactGeometry& g
)
{
    g = contactGeometry();
    const convexPolyhedron* poly = convexOf(M);
    if (!poly || wallPlanes.empty())
    {
        return false;
    }
    const vec3 o = pM.position();
    const double eps = 1e-12*poly->radius();
    static thread_local workspace w;

    // The whole body, then its part in front of every plane (the fluid's
    // side): the overlap is the rest
    loadFaces(w, *poly, pM, o, true);
    const integrals P = integrate(w.current);
    bool left = true;
    for (const auto& q : wallPlanes)
    {
        // Fluid: n.x >= c, i.e. (-n).x <= -c, about o
        left = clip(w, {-q.first, -(q.second - q.first.dot(o))}, false, eps);
        if (!left) break;
    }
    if (!left)
    {
        // Nothing in front of the planes: wholly in the wall
        return false;
    }
    const integrals F = integrate(w.current);
    const double V = P.volume - F.volume;
    if (!(V > 1e-12*P.volume))
    {
        return true;    // touching at most: no region
    }
    contactRegion r;
    r.volume = V;
    const vec3 c = (P.volume*P.centroid - F.volume*F.centroid)/V;
    r.point = c + o;
    // The body's surface is closed: its part in the wall has the vector
    // area and moment opposite to those of its part in front
    const vec3 S = -F.S;
    const vec3 Mo = -(F.M + (F.centroid - c).cross(F.S));
    if (!(S.norm() > 1e-9*P.absArea))
    {
        return false;
    }
    const double sign = meshFirst ? 1 : -1;
    r.area = S.norm();
    r.areaVector = sign*S;
    r.areaMoment = sign*Mo;
    r.normal = sign*S/r.area;
    g.regions.push_back(r);
    return true;
}

} // End namespace immersedDEM
