// The virtual mesh's octree walk (octreeWalk.H): the cells' visit, the
// planarity tests that end a branch early, and the leaves' integration

#include "octreeWalk.H"

namespace immersedDEM
{
namespace virtualMesh
{

void octreeWalk::visit
(
    const vec3& lo, double s, int level, bool inA, bool inB,
    double boundA, double boundB, baseCellSum* sum,
    int sideA, int sideB
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


bool octreeWalk::planarNear
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


bool octreeWalk::planarCell
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


bool octreeWalk::facetedNear
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


void octreeWalk::leaf
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


void octreeWalk::clippedAreaOfA
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

} // End namespace virtualMesh
} // End namespace immersedDEM
