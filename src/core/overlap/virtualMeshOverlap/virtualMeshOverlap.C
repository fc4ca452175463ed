#include "virtualMeshOverlap.H"
#include "convexOverlap.H"
#include "convexPolyhedron.H"
#include "halfSpaceShape.H"
#include "triangleMeshShape.H"
#include "overlapTools.H"
#include "sphereOverlap.H"
#include "sphereShape.H"
#include "wallMeshShape.H"
#include "surfaceDistance.H"
#include "coreError.H"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <memory>

namespace immersedDEM
{

namespace
{

using overlapTools::cellIndex;

// What one base cell contributes
struct baseCellSum
{
    double volume = 0;
    vec3 first = vec3::Zero();
    //- Outward area vector of A's surface inside B: the integral of n_A
    //  over it (|.| is the contact area, its direction the mean normal)
    vec3 areaVector = vec3::Zero();
    //- Its moment about the origin: integral of x x n_A
    vec3 areaMoment = vec3::Zero();
    std::vector<vec3> edgePoints;
    //- The leaves holding overlap
    axisAlignedBox box;
};

//- phi(t) = alpha t^2 + beta t + gamma along a column x + t e_ax: the
//  surface model of sp (negative inside) there
struct columnQuadratic
{
    double alpha, beta, gamma;
};

//- The surface model of sp over a leaf's columns: phi = n.r + (1/2) r^T S r,
//  r = x - point (S n = 0: only the tangential part of r counts), with the
//  column at offsets (a, b) along (e_u, e_w) from the leaf centre c:
//  beta and gamma are polynomials in a and b, set up once per leaf
class leafSurface
{
    double alpha_, beta0_, betaA_, betaB_;
    double gamma0_, gammaA_, gammaB_, gammaAA_, gammaAB_, gammaBB_;

public:

    leafSurface(const surfacePoint& sp, const vec3& c, int ax, int u, int w)
    {
        const mat3& S = sp.curvature;
        const vec3 r0 = c - sp.point;
        const vec3 Sr0 = S*r0;
        alpha_ = 0.5*S(ax, ax);
        beta0_ = sp.normal[ax] + Sr0[ax];
        betaA_ = S(ax, u);
        betaB_ = S(ax, w);
        gamma0_ = sp.normal.dot(r0) + 0.5*r0.dot(Sr0);
        gammaA_ = sp.normal[u] + Sr0[u];
        gammaB_ = sp.normal[w] + Sr0[w];
        gammaAA_ = 0.5*S(u, u);
        gammaAB_ = S(u, w);
        gammaBB_ = 0.5*S(w, w);
    }

    columnQuadratic column(double a, double b) const
    {
        return
        {
            alpha_,
            beta0_ + a*betaA_ + b*betaB_,
            gamma0_ + a*(gammaA_ + a*gammaAA_ + b*gammaAB_) + b*(gammaB_ + b*gammaBB_)
        };
    }
};

//- The part of a column (at most three pieces) where every clipped
//  quadratic is <= 0
struct columnSet
{
    static constexpr int maxPieces = 8;
    int size = 1;
    double lo[maxPieces], hi[maxPieces];

    columnSet(double l, double h) { lo[0] = l; hi[0] = h; }

    void keep(double l, double h, columnSet& out) const
    {
        for (int k = 0; k < size; ++k)
        {
            const double a = std::max(lo[k], l), b = std::min(hi[k], h);
            if (b > a && out.size < maxPieces)
            {
                out.lo[out.size] = a;
                out.hi[out.size] = b;
                ++out.size;
            }
        }
    }

    void clip(const columnQuadratic& q)
    {
        if (size == 0) return;
        const double inf = std::numeric_limits<double>::infinity();
        columnSet out(0, 0);
        out.size = 0;
        // Linear where the bending moves the crossing by less than 1e-6 of
        // the column
        const double span = hi[size - 1] - lo[0];
        if (std::abs(q.alpha)*span <= 1e-6*std::abs(q.beta))
        {
            if (q.beta > 0)
            {
                keep(-inf, -q.gamma/q.beta, out);
            }
            else if (q.beta < 0)
            {
                keep(-q.gamma/q.beta, inf, out);
            }
            else if (q.gamma <= 0)
            {
                keep(-inf, inf, out);
            }
        }
        else
        {
            const double disc = q.beta*q.beta - 4*q.alpha*q.gamma;
            if (disc <= 0)
            {
                // One sign throughout: that of alpha
                if (q.alpha < 0) keep(-inf, inf, out);
            }
            else
            {
                // Roots without cancellation
                const double sq = std::sqrt(disc);
                const double qq = -0.5*(q.beta + (q.beta >= 0 ? sq : -sq));
                double t1 = qq/q.alpha, t2 = q.gamma/qq;
                if (t1 > t2) std::swap(t1, t2);
                if (q.alpha > 0)
                {
                    keep(t1, t2, out);
                }
                else
                {
                    keep(-inf, t1, out);
                    keep(t2, inf, out);
                }
            }
        }
        *this = out;
    }

    //- Keep the part inside the union of the n pieces [l_k, h_k]
    void keepPieces(const double* l, const double* h, int n)
    {
        columnSet out(0, 0);
        out.size = 0;
        for (int k = 0; k < n; ++k) keep(l[k], h[k], out);
        *this = out;
    }

    bool contains(double t) const
    {
        for (int k = 0; k < size; ++k)
        {
            if (t >= lo[k] && t <= hi[k]) return true;
        }
        return false;
    }
};


//- A faceted surface (a mesh) in a leaf, exactly: its triangles near the
//  leaf, each crossing a column where the column's point falls in the
//  triangle's shadow on the plane across the columns. The shadows of a
//  sheet's triangles tile that plane once: a point on a shared edge or
//  corner belongs to one triangle only (the top-left rule on the edge
//  function, evaluated with the edge's ends in a fixed order, so the two
//  triangles sharing an edge compute the same number). Used where the
//  surface in the leaf is not one smooth sheet: at an edge or corner of a
//  faceted body, where one tangent plane would bevel the edge (a wedge of
//  volume in every leaf along the rim of a face-on-face contact, whatever
//  its depth), and where two sheets of a thin part are within the leaf.
class leafFacets
{
    struct projected
    {
        double p[3][2];     //!< corners (u, w) relative to the leaf centre, CCW
        double t0, tu, tw;  //!< the plane: t = t0 + tu a + tw b
        vec3 normal;
        double nAx;
    };

    std::vector<projected> tris_;
    vec3 c_;
    int ax_, u_, w_;
    double chord2_;     //!< squared radius of the ball holding every crossing
    bool centreInside_;

    static double edgeFunction(const double* P, const double* Q, double a, double b)
    {
        // The same number, negated, for the edge walked the other way
        const bool swap = P[0] > Q[0] || (P[0] == Q[0] && P[1] > Q[1]);
        const double* X = swap ? Q : P;
        const double* Y = swap ? P : Q;
        const double e = (Y[0] - X[0])*(b - X[1]) - (Y[1] - X[1])*(a - X[0]);
        return swap ? -e : e;
    }

    static bool covers(const projected& t, double a, double b)
    {
        for (int k = 0; k < 3; ++k)
        {
            const double* P = t.p[k];
            const double* Q = t.p[(k + 1) % 3];
            const double e = edgeFunction(P, Q, a, b);
            if (e < 0) return false;
            if (e == 0)
            {
                // Top-left: of the two directions of an edge exactly one
                const double du = Q[0] - P[0], dw = Q[1] - P[1];
                if (!(dw < 0 || (dw == 0 && du < 0))) return false;
            }
        }
        return true;
    }

public:

    //- The world triangles near a leaf of centre c, columns along ax;
    //  radius: that of the ball the triangles were gathered in;
    //  centreInside: the side of the body the centre is on
    leafFacets
    (
        const std::vector<surfaceFacet>& world, const vec3& c, int ax, int u, int w,
        double radius, bool centreInside
    )
    :
        c_(c), ax_(ax), u_(u), w_(w), chord2_(radius*radius),
        centreInside_(centreInside)
    {
        tris_.reserve(world.size());
        for (const surfaceFacet& f : world)
        {
            const double nAx = f.normal[ax];
            if (nAx == 0) continue;     // parallel to the columns: no shadow
            projected t;
            const vec3* x[3] = {&f.a, &f.b, &f.c};
            for (int k = 0; k < 3; ++k)
            {
                t.p[k][0] = (*x[k])[u] - c[u];
                t.p[k][1] = (*x[k])[w] - c[w];
            }
            const double area2 =
                (t.p[1][0] - t.p[0][0])*(t.p[2][1] - t.p[0][1])
              - (t.p[1][1] - t.p[0][1])*(t.p[2][0] - t.p[0][0]);
            if (area2 == 0) continue;
            if (area2 < 0)
            {
                std::swap(t.p[1][0], t.p[2][0]);
                std::swap(t.p[1][1], t.p[2][1]);
            }
            // n.(x - a) = 0 along x = c + a e_u + b e_w + t e_ax
            t.t0 = f.normal.dot(f.a - c)/nAx;
            t.tu = -f.normal[u]/nAx;
            t.tw = -f.normal[w]/nAx;
            t.normal = f.normal;
            t.nAx = nAx;
            tris_.push_back(t);
        }
        std::sort
        (
            tris_.begin(), tris_.end(),
            [](const projected& x, const projected& y){ return x.t0 < y.t0; }
        );
        worldFacets_ = &world;
    }

    //- The pieces of the column at (a, b) inside the body, within
    //  [-s/2, s/2]; the crossings (t, triangle) in crossT, crossTri.
    //  Returns the number of pieces.
    int column
    (
        double a, double b, double halfS, double* lo, double* hi, int maxPieces,
        std::vector<double>& crossT, std::vector<int>& crossTri
    ) const
    {
        crossT.clear();
        crossTri.clear();
        const double chord2 = chord2_ - a*a - b*b;
        for (size_t i = 0; i < tris_.size(); ++i)
        {
            const projected& t = tris_[i];
            if (!covers(t, a, b)) continue;
            const double tc = t.t0 + t.tu*a + t.tw*b;
            // Only crossings inside the ball: there the list is complete
            if (tc*tc > chord2) continue;
            crossT.push_back(tc);
            crossTri.push_back(int(i));
        }
        // In order along the column (few: insertion sort)
        for (size_t i = 1; i < crossT.size(); ++i)
        {
            for (size_t j = i; j > 0 && crossT[j] < crossT[j - 1]; --j)
            {
                std::swap(crossT[j], crossT[j - 1]);
                std::swap(crossTri[j], crossTri[j - 1]);
            }
        }
        bool in;
        if (crossT.empty())
        {
            in = sideAt(a, b);
        }
        else
        {
            // Before the first crossing: inside if it is an exit
            in = tris_[crossTri[0]].nAx > 0;
        }
        int n = 0;
        double start = -halfS;
        for (size_t i = 0; i <= crossT.size(); ++i)
        {
            const double tEnd = i < crossT.size() ? crossT[i] : halfS;
            if (in)
            {
                const double l = std::max(start, -halfS), h = std::min(tEnd, halfS);
                if (h > l && n < maxPieces)
                {
                    lo[n] = l;
                    hi[n] = h;
                    ++n;
                }
            }
            if (i < crossT.size())
            {
                // After a crossing: outside if it is an exit
                in = !(tris_[crossTri[i]].nAx > 0);
                start = crossT[i];
            }
        }
        return n;
    }

    const projected& triangle(int i) const { return tris_[i]; }

private:

    const std::vector<surfaceFacet>* worldFacets_ = nullptr;

    //- The side of the body at the column's point at t = 0, which no
    //  triangle crosses within the leaf: the last crossing of the segment
    //  from the leaf centre to it decides, else the centre's side
    bool sideAt(double a, double b) const
    {
        vec3 v = vec3::Zero();
        v[u_] = a;
        v[w_] = b;
        double best = -1;
        bool in = centreInside_;
        for (const surfaceFacet& f : *worldFacets_)
        {
            const double nv = f.normal.dot(v);
            if (nv == 0) continue;
            const double tau = f.normal.dot(f.a - c_)/nv;
            if (!(tau > 0 && tau <= 1) || tau < best) continue;
            // Inside the triangle (barycentric, closed)
            const vec3 x = c_ + tau*v;
            const vec3 e0 = f.b - f.a, e1 = f.c - f.a, d = x - f.a;
            const vec3 nn = e0.cross(e1);
            const double n2 = nn.squaredNorm();
            const double l1 = d.cross(e1).dot(nn)/n2;
            const double l2 = e0.cross(d).dot(nn)/n2;
            if (l1 < 0 || l2 < 0 || l1 + l2 > 1) continue;
            best = tau;
            in = nv < 0;
        }
        return in;
    }
};


//- A planar convex polygon: a triangle or a plane's square clipped by a
//  leaf's six faces and one more plane (at most 3 + 7 corners)
struct leafPolygon
{
    static constexpr int maxCorners = 16;
    int n = 0;
    vec3 x[maxCorners];

    //- Keep the part where normal.x <= offset; corners within tol of the
    //  plane count as on it
    void keepBelow(const vec3& normal, double offset, double tol)
    {
        if (n == 0) return;
        double d[maxCorners];
        for (int k = 0; k < n; ++k)
        {
            d[k] = normal.dot(x[k]) - offset;
            if (std::abs(d[k]) <= tol) d[k] = 0;
        }
        vec3 out[maxCorners];
        int m = 0;
        for (int k = 0; k < n; ++k)
        {
            const int l = (k + 1) % n;
            if (d[k] <= 0 && m < maxCorners) out[m++] = x[k];
            if ((d[k] < 0 && d[l] > 0) || (d[k] > 0 && d[l] < 0))
            {
                if (m < maxCorners) out[m++] = x[k] + (d[k]/(d[k] - d[l]))*(x[l] - x[k]);
            }
        }
        n = m < 3 ? 0 : m;
        for (int k = 0; k < n; ++k) x[k] = out[k];
    }

    //- Keep the part within the leaf (c, s). A polygon of outward normal
    //  nu lying on a face of the leaf belongs to the leaf on its body's
    //  side (nu leaving the leaf), so that a face of a body on a lattice
    //  plane counts once, in the leaf the body fills
    void keepInLeaf(const vec3& c, double s, const vec3& nu)
    {
        const double tol = 1e-9*s;
        for (int ax = 0; ax < 3 && n > 0; ++ax)
        {
            const double lo = c[ax] - 0.5*s, hi = c[ax] + 0.5*s;
            bool onLow = true, onHigh = true;
            for (int k = 0; k < n; ++k)
            {
                onLow = onLow && std::abs(x[k][ax] - lo) <= tol;
                onHigh = onHigh && std::abs(x[k][ax] - hi) <= tol;
            }
            if ((onLow && nu[ax] >= 0) || (onHigh && nu[ax] <= 0))
            {
                n = 0;
                return;
            }
            keepBelow(vec3::Unit(ax), hi, tol);
            keepBelow(-vec3::Unit(ax), -lo, tol);
        }
    }

    //- Its area (along unit normal nu) and first moment of area
    void integrals(const vec3& nu, double& area, vec3& first) const
    {
        area = 0;
        first = vec3::Zero();
        for (int k = 1; k + 1 < n; ++k)
        {
            const double a = 0.5*(x[k] - x[0]).cross(x[k + 1] - x[0]).dot(nu);
            area += a;
            first += (a/3)*(x[0] + x[k] + x[k + 1]);
        }
    }
};

class octreeWalk
{
    const shape& A_;
    const bodyPose& pA_;
    const shape& B_;
    const bodyPose& pB_;
    const double h_;
    const int maxLevel_;
    const long maxCells_;
    const bool facets_;

    cellIndex baseIndex(const vec3& lo) const
    {
        return {std::lround(lo.x()/h_), std::lround(lo.y()/h_), std::lround(lo.z()/h_)};
    }

public:

    long queries = 0;
    long leaves = 0;
    long planarLeaves = 0;    //!< cells ended early: planar surfaces

    //- Sums per base cell (size h), by lattice index
    std::map<cellIndex, baseCellSum> sums;

    //- Thrown when the walk would take more than maxCells cells
    struct tooManyCells {};

    //- Cells taken so far: visited, and base cells filled from a coarser
    //  cell inside both bodies
    long cells = 0;

    octreeWalk
    (
        const shape& A, const bodyPose& pA, const shape& B, const bodyPose& pB,
        double h, int L, long maxCells, bool facets
    )
    :
        A_(A), pA_(pA), B_(B), pB_(pB), h_(h), maxLevel_(L), maxCells_(maxCells),
        facets_(facets)
    {}

    //- The cell (centre c, half-diagonal r) against the surface of S:
    //  false when it lies wholly outside; else in tells whether wholly
    //  inside, and sp is the closest point where the surface crosses it.
    //  A ball no surface enters is wholly on one side of it, and the
    //  parent's centre is r from c (r the child's): the segment between
    //  the centres then crosses no surface, and the cell is on the
    //  parent's side. So where that side is known, a mesh is searched
    //  only within r (closestNear), not to its farther closest point; the
    //  cells classified, the points found, and so the overlap, are those
    //  of the full search. (Searched a hair beyond r, in proportion to
    //  the centres' distance from the origin: the lattice's coordinates
    //  are world coordinates, and their round-off moves the two centres
    //  apart by more than r where the cells are small and far from it)
    bool classify
    (
        const shape& S, const bodyPose& pS, const vec3& c, double r,
        int side, double bound, surfacePoint& sp, bool& in
    )
    {
        ++queries;
        const double reach = r + 1e-14*c.cwiseAbs().sum();
        if (side != 0 && !S.closestNear(pS, c, reach, bound, sp))
        {
            in = side < 0;
            return in;
        }
        if (side == 0)
        {
            sp = S.closest(pS, c, bound);
        }
        if (sp.distance > r)
        {
            return false;
        }
        in = sp.distance < -r;
        return true;
    }

    // level < 0: coarser than h, above the base cells; sum is then null.
    // boundA, boundB: upper bounds of the distances to the surfaces from
    // the parent's queries (the distance is 1-Lipschitz), to prune the
    // meshes' searches. sideA, sideB: the side of each surface the
    // parent's centre is on (1 outside, -1 inside, 0 not known: a root
    // cell, or a centre on the surface)
    void visit
    (
        const vec3& lo, double s, int level, bool inA, bool inB,
        double boundA, double boundB, baseCellSum* sum,
        int sideA = 0, int sideB = 0
    )
    {
        if (++cells > maxCells_)
        {
            throw tooManyCells();
        }
        if (level == 0)
        {
            sum = &sums[baseIndex(lo)];
        }
        ++leaves;
        const vec3 c = lo + vec3::Constant(0.5*s);
        const double r = 0.5*std::sqrt(3.0)*s;

        surfacePoint a, b;
        if (!inA && !classify(A_, pA_, c, r, sideA, boundA, a, inA)) return;
        if (!inB && !classify(B_, pB_, c, r, sideB, boundB, b, inB)) return;
        if (inA && inB)
        {
            if (level >= 0)
            {
                const double v = s*s*s;
                sum->volume += v;
                sum->first += v*c;
                sum->box.add(lo);
                sum->box.add(lo + vec3::Constant(s));
                return;
            }
            // A coarse cell inside both: its base cells, for the regions
            const long n = 1L << (-level);
            cells += n*n*n;
            if (cells > maxCells_)
            {
                throw tooManyCells();
            }
            for (long i = 0; i < n; ++i)
            {
                for (long j = 0; j < n; ++j)
                {
                    for (long k = 0; k < n; ++k)
                    {
                        const vec3 blo = lo + h_*vec3(i, j, k);
                        baseCellSum& b = sums[baseIndex(blo)];
                        const double v = h_*h_*h_;
                        b.volume += v;
                        b.first += v*(blo + vec3::Constant(0.5*h_));
                        b.box.add(blo);
                        b.box.add(blo + vec3::Constant(h_));
                    }
                }
            }
            return;
        }
        // Where one body is known to contain the cell only the other's
        // surface crosses it, and the leaf's tangent plane integrates that
        // to second order: one level less suffices. Where both surfaces
        // cross (the rim of the overlap, which sets the normal) refine fully.
        const int stopLevel = (inA || inB) ? std::max(0, maxLevel_ - 1) : maxLevel_;
        // Where the surfaces crossing the cell are planes that cross every
        // column of the leaf and do not meet inside it (the inside of a
        // face-on-face contact, a face on a flat wall), the leaf's columns
        // are exact at any size: no refinement. The cost of a flat contact
        // then grows with its rim, not its area.
        if (facets_ && level >= 0 && level < stopLevel && planarCell(c, s, inA, a, inB, b))
        {
            ++planarLeaves;
            leaf(c, s, inA, a, inB, b, *sum);
            return;
        }
        if (level < stopLevel)
        {
            const double h = 0.5*s;
            // A child's centre is r/2 from this centre
            const double bA = inA ? 0 : std::abs(a.distance) + 0.5*r;
            const double bB = inB ? 0 : std::abs(b.distance) + 0.5*r;
            const int sA = inA ? 0 : (a.distance > 0) - (a.distance < 0);
            const int sB = inB ? 0 : (b.distance > 0) - (b.distance < 0);
            for (int k = 0; k < 8; ++k)
            {
                const vec3 off((k & 1)*h, ((k >> 1) & 1)*h, ((k >> 2) & 1)*h);
                visit(lo + off, h, level + 1, inA, inB, bA, bB, sum, sA, sB);
            }
            return;
        }
        leaf(c, s, inA, a, inB, b, *sum);
    }

    //- Whether S's surface within the ball (c, r) is one plane, the one
    //  through sp's closest point with normal sp.normal and no curvature
    //  (a bend below 1e-9 of the cell size s over the cell: the fit of a
    //  flat face's curvature leaves round-off)
    bool planarNear
    (
        const shape& S, const bodyPose& pS, const vec3& c, double r, double s,
        const surfacePoint& sp
    )
    {
        if (S.shapeKind() == shape::kind::halfSpace)
        {
            return true;
        }
        if
        (
            (S.shapeKind() != shape::kind::triangleMesh && S.shapeKind() != shape::kind::wallMesh)
         || sp.curvature.cwiseAbs().maxCoeff()*s > 1e-9
        )
        {
            return false;
        }
        local_.clear();
        if (!S.facetsNear(pS.toBody(c), r, local_, 64) || local_.empty())
        {
            return false;
        }
        const vec3 n0 = local_[0].normal;
        const vec3& p0 = local_[0].a;
        const double tol = 1e-9*s;
        for (const surfaceFacet& f : local_)
        {
            if
            (
                f.normal.dot(n0) < 1 - 1e-12
             || std::abs(n0.dot(f.a - p0)) > tol
             || std::abs(n0.dot(f.b - p0)) > tol
             || std::abs(n0.dot(f.c - p0)) > tol
            )
            {
                return false;
            }
        }
        // The closest point's model is that plane
        return pS.vectorToWorld(n0).dot(sp.normal) > 1 - 1e-12;
    }

    //- Whether the leaf's column integration is exact in the cell (c, s):
    //  each surface near it is a plane that, over the cell's columns (along
    //  the axis the leaf would choose), stays within the cell or wholly
    //  above or below it, and two such planes do not cross each other there
    //  (their heights, clipped to the cell, differ in sign nowhere): the
    //  inside of each column is then one interval whose ends are linear
    //  over the cell, which the columns' midpoints measure exactly
    bool planarCell
    (
        const vec3& c, double s,
        bool inA, const surfacePoint& a, bool inB, const surfacePoint& b
    )
    {
        const double r = 0.5*std::sqrt(3.0)*s*(1 + 1e-9);
        if (!inA && !planarNear(A_, pA_, c, r, s, a)) return false;
        if (!inB && !planarNear(B_, pB_, c, r, s, b)) return false;
        // The leaf's column axis (as leaf() chooses it for smooth surfaces)
        vec3 facing = vec3::Zero();
        if (!inA) facing = facing.cwiseMax(a.normal.cwiseAbs());
        if (!inB) facing = facing.cwiseMax(b.normal.cwiseAbs());
        int ax = 0;
        facing.maxCoeff(&ax);
        const int u = (ax + 1) % 3, w = (ax + 2) % 3;
        // Height along the column axis of the plane of sp over the column
        // at (du, dw) from the centre
        auto height = [&](const surfacePoint& sp, double du, double dw)
        {
            return -(sp.normal.dot(c - sp.point) + du*sp.normal[u] + dw*sp.normal[w])/sp.normal[ax];
        };
        if ((!inA && std::abs(a.normal[ax]) < 1e-6) || (!inB && std::abs(b.normal[ax]) < 1e-6))
        {
            return false;
        }
        // Each plane: within [-s/2, s/2] over the whole cell, or wholly
        // above or below it (then its columns are all in or all out)
        auto classOf = [&](double t)
        {
            return t > 0.5*s ? 1 : (t < -0.5*s ? -1 : 0);
        };
        int classA = 2, classB = 2;
        int positive = 0, negative = 0;
        for (int k = 0; k < 4; ++k)
        {
            const double du = (k & 1 ? 0.5 : -0.5)*s, dw = (k & 2 ? 0.5 : -0.5)*s;
            double tA = 0, tB = 0;
            if (!inA)
            {
                tA = height(a, du, dw);
                const int cl = classOf(tA);
                if (classA != 2 && cl != classA) return false;
                classA = cl;
                tA = std::max(-0.5*s, std::min(0.5*s, tA));
            }
            if (!inB)
            {
                tB = height(b, du, dw);
                const int cl = classOf(tB);
                if (classB != 2 && cl != classB) return false;
                classB = cl;
                tB = std::max(-0.5*s, std::min(0.5*s, tB));
            }
            if (!inA && !inB)
            {
                // Round-off of coincident planes (touching faces) is no crossing
                if (tA > tB + 1e-12*s) ++positive;
                if (tA < tB - 1e-12*s) ++negative;
            }
        }
        return positive == 0 || negative == 0;
    }

    //- The triangles of sp's body near a leaf (world frame) when the
    //  surface there is not one smooth sheet: an edge or corner sharper
    //  than the crease angle, or a second sheet (a thin part), within the
    //  leaf's ball. Empty: the closest point's model holds in the leaf.
    bool facetedNear
    (
        const shape& S, const bodyPose& pS, const vec3& c, double r,
        std::vector<surfaceFacet>& world
    )
    {
        world.clear();
        local_.clear();
        if (!S.facetsNear(pS.toBody(c), r, local_, 256) || local_.size() < 2)
        {
            return false;
        }
        const double cosCrease = std::cos(surfaceDistance::creaseAngleDegrees*M_PI/180);
        bool smooth = true;
        for (size_t i = 0; i < local_.size() && smooth; ++i)
        {
            for (size_t j = i + 1; j < local_.size(); ++j)
            {
                if (local_[i].normal.dot(local_[j].normal) < cosCrease)
                {
                    smooth = false;
                    break;
                }
            }
        }
        if (smooth)
        {
            return false;
        }
        world.reserve(local_.size());
        for (const surfaceFacet& f : local_)
        {
            world.push_back
            (
                {pS.toWorld(f.a), pS.toWorld(f.b), pS.toWorld(f.c), pS.vectorToWorld(f.normal)}
            );
        }
        return true;
    }

    void leaf
    (
        const vec3& c, double s,
        bool inA, const surfacePoint& a, bool inB, const surfacePoint& b,
        baseCellSum& sum
    )
    {
        // Second-order models of the two surfaces in the leaf (the tangent
        // plane at the closest point bent by the surface's curvature there),
        // integrated exactly along columns parallel to the axis the normals
        // face most, at n x n column centres: exact for a plane facing that
        // axis (no quantisation where an overlap is a few leaves thick), and
        // free of the tangent plane's O(kappa s^2) excess where both
        // surfaces are convex. Where a mesh's surface in the leaf is not
        // one smooth sheet (an edge, a corner, a thin part), its triangles
        // there instead, exactly.
        const double r = 0.5*std::sqrt(3.0)*s*(1 + 1e-9);
        const bool facetedA = facets_ && !inA && facetedNear(A_, pA_, c, r, worldA_);
        const bool facetedB = facets_ && !inB && facetedNear(B_, pB_, c, r, worldB_);

        // The column axis: the one the two surfaces face most where they
        // are most nearly parallel (across a thin sliver, which columns
        // along it integrate exactly at any thickness); a faceted surface
        // offers each of its triangles' normals
        int ax = 0;
        {
            normalsA_.clear();
            normalsB_.clear();
            if (facetedA) for (const surfaceFacet& f : worldA_) normalsA_.push_back(f.normal);
            else if (!inA) normalsA_.push_back(a.normal);
            if (facetedB) for (const surfaceFacet& f : worldB_) normalsB_.push_back(f.normal);
            else if (!inB) normalsB_.push_back(b.normal);
            const std::vector<vec3>& one = normalsA_.empty() ? normalsB_ : normalsA_;
            const std::vector<vec3>& other = normalsA_.empty() ? normalsA_ : normalsB_;
            vec3 facing = vec3::Zero();
            double best = -1;
            for (const vec3& na : one)
            {
                if (other.empty())
                {
                    facing = facing.cwiseMax(na.cwiseAbs());
                    continue;
                }
                for (const vec3& nb : other)
                {
                    const double g = std::abs(na.dot(nb));
                    if (g > best + 1e-12)
                    {
                        best = g;
                        facing = na.cwiseAbs().cwiseMax(nb.cwiseAbs());
                    }
                }
            }
            facing.maxCoeff(&ax);
        }
        const int u = (ax + 1) % 3, w = (ax + 2) % 3;
        std::unique_ptr<leafFacets> fA, fB;
        if (facetedA) fA.reset(new leafFacets(worldA_, c, ax, u, w, r, a.distance < 0));
        if (facetedB) fB.reset(new leafFacets(worldB_, c, ax, u, w, r, b.distance < 0));

        const int n = virtualMeshOverlap::nSub;
        const double ds = s/n;
        double volume = 0;
        vec3 first = vec3::Zero();
        vec3 areaA = vec3::Zero();
        vec3 momentA = vec3::Zero();
        bool areaFromFacets = false;
        const leafSurface surfA(a, c, ax, u, w), surfB(b, c, ax, u, w);
        double lo[columnSet::maxPieces], hi[columnSet::maxPieces];
        for (int i = 0; i < n; ++i)
        {
            const double oi = (i + 0.5 - 0.5*n)*ds;
            for (int j = 0; j < n; ++j)
            {
                const double oj = (j + 0.5 - 0.5*n)*ds;
                vec3 x = c;
                x[u] += oi;
                x[w] += oj;
                columnSet inside(-0.5*s, 0.5*s);
                if (fB)
                {
                    const int m = fB->column(oi, oj, 0.5*s, lo, hi, columnSet::maxPieces, crossT_, crossTri_);
                    inside.keepPieces(lo, hi, m);
                }
                else if (!inB)
                {
                    inside.clip(surfB.column(oi, oj));
                }
                if (fA)
                {
                    // A's surface inside B (before A clips): the area vector
                    const columnSet insideB(inside);
                    const int m = fA->column(oi, oj, 0.5*s, lo, hi, columnSet::maxPieces, crossT_, crossTri_);
                    for (size_t k = 0; k < crossT_.size(); ++k)
                    {
                        const double t = crossT_[k];
                        // (-s/2, s/2] with the tangent planes' round-off
                        // margin: a face on a leaf's face counts once
                        const double tol = 1e-9*s;
                        if (t > -0.5*s + tol && t <= 0.5*s + tol && insideB.contains(t))
                        {
                            const auto& tri = fA->triangle(crossTri_[k]);
                            const vec3 dS = (ds*ds/std::abs(tri.nAx))*tri.normal;
                            vec3 xc = x;
                            xc[ax] += t;
                            areaA += dS;
                            momentA += xc.cross(dS);
                        }
                    }
                    areaFromFacets = true;
                    inside.keepPieces(lo, hi, m);
                }
                else if (!inA)
                {
                    inside.clip(surfA.column(oi, oj));
                }
                for (int k = 0; k < inside.size; ++k)
                {
                    const double l = inside.lo[k], h = inside.hi[k];
                    const double v = (h - l)*ds*ds;
                    volume += v;
                    vec3 xm = x;
                    xm[ax] += 0.5*(l + h);
                    first += v*xm;
                }
            }
        }
        // Where B is one plane in the leaf (or holds it), A's surface inside
        // it exactly: each of A's triangles (or its tangent plane) clipped
        // by the leaf and by B's plane. Sampled at the columns instead, the
        // area jumps by a column wherever the rim crosses one, and a
        // symmetric contact's normal leaves its mirror plane (issue 19).
        // Measured apart from the columns: a face parallel to them may
        // bound a sliver of the leaf that no column centre samples
        const bool clipped = !inA && !fB;
        if (clipped)
        {
            clippedAreaOfA(c, s, inB, a, b, fA != nullptr, areaA, momentA);
        }
        if (volume <= 0 && areaA.squaredNorm() == 0)
        {
            return;
        }

        // A's tangent plane inside B: its outward area vector, from where
        // the plane crosses n x n columns along the axis it faces most
        if (!inA && !areaFromFacets && !clipped)
        {
            int axA = 0;
            a.normal.cwiseAbs().maxCoeff(&axA);
            const int ua = (axA + 1) % 3, wa = (axA + 2) % 3;
            const double na = a.normal[axA];
            int crossings = 0;
            vec3 crossSum = vec3::Zero();
            for (int i = 0; i < n; ++i)
            {
                for (int j = 0; j < n; ++j)
                {
                    vec3 x = c;
                    x[ua] += (i + 0.5 - 0.5*n)*ds;
                    x[wa] += (j + 0.5 - 0.5*n)*ds;
                    const double t = -(a.distance + a.normal.dot(x - c))/na;
                    // (-s/2, s/2], shifted by a round-off margin, so that
                    // a plane on the face two cells share is seen by one
                    const double tol = 1e-9*s;
                    if (t <= -0.5*s + tol || t > 0.5*s + tol) continue;
                    x[axA] += t;
                    if (inB || b.distance + b.normal.dot(x - c) <= 0)
                    {
                        ++crossings;
                        crossSum += x;
                    }
                }
            }
            areaA = (crossings*ds*ds/std::abs(na))*a.normal;
            momentA = (ds*ds/std::abs(na))*crossSum.cross(a.normal);
        }
        sum.volume += volume;
        sum.first += first;
        sum.areaVector += areaA;
        sum.areaMoment += momentA;
        sum.box.add(c - vec3::Constant(0.5*s));
        sum.box.add(c + vec3::Constant(0.5*s));

        if (inA || inB)
        {
            return;
        }

        // Edge point: where the two tangent planes meet, nearest the centre
        const double g = a.normal.dot(b.normal);
        if (1 - g*g > 1e-8)
        {
            const double alpha = (-a.distance + g*b.distance)/(1 - g*g);
            const double beta = (-b.distance + g*a.distance)/(1 - g*g);
            const vec3 x = c + alpha*a.normal + beta*b.normal;
            if ((x - c).cwiseAbs().maxCoeff() <= 0.5*s)
            {
                sum.edgePoints.push_back(x);
            }
        }
    }

private:

    //- A's surface in the leaf (c, s) inside B (all of it when inB, else
    //  below B's tangent plane): area vector and its moment about the
    //  origin. A's triangles near the leaf (worldA_ when faceted, else
    //  gathered here), or A's tangent plane for a surface without them
    //  (a sphere). The triangles, not the closest point's plane, also where
    //  a mesh is smooth: that plane's normal is blended near edges, and a
    //  flat face's area would lean towards its edges.
    void clippedAreaOfA
    (
        const vec3& c, double s, bool inB,
        const surfacePoint& a, const surfacePoint& b, bool faceted,
        vec3& areaA, vec3& momentA
    )
    {
        if (!faceted)
        {
            const double r = 0.5*std::sqrt(3.0)*s*(1 + 1e-9);
            local_.clear();
            if (A_.facetsNear(pA_.toBody(c), r, local_, 256) && !local_.empty())
            {
                worldA_.clear();
                for (const surfaceFacet& f : local_)
                {
                    worldA_.push_back
                    (
                        {pA_.toWorld(f.a), pA_.toWorld(f.b), pA_.toWorld(f.c), pA_.vectorToWorld(f.normal)}
                    );
                }
                faceted = true;
            }
        }
        areaA = vec3::Zero();
        momentA = vec3::Zero();
        const double tol = 1e-9*s;
        auto add = [&](leafPolygon& P, const vec3& nu)
        {
            P.keepInLeaf(c, s, nu);
            if (!inB) P.keepBelow(b.normal, b.normal.dot(c) - b.distance, tol);
            double area;
            vec3 first;
            P.integrals(nu, area, first);
            if (area <= 0) return;
            areaA += area*nu;
            momentA += first.cross(nu);
        };
        if (faceted)
        {
            for (const surfaceFacet& f : worldA_)
            {
                leafPolygon P;
                P.n = 3;
                P.x[0] = f.a;
                P.x[1] = f.b;
                P.x[2] = f.c;
                // Counter-clockwise about the normal
                if ((f.b - f.a).cross(f.c - f.a).dot(f.normal) < 0) std::swap(P.x[1], P.x[2]);
                add(P, f.normal);
            }
            return;
        }
        // A square in A's tangent plane around the point nearest the
        // centre, wider than the leaf's ball
        const vec3& nu = a.normal;
        const vec3 p0 = c - a.distance*nu;
        int least = 0;
        nu.cwiseAbs().minCoeff(&least);
        const vec3 e1 = nu.cross(vec3::Unit(least)).normalized();
        const vec3 e2 = nu.cross(e1);
        leafPolygon P;
        P.n = 4;
        P.x[0] = p0 - s*e1 - s*e2;
        P.x[1] = p0 + s*e1 - s*e2;
        P.x[2] = p0 + s*e1 + s*e2;
        P.x[3] = p0 - s*e1 + s*e2;
        add(P, nu);
    }

    // Work space of the leaves
    std::vector<surfaceFacet> local_, worldA_, worldB_;
    std::vector<vec3> normalsA_, normalsB_;
    std::vector<double> crossT_;
    std::vector<int> crossTri_;
};


vec3 regionNormal
(
    const std::vector<vec3>& edgePoints,
    const vec3& areaVector,
    const vec3& centreLine
)
{
    // The orientation reference: continuous in the pose
    const vec3 ref = overlapTools::firstDirection({areaVector, centreLine});

    // Determined: not collinear, and the smallest spread clearly below
    // the other two
    overlapTools::planeFitCriteria plane;
    plane.minSpread = 1e-6;
    plane.maxFlatness = 0.25;
    plane.requireFinite = false;
    vec3 n = ref;
    overlapTools::fitPlaneNormal(edgePoints, ref, plane, n);
    return n;
}

} // End anonymous namespace


// Whether some point of a convex body (corners: its vertices in the
// wall's frame) lies behind both planes by more than eps: the part of the
// body behind p (a convex polytope) reaches behind q iff one of its
// corners does, and those are the body's corners behind p and the points
// where its edges cross p
static bool convexBehindBoth
(
    const convexPolyhedron& body,
    const std::vector<vec3>& corners,
    const wallMeshShape::plane& p,
    const wallMeshShape::plane& q,
    double eps
)
{
    auto height = [](const wallMeshShape::plane& r, const vec3& x)
    {
        return r.normal.dot(x) - r.offset;
    };
    for (const vec3& v : corners)
    {
        if (height(p, v) < 0 && height(q, v) < -eps) return true;
    }
    for (const convexPolyhedron::face& f : body.faces())
    {
        const size_t n = f.corners.size();
        for (size_t k = 0; k < n; ++k)
        {
            const vec3& a = corners[f.corners[k]];
            const vec3& b = corners[f.corners[(k + 1)%n]];
            const double ha = height(p, a), hb = height(p, b);
            if ((ha < 0) != (hb < 0))
            {
                const vec3 x = a + (ha/(ha - hb))*(b - a);
                if (height(q, x) < -eps) return true;
            }
        }
    }
    return false;
}


contactGeometry virtualMeshOverlap::evaluate
(
    const shape& A, const bodyPose& pA,
    const shape& B, const bodyPose& pB,
    const overlapSettings& settings
) const
{
    const double h = settings.h;
    const int L = settings.level;
    overlapTools::checkCellSize(type(), h);
    overlapTools::checkLevel(type(), L, overlapSettings::maxLevel);

    contactGeometry g;
    const axisAlignedBox box = overlapTools::commonBox(A, pA, B, pB);
    if (box.empty())
    {
        return g;
    }

    // A body whose bounding ball reaches no face of a wall mesh, on the
    // wall's fluid side: apart (the common box is the body's whole box
    // anywhere inside a tank or a tube, and its octree would find nothing)
    {
        const auto* wa = shapeAs<wallMeshShape>(A);
        const auto* wb = shapeAs<wallMeshShape>(B);
        if
        (
            (wa && !wb && wa->clearOf(pA.toBody(pB.position()), B.boundingRadius()))
         || (wb && !wa && wb->clearOf(pB.toBody(pA.position()), A.boundingRadius()))
        )
        {
            return g;
        }
    }

    // Convex pairs: the exact intersection, cheaper than any octree
    if (settings.convexExact)
    {
        if (convexOverlap::handles(A, B))
        {
            return convexOverlap().evaluate(A, pA, B, pB, settings);
        }
        // A convex mesh against a wall mesh that is flat wherever the
        // body reaches (a body on the floor of a tank): the wall's plane
        const auto* ma = shapeAs<triangleMeshShape>(A);
        const auto* mb = shapeAs<triangleMeshShape>(B);
        const auto* wa = shapeAs<wallMeshShape>(A);
        const auto* wb = shapeAs<wallMeshShape>(B);
        vec3 x, n;
        if
        (
            wa && mb && mb->convex()
         && wa->flatNear(pA.toBody(pB.position()), mb->boundingRadius(), x, n)
        )
        {
            const halfSpaceShape plane;
            const bodyPose pP = halfSpaceShape::poseOf(pA.toWorld(x), pA.vectorToWorld(n));
            return convexOverlap().evaluate(plane, pP, B, pB, settings);
        }
        if
        (
            ma && wb && ma->convex()
         && wb->flatNear(pB.toBody(pA.position()), ma->boundingRadius(), x, n)
        )
        {
            const halfSpaceShape plane;
            const bodyPose pP = halfSpaceShape::poseOf(pB.toWorld(x), pB.vectorToWorld(n));
            return convexOverlap().evaluate(A, pA, plane, pP, settings);
        }
        // A convex mesh in a locally convex fluid region of a wall mesh
        // (a box tank's corner, a faceted tube): exact when the body is
        // behind one of its planes only (the plane's half-space), nothing
        // when behind none; behind two or more, the octree
        const triangleMeshShape* m = wa ? mb : wb ? ma : nullptr;
        if (m && m->convex())
        {
            const bool wallFirst = wa != nullptr;
            const wallMeshShape& w = wallFirst ? *wa : *wb;
            const bodyPose& pW = wallFirst ? pA : pB;
            const bodyPose& pM = wallFirst ? pB : pA;
            std::vector<wallMeshShape::plane> planes;
            if (w.convexFluidNear(pW.toBody(pM.position()), m->boundingRadius(), planes))
            {
                const double eps = 1e-12*m->boundingRadius();
                // The body's corners in the wall's frame
                std::vector<vec3> corners;
                for (const vec3& v : m->convex()->vertices())
                {
                    corners.push_back(pW.toBody(pM.toWorld(v)));
                }
                std::vector<const wallMeshShape::plane*> crossed;
                for (const wallMeshShape::plane& q : planes)
                {
                    for (const vec3& v : corners)
                    {
                        if (q.normal.dot(v) < q.offset - eps)
                        {
                            crossed.push_back(&q);
                            break;
                        }
                    }
                }
                // Behind several planes (a pellet in a tube's corner): one
                // region per plane when the body's parts behind them are
                // apart (their sum is then the overlap with the wall's
                // solid, the union of the half-spaces); else the octree
                bool apart = true;
                for (size_t i = 0; apart && i < crossed.size(); ++i)
                {
                    for (size_t j = 0; apart && j < crossed.size(); ++j)
                    {
                        apart = i == j
                            || !convexBehindBoth(*m->convex(), corners, *crossed[i], *crossed[j], eps);
                    }
                }
                if (apart)
                {
                    for (const wallMeshShape::plane* q : crossed)
                    {
                        const halfSpaceShape plane;
                        const bodyPose pP = halfSpaceShape::poseOf
                        (
                            pW.toWorld(q->offset*q->normal), pW.vectorToWorld(q->normal)
                        );
                        const contactGeometry one = wallFirst
                            ? convexOverlap().evaluate(plane, pP, B, pB, settings)
                            : convexOverlap().evaluate(A, pA, plane, pP, settings);
                        g.regions.insert(g.regions.end(), one.regions.begin(), one.regions.end());
                    }
                    return g;
                }
                // Parts shared (a pellet pressed into a round tube's
                // facets, or into a corner): the body less its part in
                // front of every plane, one region
                std::vector<std::pair<vec3, double>> world;
                for (const wallMeshShape::plane& q : planes)
                {
                    const vec3 n = pW.vectorToWorld(q.normal);
                    world.emplace_back(n, n.dot(pW.toWorld(q.offset*q.normal)));
                }
                if (convexOverlap::againstWall(*m, pM, world, !wallFirst, g))
                {
                    return g;
                }
            }
        }
    }

    // A sphere against a wall that is flat wherever the sphere reaches:
    // the exact spherical cap (what the octree would approximate; a
    // sphere resting on a mesh patch would otherwise cost a full
    // refinement of its cap every DEM step)
    {
        const auto* sa = dynamic_cast<const sphereShape*>(&A);
        const auto* sb = dynamic_cast<const sphereShape*>(&B);
        const auto* wa = dynamic_cast<const wallMeshShape*>(&A);
        const auto* wb = dynamic_cast<const wallMeshShape*>(&B);
        vec3 x, n;
        if (wa && sb && wa->flatNear(pA.toBody(pB.position()), sb->radius(), x, n))
        {
            return sphereOverlap::cap
            (
                pA.toWorld(x), pA.vectorToWorld(n), pB.position(), sb->radius()
            );
        }
        if (sa && wb && wb->flatNear(pB.toBody(pA.position()), sa->radius(), x, n))
        {
            g = sphereOverlap::cap
            (
                pB.toWorld(x), pB.vectorToWorld(n), pA.position(), sa->radius()
            );
            for (contactRegion& r : g.regions) r.normal = -r.normal;
            return g;
        }
    }

    // Roots: cells of size H = 2^m h on the same lattice, m chosen so a few
    // roots cover the box; empty space is then dropped in large pieces
    const double extent = box.span().maxCoeff();
    int m = 0;
    while (m < 20 && h*double(1L << (m + 1)) < extent)
    {
        ++m;
    }
    const double H = h*double(1L << m);

    octreeWalk walk(A, pA, B, pB, h, L, settings.maxCells, settings.facetedEdges);
    const double noBound = std::numeric_limits<double>::max();
    const overlapTools::cellRange roots = overlapTools::latticeRange(box, H);
    long nRoots = 1;
    for (int d = 0; d < 3; ++d) nRoots *= roots.hi[d] - roots.lo[d] + 1;
    long rootsDone = 0;
    try
    {
        overlapTools::forEachLatticeCell
        (
            roots, H,
            [&](const cellIndex&, const vec3& corner)
            {
                walk.visit(corner, H, -m, false, false, noBound, noBound, nullptr);
                ++rootsDone;
            }
        );
    }
    catch (const octreeWalk::tooManyCells&)
    {
        // The cells the whole walk would take, from the share of the roots
        // walked (the one stopped counting as half)
        const double needed =
            double(walk.cells)*double(nRoots)/(double(rootsDone) + 0.5);
        std::ostringstream msg;
        msg.precision(3);
        msg << type() << ": the contact would need about " << needed
            << " cells of the virtual mesh, more than the limit of "
            << double(settings.maxCells) << " per contact: cellSize " << h
            << " m at level " << L << " is too fine for an overlap region of "
            << extent << " m (leaves of " << h/double(1L << L)
            << " m). Use a larger cellSize or a lower level";
        throw coreError(msg.str());
    }
    std::map<cellIndex, baseCellSum> sums;
    std::vector<const std::pair<const cellIndex, baseCellSum>*> areaOnly;
    for (auto& e : walk.sums)
    {
        if (e.second.volume > 0)
        {
            sums.emplace(e.first, std::move(e.second));
        }
        else if (e.second.areaVector.squaredNorm() > 0)
        {
            areaOnly.push_back(&e);
        }
    }
    // A base cell holding A's surface inside B but no volume (the volume
    // sits across a face of the lattice, or in a sliver no column samples)
    // gives its area to a neighbour with volume, the first of the 26 in a
    // fixed order
    for (const auto* e : areaOnly)
    {
        bool given = false;
        for (int k = 0; k < 27 && !given; ++k)
        {
            if (k == 13) continue;
            const cellIndex n{e->first[0] + k/9 - 1, e->first[1] + (k/3)%3 - 1, e->first[2] + k%3 - 1};
            const auto it = sums.find(n);
            if (it == sums.end()) continue;
            it->second.areaVector += e->second.areaVector;
            it->second.areaMoment += e->second.areaMoment;
            given = true;
        }
    }
    g.queries = walk.queries;
    g.leaves = walk.leaves;
    if (sums.empty())
    {
        return g;
    }

    // Regions: base cells joined across faces
    overlapTools::cellRegions sets(sums, overlapTools::cellJoin::faces);

    std::map<int, baseCellSum> cellSets;
    for (const auto& e : sums)
    {
        baseCellSum& r = cellSets[sets.label(e.first)];
        const baseCellSum& s = e.second;
        r.volume += s.volume;
        r.box.add(s.box);
    }

    // Sets of cells closer than a base cell (the boxes of their leaves
    // holding overlap) are one contact: a contact is not split by the
    // lattice, e.g. where it narrows to a corner two cells share
    std::vector<int> labels;
    for (const auto& e : cellSets) labels.push_back(e.first);
    overlapTools::disjointSets near(int(labels.size()));
    for (size_t i = 0; i < labels.size(); ++i)
    {
        const axisAlignedBox& bi = cellSets[labels[i]].box;
        for (size_t j = i + 1; j < labels.size(); ++j)
        {
            const axisAlignedBox& bj = cellSets[labels[j]].box;
            const vec3 gap =
                (bj.min - bi.max).cwiseMax(bi.min - bj.max).cwiseMax(vec3::Zero());
            if (gap.norm() < h) near.join(int(i), int(j));
        }
    }
    std::map<int, int> contactOf;
    for (size_t i = 0; i < labels.size(); ++i) contactOf[labels[i]] = near.find(int(i));

    std::map<int, baseCellSum> regions;
    for (const auto& e : sums)
    {
        baseCellSum& r = regions[contactOf[sets.label(e.first)]];
        const baseCellSum& s = e.second;
        r.volume += s.volume;
        r.first += s.first;
        r.areaVector += s.areaVector;
        r.areaMoment += s.areaMoment;
        r.edgePoints.insert(r.edgePoints.end(), s.edgePoints.begin(), s.edgePoints.end());
        r.box.add(s.box);
    }

    const vec3 centreLine = pB.position() - pA.position();
    for (const auto& e : regions)
    {
        const baseCellSum& r = e.second;
        contactRegion cr;
        cr.volume = r.volume;
        cr.point = r.first/r.volume;
        cr.normal = settings.areaVectorNormal && r.areaVector.norm() > 0
            ? vec3(r.areaVector.normalized())
            : regionNormal(r.edgePoints, r.areaVector, centreLine);
        cr.area = r.areaVector.norm();
        cr.areaVector = r.areaVector;
        cr.areaMoment = r.areaMoment - cr.point.cross(r.areaVector);
        g.regions.push_back(cr);
    }
    // A deterministic order: largest region first
    overlapTools::sortLargestFirst(g.regions, false);
    return g;
}

} // End namespace immersedDEM
