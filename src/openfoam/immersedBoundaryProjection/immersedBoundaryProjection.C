#include "immersedBoundaryProjection.H"
#include "coreConversion.H"
#include "parallelSum.H"
#include "boxFraction.H"
#include "convexCells.H"
#include "pairFilter.H"
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

        // The smallest cell, rounded down to a power of two: the same on
        // every processor and for the decomposed mesh as for the whole,
        // whatever the round-off of the cell volumes
        scalar hMin = GREAT;
        for (const scalar Vc : mesh_.V()) hMin = min(hMin, cbrt(Vc));
        hMin = returnReduce(hMin, minOp<scalar>());
        restDistance_ = restFraction*std::exp2(std::floor(std::log2(hMin)));
    }
    return largestCellSize_;
}



bool Foam::immersedBoundaryProjection::hasProjectedPose(const label bi) const
{
    return size_t(bi) < projectedGeometry_.size() && projectedGeometry_[bi];
}


void Foam::immersedBoundaryProjection::restoreProjectedPose
(
    const demSolver& dem,
    const label bi,
    const bodyPose& pose
)
{
    const size_t n = dem.bodies().size();
    projectedPose_.resize(n);
    projectedGeometry_.resize(n, nullptr);
    projectedName_.resize(n);
    projectedBox_.resize(n);
    const rigidBody& b = dem.bodies()[bi];
    projectedPose_[bi] = pose;
    projectedGeometry_[bi] = b.geometry.get();
    projectedName_[bi] = b.name;
    projectedBox_[bi] = b.geometry->worldBox(pose);
}


immersedDEM::bodyPose Foam::immersedBoundaryProjection::geometryPose
(
    const demSolver& dem,
    const size_t bi
) const
{
    const rigidBody& b = dem.bodies()[bi];
    if
    (
        projectedGeometry_.size() != dem.bodies().size()
     || projectedGeometry_[bi] != b.geometry.get()
     || projectedName_[bi] != b.name
     || !(restDistance_ > 0)
    )
    {
        return b.pose;
    }
    const bodyPose& p = projectedPose_[bi];
    const scalar moved =
        pairFilter::motionBound(p, b.pose, b.geometry->boundingRadius());
    return moved <= restDistance_ ? p : b.pose;
}


Foam::labelList Foam::immersedBoundaryProjection::bodiesToProject
(
    const demSolver& dem,
    const std::vector<bodyPose>& gp,
    bool& all,
    labelList& velocityOnly
) const
{
    const auto& bodies = dem.bodies();
    const size_t n = bodies.size();
    velocityOnly.clear();
    all =
        projectAll_ || debug || mesh_.dynamic() || mesh_.moving()
     || projectedPose_.size() != n || uibPose_.size() != n;
    if (all) return labelList();

    // Moved since their last projection: a geometry pose other than the
    // last one (the surface moved farther than restDistance); moved within
    // it, or changed their velocities: Uib only
    auto same = [](const bodyPose& a, const bodyPose& b)
    {
        return
            a.position() == b.position()
         && a.orientation().coeffs() == b.orientation().coeffs();
    };
    std::vector<bool> in(n, false);
    DynamicList<label> set;
    DynamicList<label> velocities;
    for (size_t bi = 0; bi < n; ++bi)
    {
        if (dem.isWall(int(bi))) continue;
        const rigidBody& b = bodies[bi];
        if (!same(gp[bi], projectedPose_[bi]))
        {
            in[bi] = true;
            set.append(label(bi));
        }
        else if
        (
            !same(b.pose, uibPose_[bi])
         || b.velocity != uibVelocity_[bi]
         || b.angularVelocity != uibAngularVelocity_[bi]
        )
        {
            velocities.append(label(bi));
        }
    }

    // Their cells (lambda > 0, and the sharp surface's ring) lie in their
    // world boxes grown by a cell; a body whose box, grown alike, comes
    // within a cell of theirs (before or after the move) may share cells
    // with them (the larger fraction wins, the first ring claims): it is
    // projected again too (at its geometry pose), and so on. Then the
    // bodies not projected own cells no projected body can reach, and the
    // result is that of projecting every body
    const scalar g = 2*largestCellSize_;
    std::vector<axisAlignedBox> now(n);
    for (size_t bi = 0; bi < n && set.size(); ++bi)
    {
        if (dem.isWall(int(bi))) continue;
        now[bi] = bodies[bi].geometry->worldBox(gp[bi]).inflated(g);
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
    for (const label bi : velocities)
    {
        if (!in[bi]) velocityOnly.append(bi);
    }
    if (set.empty()) return labelList();
    label nBodies = 0;
    for (size_t bi = 0; bi < n; ++bi)
    {
        if (!dem.isWall(int(bi))) ++nBodies;
    }
    if (set.size() == nBodies)
    {
        all = true;
        velocityOnly.clear();
        return labelList();
    }
    Foam::sort(set);
    return labelList(std::move(set));
}


void Foam::immersedBoundaryProjection::setVelocities
(
    const demSolver& dem,
    const std::vector<bool>& velocityOnly
)
{
    // The cells a body owns (lambda, and the sharp surface's ring) take
    // its rigid velocity there now, as a projection would
    vectorField& Uib = Uib_.primitiveFieldRef();
    const vectorField& C = mesh_.cellCentres();
    for (const label celli : touched_)
    {
        const label bi = bodyOf_[celli];
        if (bi >= 0 && velocityOnly[bi])
        {
            Uib[celli] = v(dem.bodies()[bi].pointVelocity(c(C[celli])));
        }
    }
    for (size_t bi = 0; bi < velocityOnly.size(); ++bi)
    {
        if (!velocityOnly[bi]) continue;
        const rigidBody& b = dem.bodies()[bi];
        uibPose_[bi] = b.pose;
        uibVelocity_[bi] = b.velocity;
        uibAngularVelocity_[bi] = b.angularVelocity;
    }
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
    labelList velocityOnly;
    std::vector<bodyPose> gp;
    auto geometryPoses = [&]()
    {
        gp.resize(bodies.size());
        for (size_t bi = 0; bi < bodies.size(); ++bi)
        {
            if (!dem.isWall(int(bi))) gp[bi] = geometryPose(dem, bi);
        }
    };
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
        largestCellSize();
        geometryPoses();
    }
    else
    {
        largestCellSize();
        geometryPoses();
        toProject = bodiesToProject(dem, gp, all, velocityOnly);
        if (velocityOnly.size())
        {
            std::vector<bool> only(bodies.size(), false);
            for (const label bi : velocityOnly) only[bi] = true;
            setVelocities(dem, only);
        }
        if (!all && toProject.empty())
        {
            // Nothing moved beyond restDistance: the cells stay as they
            // are (Uib set again where velocities changed)
            if (velocityOnly.size()) Uib_.correctBoundaryConditions();
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
    const scalarField& reach = cells_.reach();
    forAll(toProject, k)
    {
        const label bi = toProject[k];
        const rigidBody& b = bodies[bi];
        const bodyPose& pose = gp[bi];
        const axisAlignedBox wb = b.geometry->worldBox(pose);
        candidates[k] = cells_.candidatesOf
        (
            b, bi, treeBoundBox(v(wb.min) - grow, v(wb.max) + grow),
            0.5*largestCellSize_, debug
        );
        const labelList& cand = candidates[k];

        // Convex bodies by their planes, the others (bodies of convex
        // pieces too) by the narrow band
        std::unique_ptr<convexCells> planes;
        if (convexCells::handles(*b.geometry, false))
        {
            planes.reset(new convexCells(*b.geometry, pose));
            band[k].resize(cand.size());
            forAll(cand, i)
            {
                band[k][i] = planes->classify(c(C[cand[i]]), reach[cand[i]]);
            }
        }
        else
        {
            band[k] = cells_.bandOf
            (
                b, bi, cand, pose,
                !debug && hasProjectedPose(bi) ? &projectedPose_[bi] : nullptr
            );
        }

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
                // the band is wholly inside or outside. A cut cell: its
                // box clipped by the planes; or the surface's second-order
                // model at the centre's closest point, or eight pieces'
                // planes where a crease passes
                vec3 lo, hi;
                cellBox(celli, lo, hi);
                f = planes
                    ? planes->fraction(lo, hi)
                    : boxFraction::fromQuery(*b.geometry, pose, lo, hi, c(C[celli]), d.sp);
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
            projectSharp(bodies[toProject[k]], toProject[k], gp[toProject[k]], candidates[k], band[k]);
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

    // What each body was projected with: its geometry pose, and its pose
    // and velocities for Uib
    const size_t n = bodies.size();
    projectedPose_.resize(n);
    projectedGeometry_.resize(n, nullptr);
    projectedName_.resize(n);
    projectedBox_.resize(n);
    uibPose_.resize(n);
    uibVelocity_.resize(n, vec3::Zero());
    uibAngularVelocity_.resize(n, vec3::Zero());
    projections_.setSize(label(n), 0);
    for (const label bi : toProject)
    {
        const rigidBody& b = bodies[bi];
        projectedPose_[bi] = gp[bi];
        projectedGeometry_[bi] = b.geometry.get();
        projectedName_[bi] = b.name;
        projectedBox_[bi] = b.geometry->worldBox(gp[bi]);
        uibPose_[bi] = b.pose;
        uibVelocity_[bi] = b.velocity;
        uibAngularVelocity_[bi] = b.angularVelocity;
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
    const bodyPose& pose,
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
    const scalarField& reach = cells_.reach();
    vectorField& Uib = Uib_.primitiveFieldRef();

    auto phiAt = [&](const point& p)
    {
        return b.geometry->signedDistance(pose, c(p));
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
        // Beyond its reach (its farthest neighbour centre, processor
        // neighbours too) no neighbour centre is inside
        if (phiC > reach[celli]) continue;

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
