#include "cellsOverlap.H"
#include "overlapTools.H"

#include <algorithm>
#include <cmath>
#include <map>

namespace immersedDEM
{

namespace
{

using overlapTools::cellIndex;

struct sharedCell
{
    vec3 corner;
    double lambdaA;
    double lambdaB;
};


// The fraction of the cell's sample points inside the body
double sampledFraction
(
    const shape& s, const bodyPose& p, const vec3& corner, double h, long& queries
)
{
    const int m = cellsOverlap::nSample;
    const double ds = h/m;
    int in = 0;
    for (int l = 0; l < m; ++l)
    {
        for (int j = 0; j < m; ++j)
        {
            for (int i = 0; i < m; ++i)
            {
                in += s.inside(p, corner + ds*vec3(i + 0.5, j + 0.5, l + 0.5));
            }
        }
    }
    queries += m*m*m;
    return double(in)/(m*m*m);
}

} // End anonymous namespace


contactGeometry cellsOverlap::evaluate
(
    const shape& A, const bodyPose& pA,
    const shape& B, const bodyPose& pB,
    const overlapSettings& settings
) const
{
    const double h = settings.h;
    overlapTools::checkCellSize(type(), h);

    contactGeometry g;
    const axisAlignedBox box = overlapTools::commonBox(A, pA, B, pB);
    if (box.empty())
    {
        return g;
    }

    // The shared cells: lambda_A > 0 and lambda_B > 0
    std::map<cellIndex, sharedCell> shared;
    long queries = 0, leaves = 0;
    overlapTools::forEachScreenedCell
    (
        A, pA, B, pB, box, h, queries, leaves,
        [&](const cellIndex& ci, const vec3& corner, double dA, double dB, double r)
        {
            const double lA = dA < -r ? 1.0 : sampledFraction(A, pA, corner, h, queries);
            if (lA <= 0) return;
            const double lB = dB < -r ? 1.0 : sampledFraction(B, pB, corner, h, queries);
            if (lB <= 0) return;
            shared.emplace(ci, sharedCell{corner, lA, lB});
        }
    );
    g.queries = queries;
    g.leaves = leaves;
    if (shared.empty())
    {
        return g;
    }

    // Regions: shared cells joined across faces
    overlapTools::cellRegions sets(shared, overlapTools::cellJoin::faces);
    std::vector<const sharedCell*> cells;
    std::map<int, std::vector<int>> members;
    for (const auto& e : shared)
    {
        members[sets.label(e.first)].push_back(int(cells.size()));
        cells.push_back(&e.second);
    }

    const double V = h*h*h;
    const vec3 centreLine = pB.position() - pA.position();
    for (const auto& e : members)
    {
        double volume = 0;
        vec3 first = vec3::Zero(), mean = vec3::Zero();
        std::vector<vec3> edgeCentres;
        for (int m : e.second)
        {
            const sharedCell& sc = *cells[m];
            const vec3 c = sc.corner + vec3::Constant(0.5*h);
            const double v = std::max(0.0, sc.lambdaA + sc.lambdaB - 1)*V;
            volume += v;
            first += v*c;
            mean += c;
            if (sc.lambdaA < 1 && sc.lambdaB < 1) edgeCentres.push_back(c);
        }
        if (!(volume > 0))
        {
            continue;
        }
        mean /= double(e.second.size());

        // A to B: cells on B's side hold more of B
        vec3 side = vec3::Zero();
        double sideScale = 0;
        for (int m : e.second)
        {
            const sharedCell& sc = *cells[m];
            const vec3 x = sc.corner + vec3::Constant(0.5*h) - mean;
            side += (sc.lambdaB - sc.lambdaA)*x;
            sideScale += std::abs(sc.lambdaB - sc.lambdaA)*x.norm();
        }
        if (!(side.norm() > 1e-9*sideScale))
        {
            side = vec3::Zero();    // symmetric: round-off only
        }
        const vec3 ref = overlapTools::firstDirection({side, centreLine});

        // Undetermined (fewer than 3 edge cells, or collinear): the centre line
        vec3 normal = overlapTools::firstDirection({centreLine, side});
        overlapTools::planeFitCriteria plane;
        plane.minSpread = 1e-6;
        overlapTools::fitPlaneNormal(edgeCentres, ref, plane, normal);

        // Area: the shadow of the cells that add volume
        overlapTools::projectedPixels pixels(normal, h/nSample);
        for (int m : e.second)
        {
            const sharedCell& sc = *cells[m];
            if (sc.lambdaA + sc.lambdaB <= 1) continue;
            pixels.markCube(sc.corner, nSample);
        }

        contactRegion cr;
        cr.volume = volume;
        cr.point = first/volume;
        cr.normal = normal;
        cr.area = pixels.area();
        g.regions.push_back(cr);
    }
    overlapTools::sortLargestFirst(g.regions, true);
    return g;
}

} // End namespace immersedDEM
