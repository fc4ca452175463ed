#include "immersedDEMState.H"
#include "immersedDEMReader.H"
#include "uniformDimensionedFields.H"
#include "boxFraction.H"
#include "indexedOctree.H"
#include "treeDataCell.H"
#include "treeBoundBox.H"
#include "OFstream.H"
#include "IFstream.H"
#include "OSspecific.H"
#include "clockTime.H"
#include "surfaceFields.H"

using namespace immersedDEM;

namespace Foam
{
    defineTypeNameAndDebug(immersedDEMState, 0);
}


namespace
{

using Foam::vector;
using Foam::word;

Foam::vector v(const vec3& x)
{
    return Foam::immersedDEMReader::toFoam(x);
}

vec3 c(const Foam::vector& x)
{
    return Foam::immersedDEMReader::toCore(x);
}

} // End anonymous namespace


Foam::immersedDEMState::immersedDEMState(const fvMesh& mesh)
:
    regIOobject
    (
        IOobject
        (
            typeName,
            mesh.time().constant(),
            mesh,
            IOobject::NO_READ,
            IOobject::NO_WRITE
        )
    ),
    mesh_(mesh),
    properties_
    (
        IOobject
        (
            "immersedDEMProperties",
            mesh.time().constant(),
            mesh,
            IOobject::MUST_READ,
            IOobject::NO_WRITE
        )
    ),
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
    // Gravity from constant/g when the case has one
    const uniformDimensionedVectorField g
    (
        IOobject
        (
            "g", mesh.time().constant(), mesh,
            IOobject::READ_IF_PRESENT, IOobject::NO_WRITE, false
        ),
        dimensionedVector(dimAcceleration, Zero)
    );
    Info<< "immersedDEM: reading " << properties_.objectPath() << endl;
    dem_ = immersedDEMReader::read
    (
        properties_, mesh.time().globalPath()/mesh.time().constant()/"triSurface", g.value(), &mesh
    );
    dem_->setTime(mesh.time().value());
    Info<< "immersedDEM: " << nBodies() << " bodies, "
        << dem_->materials().size() << " materials" << endl;

    const label n = dem_->bodies().size();
    innerMomentum_.setSize(n, Zero);
    innerAngularMomentum_.setSize(n, Zero);
    previousVelocity_.setSize(n, Zero);
    previousAngularVelocity_.setSize(n, Zero);
    for (label i = 0; i < n; ++i)
    {
        previousVelocity_[i] = v(dem_->bodies()[i].velocity);
        previousAngularVelocity_[i] = v(dem_->bodies()[i].angularVelocity);
    }

    restarted_ = readRestart();

    const label nCells = project();
    Info<< "immersedDEM: projected on " << returnReduce(nCells, sumOp<label>())
        << " cells;";
    reportProjectedVolumes();
    Info<< endl;
    forAll(projectedVolume_, i)
    {
        const rigidBody& b = dem_->bodies()[i];
        if (!dem_->isWall(i) && projectedVolume_[i] < 0.5*b.geometry->volume())
        {
            WarningInFunction
                << "Body '" << b.name << "' of " << properties_.objectPath()
                << " lies mostly outside the mesh (projected "
                << projectedVolume_[i]/b.geometry->volume()
                << " of its volume): the fluid does not see it there" << endl;
        }
    }

    innerMomentumSet_ = restarted_;
}


void Foam::immersedDEMState::setInnerMomentum(const volVectorField& U)
{
    if (innerMomentumSet_)
    {
        return;
    }
    // The fluid inside the bodies as it is before the first step: if it
    // is at rest while a body starts moving, the first step's forcing sets
    // it in motion, and the inner term must cancel that part of the
    // forcing's reaction (it is the body's own volume, not the fluid
    // around it, being accelerated)
    List<vector> P, PM;
    fluidSums(U, 0, P, PM, innerMomentum_, innerAngularMomentum_);
    innerMomentumSet_ = true;
}


Foam::immersedDEMState::~immersedDEMState() = default;


Foam::label Foam::immersedDEMState::project()
{
    const clockTime timer;

    scalarField& lambda = lambda_.primitiveFieldRef();
    vectorField& Uib = Uib_.primitiveFieldRef();
    scalarField& zone = contactZone_.primitiveFieldRef();
    if (bodyOf_.size() != mesh_.nCells())
    {
        // New mesh (start, topology change): everything
        lambda = 0;
        Uib = Zero;
        zone = 0;
        bodyOf_.setSize(mesh_.nCells());
        bodyOf_ = -1;
        wallK_.setSize(mesh_.nCells());
        wallK_ = 0;
        largestCellSize_ = 0;
    }
    else
    {
        // Only the cells the last projection set: the cost follows the
        // bodies, not the mesh
        for (const label celli : touched_)
        {
            lambda[celli] = 0;
            Uib[celli] = Zero;
            zone[celli] = 0;
            bodyOf_[celli] = -1;
            wallK_[celli] = 0;
        }
    }
    touched_.clear();

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

    label nCells = 0;
    const auto& bodies = dem_->bodies();
    projectedVolume_.setSize(bodies.size());
    projectedVolume_ = Zero;
    const scalarField& V = mesh_.V();
    for (size_t bi = 0; bi < bodies.size(); ++bi)
    {
        if (dem_->isWall(int(bi))) continue;
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
                if (lambda[celli] == 0) ++nCells;
                if (bodyOf_[celli] < 0) touched_.append(celli);
                lambda[celli] = f;
                bodyOf_[celli] = label(bi);
                Uib[celli] = v(b.pointVelocity(c(C[celli])));
            }
        }
    }
    if (sharp_)
    {
        if (!(largestCellSize_ > 0))
        {
            // The ring of fluid cells next to a body's centre-inside cells
            // lies within one cell of its box
            scalar h = 0;
            for (const scalar Vc : V) h = max(h, cbrt(Vc));
            largestCellSize_ = returnReduce(h, maxOp<scalar>());
            // Split and graded hexahedra are not cubes
            largestCellSize_ *= 2;
        }
        const vector grow(vector::uniform(largestCellSize_));
        for (size_t bi = 0; bi < bodies.size(); ++bi)
        {
            if (dem_->isWall(int(bi))) continue;
            const axisAlignedBox wb = bodies[bi].geometry->worldBox(bodies[bi].pose);
            projectSharp
            (
                label(bi), cellsIn(treeBoundBox(v(wb.min) - grow, v(wb.max) + grow))
            );
        }
    }
    for (const label celli : touched_)
    {
        projectedVolume_[bodyOf_[celli]] += lambda[celli]*V[celli];
    }

    // The contact zone is a refinement field: only a dynamic mesh reads it,
    // and the pairs loop is quadratic in the bodies
    for (size_t i = 0; mesh_.dynamic() && i < bodies.size(); ++i)
    {
        if (dem_->isWall(int(i))) continue;
        for (size_t j = i + 1; j < bodies.size(); ++j)
        {
            if (dem_->isWall(int(j))) continue;
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
    Pstream::listCombineGather(projectedVolume_, plusEqOp<scalar>());
    Pstream::listCombineScatter(projectedVolume_);
    lambda_.correctBoundaryConditions();
    Uib_.correctBoundaryConditions();
    projectedTimeIndex_ = mesh_.time().timeIndex();
    projectionSeconds_ += timer.elapsedTime();
    return nCells;
}


void Foam::immersedDEMState::reportProjectedVolumes() const
{
    Info<< " sum of lambda V / body volume:";
    forAll(projectedVolume_, i)
    {
        if (dem_->isWall(i)) continue;
        const rigidBody& b = dem_->bodies()[i];
        Info<< ' ' << word(b.name) << ' ' << projectedVolume_[i]/b.geometry->volume();
    }
    Info<< endl;
}


void Foam::immersedDEMState::projectIfMeshChanged()
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
        const label n = project();
        Info<< "immersedDEM: mesh changed, projected again on "
            << returnReduce(n, sumOp<label>()) << " cells;";
        reportProjectedVolumes();
    }
}


Foam::scalar Foam::immersedDEMState::coefficient(scalar l, scalar deltaT) const
{
    if (!(l > 0) || !(deltaT > 0)) return 0;
    const scalar aMax = penaltyCap();
    return (l*(1 + aMax) >= aMax ? aMax : l/(1 - l))/deltaT;
}


Foam::scalar Foam::immersedDEMState::cellCoefficient
(
    const label celli,
    const scalar deltaT
) const
{
    if (!sharp_)
    {
        return coefficient(lambda_.primitiveField()[celli], deltaT);
    }
    if (!(deltaT > 0)) return 0;
    const scalar KMax = penaltyCap()/deltaT;
    return wallK_[celli] < 0 ? KMax : min(wallK_[celli], KMax);
}


void Foam::immersedDEMState::setSurface(const bool sharp, const scalar nu)
{
    const bool changed = sharp != sharp_ || (sharp && nu != nu_);
    sharp_ = sharp;
    nu_ = nu;
    if (changed && bodyOf_.size())
    {
        project();
    }
}


void Foam::immersedDEMState::projectSharp
(
    const label bi,
    const labelList& candidates
)
{
    const rigidBody& b = dem_->bodies()[bi];
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
                const scalar theta = phiC/(phiC - phiN);
                K += nu_*coeff/V[celli]*(1 - theta)/theta;
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
Foam::immersedDEMState::forcingCoefficient(scalar deltaT) const
{
    tmp<scalarField> tK(new scalarField(lambda_.size(), Zero));
    scalarField& K = tK.ref();
    for (const label celli : touched_)
    {
        K[celli] = cellCoefficient(celli, deltaT);
    }
    return tK;
}


void Foam::immersedDEMState::fluidSums
(
    const volVectorField& U,
    const scalar deltaT,
    List<vector>& penalty,
    List<vector>& penaltyMoment,
    List<vector>& momentum,
    List<vector>& angularMomentum
) const
{
    const label n = dem_->bodies().size();
    for (List<vector>* l : {&penalty, &penaltyMoment, &momentum, &angularMomentum})
    {
        l->setSize(n);
        *l = Zero;
    }
    const scalarField& V = mesh_.V();
    const vectorField& C = mesh_.cellCentres();
    const scalarField& lambda = lambda_.primitiveField();
    const vectorField& Uib = Uib_.primitiveField();
    for (const label celli : touched_)
    {
        const label i = bodyOf_[celli];
        if (i < 0) continue;
        const scalar w = lambda[celli]*V[celli];
        const vector r = C[celli] - v(dem_->bodies()[i].pose.position());
        const vector d =
            cellCoefficient(celli, deltaT)*V[celli]*(U[celli] - Uib[celli]);
        const vector m = w*U[celli];
        penalty[i] += d;
        penaltyMoment[i] += r ^ d;
        momentum[i] += m;
        angularMomentum[i] += r ^ m;
    }
    // Summed on the master, the sums sent back: every rank holds the same
    // bits, so the replicated DEMs stay identical
    for (List<vector>* l : {&penalty, &penaltyMoment, &momentum, &angularMomentum})
    {
        Pstream::listCombineGather(*l, plusEqOp<vector>());
        Pstream::listCombineScatter(*l);
    }
}


void Foam::immersedDEMState::fluidLoads
(
    const volVectorField& U,
    scalar rho,
    scalar deltaT,
    scalar Ca
)
{
    const clockTime timer;
    setInnerMomentum(U);
    List<vector> P, PM, M, L;
    fluidSums(U, deltaT, P, PM, M, L);
    const vector g = v(dem_->settings().gravity);
    auto& bodies = dem_->bodies();
    forAll(M, i)
    {
        if (dem_->isWall(i)) continue;
        rigidBody& b = bodies[i];
        const scalar Vb = b.geometry->volume();
        const vector F =
            rho*(P[i] + (M[i] - innerMomentum_[i])/deltaT) - rho*Vb*g;
        const vector T =
            rho*(PM[i] + (L[i] - innerAngularMomentum_[i])/deltaT);
        const scalar ma = Ca*rho*Vb;
        const vector vn = v(b.velocity);
        b.fluidForce = c(F);
        b.fluidDamping = ma/deltaT;
        b.fluidReferenceVelocity = b.velocity;
        b.fluidReferenceAcceleration = c((vn - previousVelocity_[i])/deltaT);
        b.fluidReferenceTime = dem_->time();
        b.fluidTorque = c(T);
        const vector wn = v(b.angularVelocity);
        b.fluidAngularDamping =
            Ca*rho/b.density*b.inertia().sum()/3/deltaT;
        b.fluidReferenceAngularVelocity = b.angularVelocity;
        b.fluidReferenceAngularAcceleration =
            c((wn - previousAngularVelocity_[i])/deltaT);
        previousVelocity_[i] = vn;
        previousAngularVelocity_[i] = wn;
        innerMomentum_[i] = M[i];
        innerAngularMomentum_[i] = L[i];
    }
    forcingSeconds_ += timer.elapsedTime();
}


void Foam::immersedDEMState::takeTimings(scalar& projection, scalar& forcing)
{
    projection = projectionSeconds_;
    forcing = forcingSeconds_;
    projectionSeconds_ = 0;
    forcingSeconds_ = 0;
}


Foam::fileName Foam::immersedDEMState::restartFile(const fileName& timePath) const
{
    return timePath/"uniform"/"immersedDEM"/"state";
}


void Foam::immersedDEMState::writeRestart(const fileName& timePath) const
{
    const fileName file = restartFile(timePath);
    mkDir(file.path());
    const fileName tmp = file + ".tmp";
    {
        OFstream os(tmp);
        os.precision(17);
        os  << "// immersedDEM restart state: body states, fluid momenta inside"
            << " the bodies and contact histories" << nl << nl;
        os.writeEntry("time", dem_->time());
        os  << nl << "bodies" << nl << token::BEGIN_BLOCK << incrIndent << nl;
        forAll(dem_->bodies(), i)
        {
            const rigidBody& b = dem_->bodies()[i];
            const quat& q = b.pose.orientation();
            os.beginBlock(word(b.name));
            os.writeEntry("position", v(b.pose.position()));
            os.writeEntry("orientation", List<scalar>({q.w(), q.x(), q.y(), q.z()}));
            os.writeEntry("velocity", v(b.velocity));
            os.writeEntry("angularVelocity", v(b.angularVelocity));
            os.writeEntry("fluidForce", v(b.fluidForce));
            os.writeEntry("fluidTorque", v(b.fluidTorque));
            os.writeEntry("fluidDamping", b.fluidDamping);
            os.writeEntry("fluidReferenceVelocity", v(b.fluidReferenceVelocity));
            os.writeEntry("fluidReferenceAcceleration", v(b.fluidReferenceAcceleration));
            os.writeEntry("fluidReferenceTime", b.fluidReferenceTime);
            os.writeEntry("previousVelocity", previousVelocity_[i]);
            os.writeEntry("fluidAngularDamping", b.fluidAngularDamping);
            os.writeEntry("fluidReferenceAngularVelocity", v(b.fluidReferenceAngularVelocity));
            os.writeEntry("fluidReferenceAngularAcceleration", v(b.fluidReferenceAngularAcceleration));
            os.writeEntry("previousAngularVelocity", previousAngularVelocity_[i]);
            os.writeEntry("innerMomentum", innerMomentum_[i]);
            os.writeEntry("innerAngularMomentum", innerAngularMomentum_[i]);
            os.endBlock();
        }
        os  << decrIndent << token::END_BLOCK << nl << nl;
        os  << "contacts" << nl << token::BEGIN_BLOCK << incrIndent << nl;
        label k = 0;
        for (const auto& pair : dem_->histories())
        {
            for (const contactHistory& h : pair.second)
            {
                os.beginBlock(word("contact" + Foam::name(k++)));
                os.writeEntry("bodyA", word(dem_->bodies()[pair.first.first].name));
                os.writeEntry("bodyB", word(dem_->bodies()[pair.first.second].name));
                os.writeEntry("tangentialSpring", v(h.tangentialSpring));
                os.writeEntry("normal", v(h.normal));
                os.writeEntry("point", v(h.point));
                os.writeEntry("approach", h.approach);
                os.writeEntry("maxNormalForce", h.maxNormalForce);
                os.endBlock();
            }
        }
        os  << decrIndent << token::END_BLOCK << nl;
        if (!os.good())
        {
            FatalErrorInFunction
                << "Could not write " << tmp << exit(FatalError);
        }
    }
    if (!Foam::mv(tmp, file))
    {
        FatalErrorInFunction
            << "Could not rename " << tmp << " to " << file << exit(FatalError);
    }
}


bool Foam::immersedDEMState::readRestart()
{
    const fileName file = restartFile(mesh_.time().timePath());
    if (!isFile(file))
    {
        return false;
    }
    Info<< "immersedDEM: restarting from " << file << endl;
    IFstream is(file);
    const dictionary dict(is);

    auto& bodies = dem_->bodies();
    std::map<std::string, int> index;
    forAll(bodies, i)
    {
        index[bodies[i].name] = i;
    }
    auto bodyIndex = [&](const dictionary& d, const word& key)
    {
        const word name = d.get<word>(key);
        const auto it = index.find(name);
        if (it == index.end())
        {
            FatalIOErrorInFunction(d)
                << "Keyword '" << key << "' in " << d.name() << ": no body or wall '"
                << name << "' in " << properties_.objectPath() << nl
                << exit(FatalIOError);
        }
        return it->second;
    };

    const dictionary& bd = dict.subDict("bodies");
    forAll(bodies, i)
    {
        rigidBody& b = bodies[i];
        const dictionary* dp = bd.findDict(b.name);
        if (!dp)
        {
            FatalIOErrorInFunction(bd)
                << "No state for body '" << b.name << "' in " << file
                << ": the bodies of " << properties_.objectPath()
                << " must be those of the run that wrote it" << nl
                << exit(FatalIOError);
        }
        const dictionary& d = *dp;
        const List<scalar> q(d.get<List<scalar>>("orientation"));
        if (q.size() != 4)
        {
            FatalIOErrorInFunction(d)
                << "Keyword 'orientation' in " << d.name()
                << " must be a quaternion (w x y z)" << nl << exit(FatalIOError);
        }
        b.pose = bodyPose(c(d.get<vector>("position")), quat(q[0], q[1], q[2], q[3]));
        b.velocity = c(d.get<vector>("velocity"));
        b.angularVelocity = c(d.get<vector>("angularVelocity"));
        b.fluidForce = c(d.get<vector>("fluidForce"));
        b.fluidTorque = c(d.get<vector>("fluidTorque"));
        b.fluidDamping = d.get<scalar>("fluidDamping");
        b.fluidReferenceVelocity = c(d.get<vector>("fluidReferenceVelocity"));
        b.fluidReferenceAcceleration = c(d.get<vector>("fluidReferenceAcceleration"));
        b.fluidReferenceTime = d.get<scalar>("fluidReferenceTime");
        previousVelocity_[i] = d.get<vector>("previousVelocity");
        b.fluidAngularDamping = d.get<scalar>("fluidAngularDamping");
        b.fluidReferenceAngularVelocity = c(d.get<vector>("fluidReferenceAngularVelocity"));
        b.fluidReferenceAngularAcceleration = c(d.get<vector>("fluidReferenceAngularAcceleration"));
        previousAngularVelocity_[i] = d.get<vector>("previousAngularVelocity");
        innerMomentum_[i] = d.get<vector>("innerMomentum");
        innerAngularMomentum_[i] = d.get<vector>("innerAngularMomentum");
    }

    std::map<std::pair<int, int>, std::vector<contactHistory>> histories;
    const dictionary& cd = dict.subDict("contacts");
    for (const entry& e : cd)
    {
        const dictionary& d = e.dict();
        contactHistory h;
        h.tangentialSpring = c(d.get<vector>("tangentialSpring"));
        h.normal = c(d.get<vector>("normal"));
        h.point = c(d.get<vector>("point"));
        h.approach = d.get<scalar>("approach");
        h.maxNormalForce = d.get<scalar>("maxNormalForce");
        histories[{bodyIndex(d, "bodyA"), bodyIndex(d, "bodyB")}].push_back(h);
    }
    dem_->setHistories(std::move(histories));
    dem_->setTime(dict.get<scalar>("time"));
    return true;
}


Foam::label Foam::immersedDEMState::nBodies() const
{
    label n = 0;
    for (size_t i = 0; i < dem_->bodies().size(); ++i)
    {
        if (!dem_->isWall(i)) ++n;
    }
    return n;
}


Foam::immersedDEMState& Foam::immersedDEMState::New(const fvMesh& mesh)
{
    if (!mesh.foundObject<immersedDEMState>(typeName))
    {
        immersedDEMState* s = new immersedDEMState(mesh);
        s->store();
    }
    return mesh.lookupObjectRef<immersedDEMState>(typeName);
}
