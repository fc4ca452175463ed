#include "pairFilter.H"
#include "convexDistance.H"
#include "convexPolyhedron.H"
#include "triangleMeshShape.H"
#include "sphereShape.H"
#include "halfSpaceShape.H"
#include "wallMeshShape.H"
#include "surfaceTriangles.H"

#include <algorithm>
#include <cmath>
#include <limits>

namespace immersedDEM
{

namespace
{

constexpr double unknown = -std::numeric_limits<double>::infinity();

//- A wall surface: the body's ball (world centre c, radius R) lies where
//  the wall's distance has the sign of a closed surface (every point of the
//  ball nearer to a face away from the rim than to any face at the rim), and
//  'probe' (a world point of the body) is on the fluid side
bool wallSideClear
(
    const wallMeshShape& W, const bodyPose& pW,
    const vec3& c, double R, const vec3& probe
)
{
    const vec3 cW = pW.toBody(c);
    if (const triangleBVH* open = W.openFaces())
    {
        const double dAll = std::abs(W.distanceField().closest(cW).distance);
        const double dOpen = std::sqrt(open->closest(cW).distSqr);
        if (!(dOpen - R > dAll + R))
        {
            return false;
        }
    }
    return W.signedDistance(pW.toBody(probe)) > 0;
}


//- Gap between a plane and a shape
double planeGap(const bodyPose& pP, const shape& S, const bodyPose& pS)
{
    const vec3 n = pP.vectorToWorld(vec3::UnitZ());
    const double h0 = n.dot(pS.position() - pP.position());
    if (const auto* s = shapeAs<sphereShape>(S))
    {
        return h0 - s->radius();
    }
    if (const auto* m = shapeAs<triangleMeshShape>(S))
    {
        return h0 + m->distanceField().tree().minAlong(pS.vectorToBody(n));
    }
    return h0 - S.boundingRadius();
}


//- Gap between a sphere (centre c, radius r) and a surface shape
double sphereGap(const vec3& c, double r, const shape& S, const bodyPose& pS)
{
    const double d = S.signedDistance(pS, c);
    if (!(d > r))
    {
        return d - r;
    }
    if (const auto* w = shapeAs<wallMeshShape>(S))
    {
        if (!wallSideClear(*w, pS, c, r, c))
        {
            return unknown;
        }
    }
    return d - r;
}

} // End anonymous namespace


double pairFilter::engineReach(const std::string& method, const overlapSettings& s)
{
    if (method == "virtualMesh")
    {
        return 1.01*std::sqrt(3.0)*s.h/double(1L << std::max(0, s.level));
    }
    return 1e-9*s.h;
}


double pairFilter::motionBound(const bodyPose& p0, const bodyPose& p1, double radius)
{
    if (p0.orientation().coeffs() == p1.orientation().coeffs())
    {
        return (p1.position() - p0.position()).norm();
    }
    // |R1 x - R0 x| = |(R1 R0^T - I) R0 x| <= 2 sin(theta/2) |x|, and
    // sin(theta/2) is the length of the vector part of q1 q0^-1
    const quat dq = p1.orientation()*p0.orientation().conjugate();
    const double s = std::min(1.0, dq.vec().norm()*(1 + 1e-12) + 1e-15);
    return (p1.position() - p0.position()).norm() + 2*s*radius;
}


double pairFilter::gapLowerBound
(
    const shape& A, const bodyPose& pA,
    const shape& B, const bodyPose& pB,
    double stopBelow, double cap
)
{
    const double RA = A.boundingRadius(), RB = B.boundingRadius();
    const double spheres = (pA.position() - pB.position()).norm() - RA - RB;

    const auto* sA = shapeAs<sphereShape>(A);
    const auto* sB = shapeAs<sphereShape>(B);
    if (sA && sB)
    {
        return spheres;
    }
    if (spheres >= cap)
    {
        return spheres;
    }

    if (shapeAs<halfSpaceShape>(A))
    {
        return planeGap(pA, B, pB);
    }
    if (shapeAs<halfSpaceShape>(B))
    {
        return planeGap(pB, A, pA);
    }

    const triangleBVH* tA = trianglesOf(A);
    const triangleBVH* tB = trianglesOf(B);
    if (sA && tB)
    {
        return sphereGap(pA.position(), sA->radius(), B, pB);
    }
    if (sB && tA)
    {
        return sphereGap(pB.position(), sB->radius(), A, pA);
    }
    if (!tA || !tB || tA->empty() || tB->empty())
    {
        return spheres;
    }

    // B's triangles in A's frame: x_A = R_A^T (R_B x_B + c_B - c_A)
    const mat3 R = pA.rotation().transpose()*pB.rotation();
    const vec3 t = pA.rotation().transpose()*(pB.position() - pA.position());

    // A convex body in a locally convex part of a wall mesh: the least
    // height of its corners over the wall's planes, exact
    {
        bool wallFirst = false;
        const convexWallGap cw = convexWallDistance(A, pA, B, pB, cap, wallFirst);
        if (cw.known)
        {
            return cw.gap - 1e-9*std::min(RA, RB);
        }
    }
    // Two convex meshes: the exact distance of their corners' hulls
    // (GJK), less round-off; no surface inside the other can hide there
    const auto* mA = shapeAs<triangleMeshShape>(A);
    const auto* mB = shapeAs<triangleMeshShape>(B);
    if (mA && mB && mA->convex() && mB->convex())
    {
        const convexClosest c =
            convexDistance(mA->convex()->vertices(), mB->convex()->vertices(), R, t);
        return c.intersecting ? 0.0 : c.distance - 1e-9*std::min(RA, RB);
    }
    // Bodies of convex pieces (and convex ones): the least distance of
    // their pieces, exact, no surface inside another to hide
    if
    (
        mA && mB && madeOfConvexParts(*mA) && madeOfConvexParts(*mB)
     && (!mA->convex() || !mB->convex())
    )
    {
        const convexClosest c = closestParts(*mA, pA, *mB, pB, cap, stopBelow, true);
        return c.intersecting ? 0.0 : c.distance - 1e-9*std::min(RA, RB);
    }
    const double g = triangleBVH::separation(*tA, *tB, R, t, cap, stopBelow);
    if (!(g > 0))
    {
        return g;
    }

    // The surfaces are apart: neither solid inside the other
    const auto* wA = shapeAs<wallMeshShape>(A);
    const auto* wB = shapeAs<wallMeshShape>(B);
    const vec3 cornerA = pA.toWorld(tA->anyCorner());
    const vec3 cornerB = pB.toWorld(tB->anyCorner());
    if (wA && wB)
    {
        return unknown;
    }
    if (wA)
    {
        return wallSideClear(*wA, pA, pB.position(), RB, cornerB) ? g : unknown;
    }
    if (wB)
    {
        return wallSideClear(*wB, pB, pA.position(), RA, cornerA) ? g : unknown;
    }
    if (A.signedDistance(pA, cornerB) > 0 && B.signedDistance(pB, cornerA) > 0)
    {
        return g;
    }
    return unknown;
}


bool pairFilter::separated
(
    int a, int b,
    const shape& A, const bodyPose& pA,
    const shape& B, const bodyPose& pB
)
{
    ++counters_.tested;
    const double RA = A.boundingRadius(), RB = B.boundingRadius();
    const double spheres = (pA.position() - pB.position()).norm() - RA - RB;
    if (spheres > reach_)
    {
        ++counters_.rejectedBySpheres;
        return true;
    }
    const auto* sA = shapeAs<sphereShape>(A);
    const auto* sB = shapeAs<sphereShape>(B);
    if (sA && sB)
    {
        // The spheres' gap is exact: nothing better to prove
        ++counters_.passed;
        return false;
    }
    // A plane and a sphere: the exact gap costs less than a record
    const bool planeA = sB && shapeAs<halfSpaceShape>(A);
    const bool planeB = sA && shapeAs<halfSpaceShape>(B);
    if (planeA || planeB)
    {
        const double g = planeA ? planeGap(pA, B, pB) : planeGap(pB, A, pA);
        if (g > reach_)
        {
            ++counters_.rejectedBySpheres;
            return true;
        }
        ++counters_.passed;
        return false;
    }

    // The gap a proof must exceed: any positive one, or the reach
    const double beyond = provenGapRejects_ ? 0.0 : reach_;
    record& r = records_[key(a, b)];
    // A record of other shapes (a body given a new shape) is void
    const bool known = r.stamp != 0 && r.A == &A && r.B == &B;
    r.stamp = stamp_;
    if (known && r.gap > beyond)
    {
        const double g = r.gap - motionBound(r.pA, pA, RA) - motionBound(r.pB, pB, RB);
        if (g > beyond)
        {
            ++counters_.rejectedByReuse;
            return true;
        }
    }
    if (known && r.touching)
    {
        ++counters_.passed;
        return false;
    }

    // A new proof; no need to see further than a margin that lets it
    // serve for a while
    ++counters_.proofs;
    const double cap = reach_ + std::max(reach_, 0.25*std::min(RA, RB));
    r.pA = pA;
    r.pB = pB;
    r.A = &A;
    r.B = &B;
    r.gap = gapLowerBound(A, pA, B, pB, beyond, cap);
    r.touching = false;
    if (r.gap > beyond)
    {
        ++counters_.rejectedByProof;
        return true;
    }
    ++counters_.passed;
    return false;
}


void pairFilter::engineResult(int a, int b, bool touching)
{
    const auto it = records_.find(key(a, b));
    if (it != records_.end())
    {
        it->second.touching = touching;
    }
}


void pairFilter::stillTouching(int a, int b)
{
    const auto it = records_.find(key(a, b));
    if (it != records_.end())
    {
        it->second.stamp = stamp_;
        it->second.touching = true;
    }
}


void pairFilter::endSweep()
{
    for (auto it = records_.begin(); it != records_.end();)
    {
        if (it->second.stamp != stamp_)
        {
            it = records_.erase(it);
        }
        else
        {
            ++it;
        }
    }
}

} // End namespace immersedDEM
