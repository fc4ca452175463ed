#include "immersedBodyBand.H"
#include "coreConversion.H"
#include "pairFilter.H"

using namespace immersedDEM;

namespace
{

constexpr auto v = &Foam::coreConversion::toFoam;
constexpr auto c = &Foam::coreConversion::toCore;

} // End anonymous namespace


Foam::immersedBodyBand::immersedBodyBand(const fvMesh& mesh)
:
    mesh_(mesh)
{}


void Foam::immersedBodyBand::clear()
{
    cellBoxes_.clear();
    reach_.clear();
    cellTree_.clear();
    bands_.clear();
    cleared_ = true;
}


void Foam::immersedBodyBand::update()
{
    const bool changing = mesh_.topoChanging() || mesh_.moving();
    if (cellBoxes_.size() == mesh_.nCells() && !changing && !cleared_)
    {
        return;
    }
    cleared_ = false;
    const pointField& points = mesh_.points();
    const vectorField& C = mesh_.cellCentres();
    const cellList& cells = mesh_.cells();
    const faceList& faces = mesh_.faces();
    const labelUList& own = mesh_.owner();
    const labelUList& nei = mesh_.neighbour();
    const label nInternal = mesh_.nInternalFaces();
    const polyBoundaryMesh& patches = mesh_.boundaryMesh();

    // Bounding boxes, and the reach of each centre: its box's farthest
    // corner and its farthest neighbour centre (across processor faces
    // too), beyond which the sharp surface needs only the sign
    cellBoxes_.setSize(mesh_.nCells());
    reach_.setSize(mesh_.nCells());
    bands_.clear();
    forAll(cells, celli)
    {
        treeBoundBox& b = cellBoxes_[celli];
        b = treeBoundBox(point::uniform(GREAT), point::uniform(-GREAT));
        for (const label facei : cells[celli])
        {
            for (const label pi : faces[facei])
            {
                b.min() = min(b.min(), points[pi]);
                b.max() = max(b.max(), points[pi]);
            }
        }
        const vector far = max(cmptMag(b.max() - C[celli]), cmptMag(C[celli] - b.min()));
        reach_[celli] = mag(far);
    }
    for (label facei = 0; facei < nInternal; ++facei)
    {
        const scalar d = mag(C[nei[facei]] - C[own[facei]]);
        reach_[own[facei]] = max(reach_[own[facei]], d);
        reach_[nei[facei]] = max(reach_[nei[facei]], d);
    }
    forAll(patches, patchi)
    {
        if (!patches[patchi].coupled()) continue;
        const vectorField delta(mesh_.boundary()[patchi].delta());
        const labelUList& fc = patches[patchi].faceCells();
        forAll(fc, i)
        {
            reach_[fc[i]] = max(reach_[fc[i]], mag(delta[i]));
        }
    }
    // Round-off of the centres and distances
    reach_ *= 1 + 1e-9;

    // A tree over the cached boxes (OpenFOAM's own cell tree recomputes a
    // cell's box at every test). A mesh that moves or changes its
    // topology (dynamicRefineFvMesh, every step or so) is scanned instead:
    // building a tree for it costs more than one pass over the boxes
    cellTree_.clear();
    if (!changing)
    {
        treeBoundBox overall(points);
        overall.inflate(1e-4);
        overall.min() -= point::uniform(ROOTVSMALL);
        overall.max() += point::uniform(ROOTVSMALL);
        cellTree_.reset
        (
            new indexedOctree<treeDataCell>
            (
                treeDataCell(true, mesh_, polyMesh::CELL_TETS),
                overall, 8, 10, 5.0
            )
        );
    }
}


Foam::labelList Foam::immersedBodyBand::cellsIn(const treeBoundBox& bb) const
{
    if (cellTree_.valid())
    {
        const labelList hits(cellTree_->findBox(bb));
        labelList found(hits.size());
        forAll(hits, i)
        {
            found[i] = cellTree_->shapes().cellLabels()[hits[i]];
        }
        // The tree's order depends on its leaves; the cells' order is
        // that of a scan
        Foam::sort(found);
        return found;
    }
    DynamicList<label> found;
    forAll(cellBoxes_, celli)
    {
        if (cellBoxes_[celli].overlaps(bb)) found.append(celli);
    }
    return labelList(std::move(found));
}


Foam::labelList Foam::immersedBodyBand::candidatesOf
(
    const rigidBody& b,
    const label bi,
    const treeBoundBox& bb,
    const scalar skin,
    const bool fromScratch
)
{
    if (bands_.size() <= size_t(bi)) bands_.resize(bi + 1);
    bodyBand& last = bands_[bi];
    const bool same = last.geometry == b.geometry.get() && last.name == b.name;
    if
    (
        fromScratch || !same || last.skinCells.empty()
     || !last.skinBox.contains(bb.min()) || !last.skinBox.contains(bb.max())
    )
    {
        // A new skin: bb grown on each side (by a cell, a body moving a
        // percent of a cell per step keeps it for tens of steps)
        const vector grow(vector::uniform(skin));
        last.skinBox = treeBoundBox(bb.min() - grow, bb.max() + grow);
        last.skinCells = cellsIn(last.skinBox);
        if (!same)
        {
            // Not the body of the last band: that band is void
            last.name = b.name;
            last.geometry = b.geometry.get();
            last.cells.clear();
            last.phi.clear();
        }
    }
    DynamicList<label> found(last.skinCells.size());
    for (const label celli : last.skinCells)
    {
        if (cellBoxes_[celli].overlaps(bb)) found.append(celli);
    }
    return labelList(std::move(found));
}


std::vector<narrowBand::value> Foam::immersedBodyBand::bandOf
(
    const rigidBody& b,
    const label bi,
    const labelList& cand,
    const bodyPose& pose,
    const bodyPose* lastPose
)
{
    const vectorField& C = mesh_.cellCentres();
    std::vector<narrowBand::value> band(cand.size());

    // The last band of this body, if it is the same body on the same mesh
    // and its pose then is known (none: every cell from its queries)
    if (bands_.size() <= size_t(bi)) bands_.resize(bi + 1);
    bodyBand& last = bands_[bi];
    const bool known =
        lastPose && last.geometry == b.geometry.get() && last.name == b.name
     && last.cells.size();

    // A cell centre x keeps its signed distance to within the distance
    // x moved in the body's frame since: |dx| + 2 sin(dtheta/2) |x - c|
    scalar m = 0;
    if (known)
    {
        scalar R = 0;
        for (const label celli : cand)
        {
            R = max(R, mag(C[celli] - v(pose.position())));
        }
        m = pairFilter::motionBound(*lastPose, pose, R);
    }

    // Settled from the last band, or queried: one by one where the cell
    // was near the surface, by narrowBand where new to the body's box
    std::vector<label> again, fresh;
    label j = 0;
    forAll(cand, i)
    {
        const label celli = cand[i];
        if (known)
        {
            while (j < last.cells.size() && last.cells[j] < celli) ++j;
        }
        if (!known || j >= last.cells.size() || last.cells[j] != celli)
        {
            fresh.push_back(i);
            continue;
        }
        const scalar lower = mag(last.phi[j]) - m;
        if (lower > reach_[celli])
        {
            band[i].exact = false;
            band[i].phi = last.phi[j] > 0 ? lower : -lower;
        }
        else
        {
            again.push_back(i);
        }
    }
    for (const label i : again)
    {
        narrowBand::value& d = band[i];
        d.sp = b.geometry->closest(pose, c(C[cand[i]]));
        d.phi = d.sp.distance;
        d.exact = true;
    }
    if (!fresh.empty())
    {
        std::vector<vec3> x(fresh.size());
        std::vector<double> r(fresh.size());
        forAll(fresh, k)
        {
            x[k] = c(C[cand[fresh[k]]]);
            r[k] = reach_[cand[fresh[k]]];
        }
        const auto found = narrowBand::signedDistances(*b.geometry, pose, x, r);
        forAll(fresh, k)
        {
            band[fresh[k]] = found[k];
        }
    }

    last.name = b.name;
    last.geometry = b.geometry.get();
    last.cells = cand;
    last.phi.resize(cand.size());
    forAll(cand, i)
    {
        last.phi[i] = band[i].phi;
    }
    return band;
}


