#include "immersedBoundaryProjection.H"
#include "coreConversion.H"
#include "parallelSum.H"
#include "boxFraction.H"
#include "convexCells.H"
#include "treeBoundBox.H"
#include "clockTime.H"

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
        shiftOf_.clear();
        secondShiftOf_.clear();
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
        if (dem.periodic().active())
        {
            // Periodic: every body every step (its images come and go)
            all = true;
            toProject.clear();
            velocityOnly.clear();
        }
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
            if (shiftOf_.size())
            {
                shiftOf_[celli] = Zero;
                secondShiftOf_[celli] = Zero;
            }
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
    // Each body's images that meet the mesh: itself, and in a periodic
    // domain its copies a period away where it is cut by a periodic
    // boundary (periodicBox::imageShifts). An image is projected as the
    // body at its pose moved by the shift; its cells keep the shift
    // (bodyShift), so that the body's velocity there and its fluid
    // moments are those of the image. Band slots: the body's own index for
    // itself, others past the bodies (queried afresh: no earlier pose)
    const periodicBox& periodic = dem.periodic();
    struct image
    {
        label k;
        vec3 shift;
        label slot;
    };
    std::vector<image> images;
    forAll(toProject, k)
    {
        const label bi = toProject[k];
        if (!periodic.active())
        {
            images.push_back({k, vec3::Zero(), bi});
            continue;
        }
        const axisAlignedBox wb = bodies[bi].geometry->worldBox(gp[bi]);
        const vec3 g = c(grow);
        const auto shifts = periodic.imageShifts(axisAlignedBox(wb.min - g, wb.max + g));
        forAll(shifts, m)
        {
            const bool self = shifts[m].isZero();
            images.push_back
            (
                {k, shifts[m], self ? bi : label((m + 1)*bodies.size() + bi)}
            );
        }
    }
    if (periodic.active() && shiftOf_.size() != mesh_.nCells())
    {
        shiftOf_.setSize(mesh_.nCells(), Zero);
        secondShiftOf_.setSize(mesh_.nCells(), Zero);
    }
    const bool shifted = periodic.active();

    std::vector<labelList> candidates(images.size());
    std::vector<std::vector<narrowBand::value>> band(images.size());
    std::vector<bodyPose> imagePose(images.size());
    projectedVolume_.setSize(bodies.size());
    projectedVolume_ = Zero;
    const scalarField& reach = cells_.reach();
    for (size_t ii = 0; ii < images.size(); ++ii)
    {
        const label bi = toProject[images[ii].k];
        const vec3& s = images[ii].shift;
        const label slot = images[ii].slot;
        const rigidBody& b = bodies[bi];
        bodyPose& pose = imagePose[ii];
        pose = gp[bi];
        if (slot != bi) pose.setPosition(pose.position() + s);
        const axisAlignedBox wb = b.geometry->worldBox(pose);
        candidates[ii] = cells_.candidatesOf
        (
            b, slot, treeBoundBox(v(wb.min) - grow, v(wb.max) + grow),
            0.5*largestCellSize_, debug || slot != bi
        );
        const labelList& cand = candidates[ii];

        // Convex bodies by their planes, the others (bodies of convex
        // pieces too) by the narrow band
        std::unique_ptr<convexCells> planes;
        if (convexCells::handles(*b.geometry, false))
        {
            planes.reset(new convexCells(*b.geometry, pose));
            band[ii].resize(cand.size());
            forAll(cand, i)
            {
                band[ii][i] = planes->classify(c(C[cand[i]]), reach[cand[i]]);
            }
        }
        else
        {
            band[ii] = cells_.bandOf
            (
                b, slot, cand, pose,
                !debug && slot == bi && hasProjectedPose(bi) ? &projectedPose_[bi] : nullptr
            );
        }

        const treeBoundBox bb(v(wb.min), v(wb.max));
        forAll(cand, i)
        {
            const label celli = cand[i];
            if (!cellBoxes[celli].overlaps(bb)) continue;
            const narrowBand::value& d = band[ii][i];
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
                    if (shifted) secondShiftOf_[celli] = shiftOf_[celli];
                }
                lambda[celli] = f;
                bodyOf_[celli] = label(bi);
                if (shifted) shiftOf_[celli] = v(s);
                Uib[celli] = v(b.pointVelocity(c(C[celli]) - s));
            }
            else if (f > secondLambda_[celli])
            {
                secondOf_[celli] = label(bi);
                secondLambda_[celli] = f;
                if (shifted) secondShiftOf_[celli] = v(s);
            }
        }
    }
    if (forcing_.sharp)
    {
        for (size_t ii = 0; ii < images.size(); ++ii)
        {
            const label bi = toProject[images[ii].k];
            projectSharp
            (
                bodies[bi], bi, imagePose[ii], images[ii].shift,
                candidates[ii], band[ii]
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


Foam::scalar Foam::immersedBoundaryProjection::takeSeconds()
{
    const scalar s = seconds_;
    seconds_ = 0;
    return s;
}
