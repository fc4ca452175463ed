#include "immersedBoundaryProjection.H"
#include "coreConversion.H"
#include "parallelSum.H"
#include "boxFraction.H"
#include "narrowBand.H"
#include "pairFilter.H"
#include "indexedOctree.H"
#include "treeDataCell.H"
#include "treeBoundBox.H"
#include "clockTime.H"
#include "surfaceFields.H"

using namespace immersedDEM;

namespace Foam
{
    defineTypeNameAndDebug(immersedBoundaryProjection, 0);
}


namespace
{

constexpr auto v = &Foam::coreConversion::toFoam;
constexpr auto c = &Foam::coreConversion::toCore;

} // End anonymous namespace


Foam::immersedBoundaryProjection::immersedBoundaryProjection(const fvMesh& mesh)
:
    mesh_(mesh),
    lambda_
    (
        IOobject("lambda", mesh.time().timeName(), mesh, IOobject::NO_READ, IOobject::AUTO_WRITE),
        mesh,
        dimensionedScalar(dimless, Zero)
    ),
    Uib_
    (
        IOobject("Uib", mesh.time().timeName(), mesh, IOobject::NO_READ, IOobject::AUTO_WRITE),
        mesh,
        dimensionedVector(dimVelocity, Zero)
    ),
    contactZone_
    (
        IOobject("contactZone", mesh.time().timeName(), mesh, IOobject::NO_READ, IOobject::NO_WRITE),
        mesh,
        dimensionedScalar(dimless, Zero)
    )
{
    // Until an fvOption sets the forcing nothing forces the fluid: the
    // plain volume fractions
    forcing_.sharp = false;
}


Foam::scalar Foam::immersedBoundaryProjection::largestCellSize()
{
    if (!(largestCellSize_ > 0))
    {
        // The ring of fluid cells next to a body's centre-inside cells
        // lies within one cell of its box
        scalar h = 0;
        for (const scalar Vc : mesh_.V()) h = max(h, cbrt(Vc));
        largestCellSize_ = returnReduce(h, maxOp<scalar>());
        // Split and graded hexahedra are not cubes
        largestCellSize_ *= 2;
    }
    return largestCellSize_;
}


void Foam::immersedBoundaryProjection::updateCellData()
{
    const bool changing = mesh_.topoChanging() || mesh_.moving();
    if (cellBoxes_.size() == mesh_.nCells() && !changing)
    {
        return;
    }
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
    lastBand_.clear();
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


Foam::labelList Foam::immersedBoundaryProjection::cellsIn(const treeBoundBox& bb) const
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


Foam::labelList Foam::immersedBoundaryProjection::candidatesOf
(
    const rigidBody& b,
    const label bi,
    const treeBoundBox& bb
)
{
    if (lastBand_.size() <= size_t(bi)) lastBand_.resize(bi + 1);
    bodyBand& last = lastBand_[bi];
    const bool same = last.geometry == b.geometry.get() && last.name == b.name;
    if
    (
        debug || !same || last.skinCells.empty()
     || !last.skinBox.contains(bb.min()) || !last.skinBox.contains(bb.max())
    )
    {
        // A new skin: bb grown by a cell on each side (a body moving a
        // percent of a cell per step keeps it for tens of steps)
        const vector skin(vector::uniform(0.5*largestCellSize_));
        last.skinBox = treeBoundBox(bb.min() - skin, bb.max() + skin);
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


std::vector<narrowBand::value> Foam::immersedBoundaryProjection::bandOf
(
    const rigidBody& b,
    const label bi,
    const labelList& cand
)
{
    const vectorField& C = mesh_.cellCentres();
    std::vector<narrowBand::value> band(cand.size());

    // The last band of this body, if it is the same body on the same mesh
    // (the debug switch: none, every cell from its queries)
    if (lastBand_.size() <= size_t(bi)) lastBand_.resize(bi + 1);
    bodyBand& last = lastBand_[bi];
    const bool known =
        !debug && last.geometry == b.geometry.get() && last.name == b.name
     && size_t(bi) < projectedPose_.size() && last.cells.size();

    // A cell centre x keeps its signed distance to within the distance
    // x moved in the body's frame since: |dx| + 2 sin(dtheta/2) |x - c|
    scalar m = 0;
    if (known)
    {
        scalar R = 0;
        for (const label celli : cand)
        {
            R = max(R, mag(C[celli] - v(b.pose.position())));
        }
        m = pairFilter::motionBound(projectedPose_[bi], b.pose, R);
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
        d.sp = b.geometry->closest(b.pose, c(C[cand[i]]));
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
        const auto found = narrowBand::signedDistances(*b.geometry, b.pose, x, r);
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


Foam::labelList Foam::immersedBoundaryProjection::bodiesToProject
(
    const demSolver& dem,
    bool& all
) const
{
    const auto& bodies = dem.bodies();
    const size_t n = bodies.size();
    all =
        projectAll_ || debug || mesh_.dynamic() || mesh_.moving()
     || projectedPose_.size() != n;
    if (all) return labelList();

    // Moved since their last projection: pose or velocities (Uib)
    std::vector<bool> in(n, false);
    DynamicList<label> set;
    for (size_t bi = 0; bi < n; ++bi)
    {
        if (dem.isWall(int(bi))) continue;
        const rigidBody& b = bodies[bi];
        const bodyPose& p = projectedPose_[bi];
        if
        (
            b.pose.position() != p.position()
         || b.pose.orientation().coeffs() != p.orientation().coeffs()
         || b.velocity != projectedVelocity_[bi]
         || b.angularVelocity != projectedAngularVelocity_[bi]
        )
        {
            in[bi] = true;
            set.append(label(bi));
        }
    }
    if (set.empty()) return labelList();

    // Their cells (lambda > 0, and the sharp surface's ring) lie in their
    // world boxes grown by a cell; a body whose box, grown alike, comes
    // within a cell of theirs (before or after the move) may share cells
    // with them (the larger fraction wins, the first ring claims): it is
    // projected again too, and so on. Then the bodies not projected own
    // cells no projected body can reach, and the result is that of
    // projecting every body
    const scalar g = 2*largestCellSize_;
    std::vector<axisAlignedBox> now(n);
    for (size_t bi = 0; bi < n; ++bi)
    {
        if (dem.isWall(int(bi))) continue;
        now[bi] = bodies[bi].geometry->worldBox(bodies[bi].pose).inflated(g);
    }
    for (label k = 0; k < set.size(); ++k)
    {
        const label i = set[k];
        const axisAlignedBox before = projectedBox_[i].inflated(g);
        for (size_t j = 0; j < n; ++j)
        {
            if (in[j] || dem.isWall(int(j))) continue;
            if (now[j].overlaps(now[i]) || now[j].overlaps(before))
            {
                in[j] = true;
                set.append(label(j));
            }
        }
    }
    label nBodies = 0;
    for (size_t bi = 0; bi < n; ++bi)
    {
        if (!dem.isWall(int(bi))) ++nBodies;
    }
    if (set.size() == nBodies)
    {
        all = true;
        return labelList();
    }
    Foam::sort(set);
    return labelList(std::move(set));
}


Foam::label Foam::immersedBoundaryProjection::project(const demSolver& dem)
{
    const clockTime timer;

    scalarField& lambda = lambda_.primitiveFieldRef();
    vectorField& Uib = Uib_.primitiveFieldRef();
    scalarField& zone = contactZone_.primitiveFieldRef();
    const auto& bodies = dem.bodies();
    const scalarField& V = mesh_.V();

    bool all = true;
    labelList toProject;
    if (bodyOf_.size() != mesh_.nCells())
    {
        // New mesh (start, topology change): everything
        lambda = 0;
        Uib = Zero;
        zone = 0;
        bodyOf_.setSize(mesh_.nCells());
        bodyOf_ = -1;
        secondOf_.setSize(mesh_.nCells());
        secondOf_ = -1;
        secondLambda_.setSize(mesh_.nCells());
        secondLambda_ = 0;
        wallK_.setSize(mesh_.nCells());
        wallK_ = 0;
        largestCellSize_ = 0;
        cellBoxes_.clear();
        touched_.clear();
    }
    else
    {
        largestCellSize();
        toProject = bodiesToProject(dem, all);
        if (!all && toProject.empty())
        {
            // Nothing moved: the cells stay as they are
            lastProjected_ = 0;
            projectedTimeIndex_ = mesh_.time().timeIndex();
            seconds_ += timer.elapsedTime();
            label nCells = 0;
            for (const label celli : touched_)
            {
                if (lambda[celli] > 0) ++nCells;
            }
            return nCells;
        }
        // Only the cells the last projection set (of the bodies projected
        // now): the cost follows the bodies, not the mesh
        std::vector<bool> again(bodies.size(), all);
        for (const label bi : toProject) again[bi] = true;
        label kept = 0;
        for (const label celli : touched_)
        {
            const label bi = bodyOf_[celli];
            if (!all && bi >= 0 && !again[bi])
            {
                // Kept; a share of a body projected again is set again
                if (secondOf_[celli] >= 0 && again[secondOf_[celli]])
                {
                    secondOf_[celli] = -1;
                    secondLambda_[celli] = 0;
                }
                touched_[kept++] = celli;
                continue;
            }
            lambda[celli] = 0;
            Uib[celli] = Zero;
            zone[celli] = 0;
            bodyOf_[celli] = -1;
            secondOf_[celli] = -1;
            secondLambda_[celli] = 0;
            wallK_[celli] = 0;
        }
        touched_.setSize(kept);
    }
    if (all)
    {
        toProject.setSize(bodies.size());
        label k = 0;
        for (size_t bi = 0; bi < bodies.size(); ++bi)
        {
            if (!dem.isWall(int(bi))) toProject[k++] = label(bi);
        }
        toProject.setSize(k);
    }
    largestCellSize();

    const vectorField& C = mesh_.cellCentres();
    updateCellData();
    auto cellBox = [&](const label celli, vec3& lo, vec3& hi)
    {
        lo = c(cellBoxes_[celli].min());
        hi = c(cellBoxes_[celli].max());
    };

    // Each body's cells: those whose boxes meet its world box (grown by a
    // cell for the sharp surface's ring of fluid cells), with the signed
    // distances of their centres, exact near the surface only
    // (narrowBand: far cells are settled in groups)
    const vector grow
    (
        vector::uniform(forcing_.sharp ? largestCellSize_ : scalar(0))
    );
    std::vector<labelList> candidates(toProject.size());
    std::vector<std::vector<narrowBand::value>> band(toProject.size());
    projectedVolume_.setSize(bodies.size());
    projectedVolume_ = Zero;
    forAll(toProject, k)
    {
        const label bi = toProject[k];
        const rigidBody& b = bodies[bi];
        const axisAlignedBox wb = b.geometry->worldBox(b.pose);
        candidates[k] = candidatesOf(b, bi, treeBoundBox(v(wb.min) - grow, v(wb.max) + grow));
        const labelList& cand = candidates[k];
        band[k] = bandOf(b, bi, cand);

        const treeBoundBox bb(v(wb.min), v(wb.max));
        forAll(cand, i)
        {
            const label celli = cand[i];
            if (!cellBoxes_[celli].overlaps(bb)) continue;
            const narrowBand::value& d = band[k][i];
            scalar f = d.phi < 0 ? 1 : 0;
            if (d.exact)
            {
                // The reach covers the box's corners: a cell settled by
                // the band is wholly inside or outside. A cut cell: the
                // surface's second-order model at the centre's closest
                // point, or eight pieces' planes where a crease passes
                vec3 lo, hi;
                cellBox(celli, lo, hi);
                f = boxFraction::fromQuery(*b.geometry, b.pose, lo, hi, c(C[celli]), d.sp);
            }
            if (f > lambda[celli])
            {
                if (bodyOf_[celli] < 0) touched_.append(celli);
                if (bodyOf_[celli] >= 0 && lambda[celli] > secondLambda_[celli])
                {
                    // The body that had the cell keeps its share of it
                    secondOf_[celli] = bodyOf_[celli];
                    secondLambda_[celli] = lambda[celli];
                }
                lambda[celli] = f;
                bodyOf_[celli] = label(bi);
                Uib[celli] = v(b.pointVelocity(c(C[celli])));
            }
            else if (f > secondLambda_[celli])
            {
                secondOf_[celli] = label(bi);
                secondLambda_[celli] = f;
            }
        }
    }
    if (forcing_.sharp)
    {
        forAll(toProject, k)
        {
            projectSharp(bodies[toProject[k]], toProject[k], candidates[k], band[k]);
        }
    }
    label nCells = 0;
    for (const label celli : touched_)
    {
        if (bodyOf_[celli] < 0) continue;
        if (lambda[celli] > 0) ++nCells;
        projectedVolume_[bodyOf_[celli]] += lambda[celli]*V[celli];
        if (secondOf_[celli] >= 0)
        {
            projectedVolume_[secondOf_[celli]] += secondLambda_[celli]*V[celli];
        }
    }

    // The contact zone is a refinement field: only a dynamic mesh reads it,
    // and the pairs loop is quadratic in the bodies
    for (size_t i = 0; mesh_.dynamic() && i < bodies.size(); ++i)
    {
        if (dem.isWall(int(i))) continue;
        for (size_t j = i + 1; j < bodies.size(); ++j)
        {
            if (dem.isWall(int(j))) continue;
            const scalar margin = 0.5*min
            (
                bodies[i].equivalentRadius(), bodies[j].equivalentRadius()
            );
            const axisAlignedBox bi = bodies[i].geometry->worldBox(bodies[i].pose);
            const axisAlignedBox bj = bodies[j].geometry->worldBox(bodies[j].pose);
            const vec3 lo = bi.min.cwiseMax(bj.min) - vec3::Constant(margin);
            const vec3 hi = bi.max.cwiseMin(bj.max) + vec3::Constant(margin);
            if ((lo.array() > hi.array()).any()) continue;
            for (const label celli : cellsIn(treeBoundBox(v(lo), v(hi))))
            {
                if (bodyOf_[celli] < 0 && zone[celli] == 0)
                {
                    touched_.append(celli);
                }
                zone[celli] = 1;
            }
        }
    }
    contactZone_.correctBoundaryConditions();
    immersedDEMParallel::sumOverProcessors(projectedVolume_);
    lambda_.correctBoundaryConditions();
    Uib_.correctBoundaryConditions();
    projectedTimeIndex_ = mesh_.time().timeIndex();

    // What each body was projected with
    const size_t n = bodies.size();
    projectedPose_.resize(n);
    projectedVelocity_.resize(n, vec3::Zero());
    projectedAngularVelocity_.resize(n, vec3::Zero());
    projectedBox_.resize(n);
    projections_.setSize(label(n), 0);
    for (const label bi : toProject)
    {
        const rigidBody& b = bodies[bi];
        projectedPose_[bi] = b.pose;
        projectedVelocity_[bi] = b.velocity;
        projectedAngularVelocity_[bi] = b.angularVelocity;
        projectedBox_[bi] = b.geometry->worldBox(b.pose);
        ++projections_[bi];
    }
    lastProjected_ = toProject.size();
    projectAll_ = false;

    seconds_ += timer.elapsedTime();
    return nCells;
}


void Foam::immersedBoundaryProjection::reportProjectedVolumes(const demSolver& dem) const
{
    Info<< " sum of lambda V / body volume:";
    forAll(projectedVolume_, i)
    {
        if (dem.isWall(i)) continue;
        const rigidBody& b = dem.bodies()[i];
        Info<< ' ' << word(b.name) << ' ' << projectedVolume_[i]/b.geometry->volume();
    }
    Info<< endl;
}


void Foam::immersedBoundaryProjection::projectIfMeshChanged(const demSolver& dem)
{
    if
    (
        bodyOf_.size() != mesh_.nCells()
     || (mesh_.topoChanging() && projectedTimeIndex_ != mesh_.time().timeIndex())
    )
    {
        // The cell numbering changed: reset every cell, not the ones the
        // last projection set
        bodyOf_.clear();
        const label n = project(dem);
        Info<< "immersedDEM: mesh changed, projected again on "
            << returnReduce(n, sumOp<label>()) << " cells;";
        reportProjectedVolumes(dem);
    }
}


Foam::scalar Foam::immersedBoundaryProjection::cellCoefficient
(
    const label celli,
    const scalar deltaT
) const
{
    if (!forcing_.sharp)
    {
        return immersedForcing::diffuseCoefficient
        (
            lambda_.primitiveField()[celli], deltaT, forcing_.penalty
        );
    }
    return immersedForcing::sharpCoefficient(wallK_[celli], deltaT, forcing_.penalty);
}


void Foam::immersedBoundaryProjection::setForcing
(
    const immersedBoundaryForcingSettings& s,
    const demSolver& dem
)
{
    const bool changed =
        s.sharp != forcing_.sharp || (s.sharp && s.nu != forcing_.nu);
    forcing_ = s;
    registered_ = true;
    if (changed && bodyOf_.size())
    {
        projectAll_ = true;
        project(dem);
    }
}


void Foam::immersedBoundaryProjection::projectSharp
(
    const rigidBody& b,
    const label bi,
    const labelList& candidates,
    const std::vector<::immersedDEM::narrowBand::value>& band
)
{
    const vectorField& C = mesh_.cellCentres();
    const scalarField& V = mesh_.V();
    const labelUList& own = mesh_.owner();
    const labelUList& nei = mesh_.neighbour();
    const cellList& cells = mesh_.cells();
    const surfaceScalarField& magSf = mesh_.magSf();
    const surfaceScalarField& deltaCoeffs = mesh_.nonOrthDeltaCoeffs();
    const label nInternal = mesh_.nInternalFaces();
    vectorField& Uib = Uib_.primitiveFieldRef();

    auto phiAt = [&](const point& p)
    {
        return b.geometry->signedDistance(b.pose, c(p));
    };
    // The band's values: exact near the surface; elsewhere of the right
    // sign and larger than the cell's reach (its farthest neighbour), so
    // such a cell outside meets no centre inside below, and such a cell
    // inside, as a neighbour, is never next to an outside cell that uses
    // its value (phiC - phiN <= |d| <= reach)
    // (in phiOf_, a field of the mesh's cells holding GREAT elsewhere,
    // reset below)
    if (phiOf_.size() != mesh_.nCells())
    {
        phiOf_.setSize(mesh_.nCells());
        phiOf_ = GREAT;
    }
    forAll(candidates, i)
    {
        phiOf_[candidates[i]] = band[i].phi;
    }

    // Centres across processor faces: this side's centre plus the
    // coupled delta (computed for a patch when one of its faces is met)
    const polyBoundaryMesh& patches = mesh_.boundaryMesh();
    PtrList<vectorField> patchDelta(patches.size());

    for (const label celli : candidates)
    {
        const scalar phiC = phiOf_[celli];
        const label owner = bodyOf_[celli];
        if (phiC <= 0)
        {
            // Inside: follows the body, unless another body has more of
            // the cell
            if (owner == bi)
            {
                wallK_[celli] = -1;
            }
            continue;
        }
        if (owner >= 0 && owner != bi) continue;

        // Over the faces to centre-inside neighbours: the discrete
        // Laplacian puts the no-slip value at the neighbour's centre, a
        // distance |d| away, where the wall is at theta |d|; the source
        // nu |Sf| deltaCoeff/V (1/theta - 1) (Uib - U) makes the cell's
        // shear that of the wall where it is
        // A signed distance changes no faster than the position, so a
        // neighbour centre nearer than phiC is outside: no query for it
        scalar K = 0;
        for (const label facei : cells[celli])
        {
            scalar phiN = 0;
            scalar coeff = 0;
            if (facei < nInternal)
            {
                const label n = own[facei] == celli ? nei[facei] : own[facei];
                if (phiC > mag(C[n] - C[celli])) continue;
                phiN = phiOf_[n] < GREAT ? phiOf_[n] : phiAt(C[n]);
                coeff = magSf[facei]*deltaCoeffs[facei];
            }
            else
            {
                const label patchi = patches.whichPatch(facei);
                if (!patches[patchi].coupled()) continue;
                const label pfi = facei - patches[patchi].start();
                if (!patchDelta.set(patchi))
                {
                    patchDelta.set(patchi, mesh_.boundary()[patchi].delta().ptr());
                }
                const vector& d = patchDelta[patchi][pfi];
                if (phiC > mag(d)) continue;
                phiN = phiAt(C[celli] + d);
                coeff =
                    magSf.boundaryField()[patchi][pfi]
                   *deltaCoeffs.boundaryField()[patchi][pfi];
            }
            if (phiN <= 0)
            {
                K += immersedForcing::wallShearCoefficient
                (
                    forcing_.nu, coeff, V[celli], phiC, phiN
                );
            }
        }
        if (K > 0)
        {
            if (owner < 0)
            {
                touched_.append(celli);
                bodyOf_[celli] = bi;
                Uib[celli] = v(b.pointVelocity(c(C[celli])));
            }
            wallK_[celli] = K;
        }
    }
    for (const label celli : candidates)
    {
        phiOf_[celli] = GREAT;
    }
}


Foam::tmp<Foam::scalarField>
Foam::immersedBoundaryProjection::forcingCoefficient(scalar deltaT) const
{
    tmp<scalarField> tK(new scalarField(lambda_.size(), Zero));
    scalarField& K = tK.ref();
    for (const label celli : touched_)
    {
        K[celli] = cellCoefficient(celli, deltaT);
    }
    return tK;
}


Foam::scalar Foam::immersedBoundaryProjection::takeSeconds()
{
    const scalar s = seconds_;
    seconds_ = 0;
    return s;
}
