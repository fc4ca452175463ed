#include "virtualMeshOverlap.H"
#include "overlapTools.H"
#include "sphereOverlap.H"
#include "sphereShape.H"
#include "wallMeshShape.H"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

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
    std::vector<vec3> edgePoints;
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
    int size = 1;
    double lo[4], hi[4];

    columnSet(double l, double h) { lo[0] = l; hi[0] = h; }

    void keep(double l, double h, columnSet& out) const
    {
        for (int k = 0; k < size; ++k)
        {
            const double a = std::max(lo[k], l), b = std::min(hi[k], h);
            if (b > a && out.size < 4)
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
};

class octreeWalk
{
    const shape& A_;
    const bodyPose& pA_;
    const shape& B_;
    const bodyPose& pB_;
    const double h_;
    const int maxLevel_;

    cellIndex baseIndex(const vec3& lo) const
    {
        return {std::lround(lo.x()/h_), std::lround(lo.y()/h_), std::lround(lo.z()/h_)};
    }

public:

    long queries = 0;
    long leaves = 0;

    //- Sums per base cell (size h), by lattice index
    std::map<cellIndex, baseCellSum> sums;

    octreeWalk
    (
        const shape& A, const bodyPose& pA, const shape& B, const bodyPose& pB,
        double h, int L
    )
    :
        A_(A), pA_(pA), B_(B), pB_(pB), h_(h), maxLevel_(L)
    {}

    // level < 0: coarser than h, above the base cells; sum is then null.
    // boundA, boundB: upper bounds of the distances to the surfaces from
    // the parent's queries (the distance is 1-Lipschitz), to prune the
    // meshes' searches
    void visit
    (
        const vec3& lo, double s, int level, bool inA, bool inB,
        double boundA, double boundB, baseCellSum* sum
    )
    {
        if (level == 0)
        {
            sum = &sums[baseIndex(lo)];
        }
        ++leaves;
        const vec3 c = lo + vec3::Constant(0.5*s);
        const double r = 0.5*std::sqrt(3.0)*s;

        surfacePoint a, b;
        if (!inA)
        {
            a = A_.closest(pA_, c, boundA);
            ++queries;
            if (a.distance > r) return;
            inA = a.distance < -r;
        }
        if (!inB)
        {
            b = B_.closest(pB_, c, boundB);
            ++queries;
            if (b.distance > r) return;
            inB = b.distance < -r;
        }
        if (inA && inB)
        {
            if (level >= 0)
            {
                const double v = s*s*s;
                sum->volume += v;
                sum->first += v*c;
                return;
            }
            // A coarse cell inside both: its base cells, for the regions
            const long n = 1L << (-level);
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
        if (level < stopLevel)
        {
            const double h = 0.5*s;
            // A child's centre is r/2 from this centre
            const double bA = inA ? 0 : std::abs(a.distance) + 0.5*r;
            const double bB = inB ? 0 : std::abs(b.distance) + 0.5*r;
            for (int k = 0; k < 8; ++k)
            {
                const vec3 off((k & 1)*h, ((k >> 1) & 1)*h, ((k >> 2) & 1)*h);
                visit(lo + off, h, level + 1, inA, inB, bA, bB, sum);
            }
            return;
        }
        leaf(c, s, inA, a, inB, b, *sum);
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
        // surfaces are convex
        const vec3 nMax = (inA ? vec3::Zero() : vec3(a.normal.cwiseAbs()))
            .cwiseMax(inB ? vec3::Zero() : vec3(b.normal.cwiseAbs()));
        int ax = 0;
        nMax.maxCoeff(&ax);
        const int u = (ax + 1) % 3, w = (ax + 2) % 3;

        const int n = virtualMeshOverlap::nSub;
        const double ds = s/n;
        double volume = 0;
        vec3 first = vec3::Zero();
        vec3 areaA = vec3::Zero();
        const leafSurface surfA(a, c, ax, u, w), surfB(b, c, ax, u, w);
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
                if (!inA) inside.clip(surfA.column(oi, oj));
                if (!inB) inside.clip(surfB.column(oi, oj));
                for (int k = 0; k < inside.size; ++k)
                {
                    const double lo = inside.lo[k], hi = inside.hi[k];
                    const double v = (hi - lo)*ds*ds;
                    volume += v;
                    vec3 xm = x;
                    xm[ax] += 0.5*(lo + hi);
                    first += v*xm;
                }
            }
        }
        if (volume <= 0)
        {
            return;
        }

        // A's tangent plane inside B: its outward area vector, from where
        // the plane crosses n x n columns along the axis it faces most
        if (!inA)
        {
            int axA = 0;
            a.normal.cwiseAbs().maxCoeff(&axA);
            const int ua = (axA + 1) % 3, wa = (axA + 2) % 3;
            const double na = a.normal[axA];
            int crossings = 0;
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
                    if (inB || b.distance + b.normal.dot(x - c) <= 0) ++crossings;
                }
            }
            areaA = (crossings*ds*ds/std::abs(na))*a.normal;
        }
        sum.volume += volume;
        sum.first += first;
        sum.areaVector += areaA;

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

    octreeWalk walk(A, pA, B, pB, h, L);
    const double noBound = std::numeric_limits<double>::max();
    overlapTools::forEachLatticeCell
    (
        overlapTools::latticeRange(box, H), H,
        [&](const cellIndex&, const vec3& corner)
        {
            walk.visit(corner, H, -m, false, false, noBound, noBound, nullptr);
        }
    );
    std::map<cellIndex, baseCellSum> sums;
    for (auto& e : walk.sums)
    {
        if (e.second.volume > 0)
        {
            sums.emplace(e.first, std::move(e.second));
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

    std::map<int, baseCellSum> regions;
    for (const auto& e : sums)
    {
        baseCellSum& r = regions[sets.label(e.first)];
        const baseCellSum& s = e.second;
        r.volume += s.volume;
        r.first += s.first;
        r.areaVector += s.areaVector;
        r.edgePoints.insert(r.edgePoints.end(), s.edgePoints.begin(), s.edgePoints.end());
    }

    const vec3 centreLine = pB.position() - pA.position();
    for (const auto& e : regions)
    {
        const baseCellSum& r = e.second;
        contactRegion cr;
        cr.volume = r.volume;
        cr.point = r.first/r.volume;
        cr.normal = regionNormal(r.edgePoints, r.areaVector, centreLine);
        cr.area = r.areaVector.norm();
        g.regions.push_back(cr);
    }
    // A deterministic order: largest region first
    overlapTools::sortLargestFirst(g.regions, false);
    return g;
}

} // End namespace immersedDEM
