#include "immersedBoundaryProjection.H"
#include "coreConversion.H"
#include "parallelSum.H"
#include "boxFraction.H"
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

    const pointField& points = mesh_.points();
    const vectorField& C = mesh_.cellCentres();

    // The cells whose bounding boxes meet a box. On a mesh that has just
    // changed its topology (dynamicRefineFvMesh, every step or so)
    // OpenFOAM's cell tree would be built again for the whole mesh first:
    // seconds for a million cells. One pass over the cells' bounding
    // boxes costs a small fraction of that, so it is used then; a static
    // mesh keeps its tree and the cost follows the bodies.
    const bool scan = mesh_.topoChanging();
    List<treeBoundBox> cellBoxes;
    if (scan)
    {
        const cellList& cells = mesh_.cells();
        const faceList& faces = mesh_.faces();
        cellBoxes.setSize(mesh_.nCells());
        forAll(cells, celli)
        {
            treeBoundBox& b = cellBoxes[celli];
            b = treeBoundBox(point::uniform(GREAT), point::uniform(-GREAT));
            for (const label facei : cells[celli])
            {
                for (const label pi : faces[facei])
                {
                    b.min() = min(b.min(), points[pi]);
                    b.max() = max(b.max(), points[pi]);
                }
            }
        }
    }
    auto cellsIn = [&](const treeBoundBox& bb)
    {
        if (!scan)
        {
            const indexedOctree<treeDataCell>& tree = mesh_.cellTree();
            const labelList hits(tree.findBox(bb));
            labelList found(hits.size());
            forAll(hits, i)
            {
                found[i] = tree.shapes().cellLabels()[hits[i]];
            }
            return found;
        }
        DynamicList<label> found;
        forAll(cellBoxes, celli)
        {
            if (cellBoxes[celli].overlaps(bb)) found.append(celli);
        }
        return labelList(std::move(found));
    };
    // The cell's bounding box stands in for the cell (exact for the
    // axis-aligned hexahedra of blockMesh and snappyHexMesh)
    auto cellBox = [&](const label celli, vec3& lo, vec3& hi)
    {
        if (scan)
        {
            lo = c(cellBoxes[celli].min());
            hi = c(cellBoxes[celli].max());
            return;
        }
        lo = vec3::Constant(GREAT);
        hi = vec3::Constant(-GREAT);
        for (const label pi : mesh_.cellPoints()[celli])
        {
            const vec3 p = c(points[pi]);
            lo = lo.cwiseMin(p);
            hi = hi.cwiseMax(p);
        }
    };

    projectedVolume_.setSize(bodies.size());
    projectedVolume_ = Zero;
    for (const label bi : toProject)
    {
        const rigidBody& b = bodies[bi];
        const axisAlignedBox wb = b.geometry->worldBox(b.pose);
        const treeBoundBox bb(v(wb.min), v(wb.max));
        for (const label celli : cellsIn(bb))
        {
            vec3 lo, hi;
            cellBox(celli, lo, hi);
            const scalar f = boxFraction::of(*b.geometry, b.pose, lo, hi, 1);
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
        const vector grow(vector::uniform(largestCellSize_));
        for (const label bi : toProject)
        {
            const axisAlignedBox wb = bodies[bi].geometry->worldBox(bodies[bi].pose);
            projectSharp
            (
                bodies[bi], label(bi),
                cellsIn(treeBoundBox(v(wb.min) - grow, v(wb.max) + grow))
            );
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
    const labelList& candidates
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
    Map<scalar> phi(2*candidates.size());
    for (const label celli : candidates)
    {
        phi.insert(celli, phiAt(C[celli]));
    }

    // Centres across processor faces: this side's centre plus the
    // coupled delta (computed for a patch when one of its faces is met)
    const polyBoundaryMesh& patches = mesh_.boundaryMesh();
    PtrList<vectorField> patchDelta(patches.size());

    for (const label celli : candidates)
    {
        const scalar phiC = phi[celli];
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
                const auto iter = phi.cfind(n);
                phiN = iter.found() ? *iter : phiAt(C[n]);
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
