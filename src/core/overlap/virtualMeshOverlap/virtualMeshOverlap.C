#include "virtualMeshOverlap.H"
#include "octreeWalk.H"
#include "exactShortcuts.H"
#include "overlapTools.H"
#include "coreError.H"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

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

    // The exact answers, where one holds
    if (exactShortcuts::answer(*this, A, pA, B, pB, settings, g))
    {
        return g;
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
