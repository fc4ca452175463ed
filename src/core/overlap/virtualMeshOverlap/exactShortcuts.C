#include "exactShortcuts.H"
#include "convexOverlap.H"
#include "convexPolyhedron.H"
#include "pieceOverlap.H"
#include "halfSpaceShape.H"
#include "triangleMeshShape.H"
#include "sphereOverlap.H"
#include "sphereShape.H"
#include "wallMeshShape.H"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace immersedDEM
{

namespace
{

// Whether some point of a convex body (corners: its vertices in the
// wall's frame) lies behind both planes by more than eps: the part of the
// body behind p (a convex polytope) reaches behind q iff one of its
// corners does, and those are the body's corners behind p and the points
// where its edges cross p
bool convexBehindBoth
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


// Distance from x to the region behind both planes p and q (where both
// heights are negative): zero inside it; else the least of the
// distances to the projections of x onto p, onto q and onto their common
// line that lie in the region (the nearest point of a convex region is
// the projection onto the planes active there, and any point of the
// region is at least that far). Infinite when the region is empty
// (opposite walls nearer than the two planes' offsets allow)
double distanceBehindBoth
(
    const vec3& x,
    const wallMeshShape::plane& p,
    const wallMeshShape::plane& q
)
{
    const double hp = p.normal.dot(x) - p.offset;
    const double hq = q.normal.dot(x) - q.offset;
    if (hp <= 0 && hq <= 0) return 0;
    const double c = p.normal.dot(q.normal);
    double best = std::numeric_limits<double>::infinity();
    // Onto p (x - hp n_p, whose height over q is hq - hp c), onto q
    if (hp > 0 && hq - hp*c <= 0) best = hp;
    if (hq > 0 && hp - hq*c <= 0) best = std::min(best, hq);
    // Onto the common line: x - a n_p - b n_q on both planes, a + b c = hp
    // and a c + b = hq; none for parallel planes
    const double det = 1 - c*c;
    if (det > 1e-12)
    {
        const double a = (hp - c*hq)/det;
        const double b = (hq - c*hp)/det;
        best = std::min(best, std::sqrt(std::max(a*a + b*b + 2*a*b*c, 0.0)));
    }
    return best;
}

} // End anonymous namespace


bool exactShortcuts::answer
(
    const overlapEngine& engine,
    const shape& A, const bodyPose& pA,
    const shape& B, const bodyPose& pB,
    const overlapSettings& settings,
    contactGeometry& g
)
{
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
            return true;
        }
    }

    // Two spheres, or a sphere and a plane: the analytic lens or cap (a
    // suspension in a periodic box, where the DEM's sphere sweep does not
    // take the pairs, would otherwise refine every lens to d/320)
    if (settings.convexExact && sphereOverlap::handles(A, B))
    {
        g = sphereOverlap().evaluate(A, pA, B, pB, settings);
        return true;
    }

    // Bodies made of convex pieces: the sum of their pieces' exact
    // overlaps, each pair of pieces measured here (the convex routes below)
    if (settings.convexExact && pieceOverlap::handles(A, B))
    {
        g = pieceOverlap::evaluate(engine, A, pA, B, pB, settings);
        return true;
    }

    // Convex pairs: the exact intersection, cheaper than any octree
    if (settings.convexExact)
    {
        if (convexOverlap::handles(A, B))
        {
            g = convexOverlap().evaluate(A, pA, B, pB, settings);
            return true;
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
            g = convexOverlap().evaluate(plane, pP, B, pB, settings);
            return true;
        }
        if
        (
            ma && wb && ma->convex()
         && wb->flatNear(pB.toBody(pA.position()), ma->boundingRadius(), x, n)
        )
        {
            const halfSpaceShape plane;
            const bodyPose pP = halfSpaceShape::poseOf(pB.toWorld(x), pB.vectorToWorld(n));
            g = convexOverlap().evaluate(A, pA, plane, pP, settings);
            return true;
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
                    return true;
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
                    return true;
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
            g = sphereOverlap::cap
            (
                pA.toWorld(x), pA.vectorToWorld(n), pB.position(), sb->radius()
            );
            return true;
        }
        if (sa && wb && wb->flatNear(pB.toBody(pA.position()), sa->radius(), x, n))
        {
            g = sphereOverlap::cap
            (
                pB.toWorld(x), pB.vectorToWorld(n), pA.position(), sa->radius()
            );
            for (contactRegion& r : g.regions) r.normal = -r.normal;
            return true;
        }
        // A sphere in a locally convex fluid region of a wall mesh (a box
        // tank's corner or edge): one cap per plane it crosses when no two
        // caps share a point (the sphere's parts behind two planes are
        // apart iff the region behind both is at least a radius from its
        // centre); their sum is then its overlap with the wall's solid,
        // the union of the half-spaces. Caps that meet (a sphere pressed
        // into a faceted tube) stay the octree's
        if (settings.convexExact && ((wa && sb) || (sa && wb)))
        {
            const bool wallFirst = wa != nullptr;
            const wallMeshShape& w = wallFirst ? *wa : *wb;
            const bodyPose& pW = wallFirst ? pA : pB;
            const bodyPose& pS = wallFirst ? pB : pA;
            const double R = wallFirst ? sb->radius() : sa->radius();
            const vec3 c = pW.toBody(pS.position());
            std::vector<wallMeshShape::plane> planes;
            if (w.convexFluidNear(c, R, planes))
            {
                const double eps = 1e-12*R;
                std::vector<const wallMeshShape::plane*> crossed;
                for (const wallMeshShape::plane& q : planes)
                {
                    if (q.normal.dot(c) - q.offset < R - eps) crossed.push_back(&q);
                }
                bool apart = true;
                for (size_t i = 0; apart && i < crossed.size(); ++i)
                {
                    for (size_t j = i + 1; apart && j < crossed.size(); ++j)
                    {
                        apart = distanceBehindBoth(c, *crossed[i], *crossed[j]) >= R - eps;
                    }
                }
                if (apart)
                {
                    for (const wallMeshShape::plane* q : crossed)
                    {
                        contactGeometry one = sphereOverlap::cap
                        (
                            pW.toWorld(q->offset*q->normal),
                            pW.vectorToWorld(q->normal),
                            pS.position(),
                            R
                        );
                        for (contactRegion& r : one.regions)
                        {
                            if (!wallFirst) r.normal = -r.normal;
                            g.regions.push_back(r);
                        }
                    }
                    return true;
                }
            }
        }
    }

    return false;
}

} // End namespace immersedDEM
