#include "immersedBoundaryProjection.H"
#include "coreConversion.H"
#include "parallelSum.H"
#include "boxFraction.H"
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
    cells_(mesh),
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
        cells_.clear();
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
    cells_.update();
    const List<treeBoundBox>& cellBoxes = cells_.cellBoxes();
    auto cellBox = [&](const label celli, vec3& lo, vec3& hi)
    {
        lo = c(cellBoxes[celli].min());
        hi = c(cellBoxes[celli].max());
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
        candidates[k] = cells_.candidatesOf
        (
            b, bi, treeBoundBox(v(wb.min) - grow, v(wb.max) + grow),
            0.5*largestCellSize_, debug
        );
        const labelList& cand = candidates[k];
        band[k] = cells_.bandOf
        (
            b, bi, cand,
            !debug && size_t(bi) < projectedPose_.size() ? &projectedPose_[bi] : nullptr
        );

        const treeBoundBox bb(v(wb.min), v(wb.max));
        forAll(cand, i)
        {
            const label celli = cand[i];
            if (!cellBoxes[celli].overlaps(bb)) continue;
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
            for (const label celli : cells_.cellsIn(treeBoundBox(v(lo), v(hi))))
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
