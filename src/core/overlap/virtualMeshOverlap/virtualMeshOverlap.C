#include "virtualMeshOverlap.H"
#include "octreeWalk.H"
#include "convexOverlap.H"
#include "convexPolyhedron.H"
#include "pieceOverlap.H"
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
using namespace virtualMesh;


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

    // Bodies made of convex pieces: the sum of their pieces' exact
    // overlaps, each pair of pieces measured here (the convex routes below)
    if (settings.convexExact && pieceOverlap::handles(A, B))
    {
        return pieceOverlap::evaluate(*this, A, pA, B, pB, settings);
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
