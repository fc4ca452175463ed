#include "immersedFluidCoupling.H"
#include "immersedBoundaryProjection.H"
#include "coreConversion.H"
#include "immersedForcing.H"
#include "parallelSum.H"
#include "clockTime.H"
#include "syncTools.H"
#include "surfaceFields.H"

#include <algorithm>
#include <bitset>
#include <cmath>

using namespace immersedDEM;

namespace Foam
{
    defineTypeNameAndDebug(immersedFluidCoupling, 0);
}


namespace
{

constexpr auto v = &Foam::coreConversion::toFoam;
constexpr auto c = &Foam::coreConversion::toCore;

// The measured added mass's writer and reader for the restart (prefix +
// the measurement's member names)
struct measuredWriter
{
    Foam::Ostream& os;
    const char* prefix;
    void operator()(const char* n, const double& x) const
    {
        os.writeEntry(Foam::word(Foam::word(prefix) + n), x);
    }
    void operator()(const char* n, const vec3& x) const
    {
        os.writeEntry(Foam::word(Foam::word(prefix) + n), v(x));
    }
};

struct measuredReader
{
    const Foam::dictionary& d;
    const char* prefix;
    void operator()(const char* n, double& x) const
    {
        d.readIfPresent(Foam::word(Foam::word(prefix) + n), x);
    }
    void operator()(const char* n, vec3& x) const
    {
        Foam::vector y;
        if (d.readIfPresent(Foam::word(Foam::word(prefix) + n), y)) x = c(y);
    }
};

} // End anonymous namespace


Foam::immersedFluidCoupling::immersedFluidCoupling(const demSolver& dem)
{
    const label n = dem.bodies().size();
    innerMomentum_.setSize(n, Zero);
    innerAngularMomentum_.setSize(n, Zero);
    innerMomentum0_.setSize(n, Zero);
    innerAngularMomentum0_.setSize(n, Zero);
    previousVelocity_.setSize(n, Zero);
    previousAngularVelocity_.setSize(n, Zero);
    previousVelocity0_.setSize(n, Zero);
    previousAngularVelocity0_.setSize(n, Zero);
    history_.setSize(n, 0);
    wasInContact_.setSize(n, false);
    recentContacts_.setSize(n, allSteps);
    addedMass_.setSize(n);
    addedInertia_.setSize(n);
    sizes_.setSize(n);
    sized_.setSize(n, false);
    for (label i = 0; i < n; ++i)
    {
        previousVelocity_[i] = v(dem.bodies()[i].velocity);
        previousAngularVelocity_[i] = v(dem.bodies()[i].angularVelocity);
    }
}


void Foam::immersedFluidCoupling::setInnerMomentum
(
    const immersedBoundaryProjection& projection,
    const demSolver& dem,
    const volVectorField& U
)
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
    fluidSums(projection, dem, U, 0, P, PM, innerMomentum_, innerAngularMomentum_);
    innerMomentumSet_ = true;
}


void Foam::immersedFluidCoupling::fluidSums
(
    const immersedBoundaryProjection& projection,
    const demSolver& dem,
    const volVectorField& U,
    const scalar deltaT,
    List<vector>& penalty,
    List<vector>& penaltyMoment,
    List<vector>& momentum,
    List<vector>& angularMomentum
) const
{
    const label n = dem.bodies().size();
    for (List<vector>* l : {&penalty, &penaltyMoment, &momentum, &angularMomentum})
    {
        l->setSize(n);
        *l = Zero;
    }
    const fvMesh& mesh = U.mesh();
    const scalarField& V = mesh.V();
    const vectorField& C = mesh.cellCentres();
    const scalarField& lambda = projection.lambda().primitiveField();
    const vectorField& Uib = projection.Uib().primitiveField();
    const labelList& bodyOf = projection.bodyOf();
    const labelList& secondOf = projection.secondOf();
    const scalarField& secondLambda = projection.secondLambda();
    for (const label celli : projection.touched())
    {
        const label i = bodyOf[celli];
        if (i < 0) continue;
        const scalar w = lambda[celli]*V[celli];
        const vector r = C[celli] - v(dem.bodies()[i].pose.position());
        const vector d =
            projection.cellCoefficient(celli, deltaT)*V[celli]*(U[celli] - Uib[celli]);
        const vector m = w*U[celli];
        penalty[i] += d;
        penaltyMoment[i] += r ^ d;
        momentum[i] += m;
        angularMomentum[i] += r ^ m;

        // The fluid in a cell shared with a second body: its part of the
        // cell is that body's inner fluid
        const label j = secondOf[celli];
        if (j >= 0)
        {
            const vector mj = secondLambda[celli]*V[celli]*U[celli];
            const vector rj = C[celli] - v(dem.bodies()[j].pose.position());
            momentum[j] += mj;
            angularMomentum[j] += rj ^ mj;
        }
    }
    if (deltaT > 0)
    {
        sealedFacePressure(projection, dem, U, deltaT, penalty, penaltyMoment);
    }
    for (List<vector>* l : {&penalty, &penaltyMoment, &momentum, &angularMomentum})
    {
        immersedDEMParallel::sumOverProcessors(*l);
    }
}


void Foam::immersedFluidCoupling::sealedFacePressure
(
    const immersedBoundaryProjection& projection,
    const demSolver& dem,
    const volVectorField& U,
    const scalar deltaT,
    List<vector>& penalty,
    List<vector>& penaltyMoment
) const
{
    const fvMesh& mesh = U.mesh();
    const volScalarField* pp = mesh.findObject<volScalarField>(pName_);
    if (!pp) return;
    const volScalarField& p = *pp;

    // The forced cells: K deltaT >= 1, the cell follows its body more than
    // the fluid (sharp: centre inside; diffuse: lambda >= 1/2). Their
    // pressure is decoupled from the fluid's (diffusivity 1/(A + K))
    labelList forced(mesh.nCells(), -1);
    const labelList& bodyOf = projection.bodyOf();
    for (const label celli : projection.touched())
    {
        if
        (
            bodyOf[celli] >= 0
         && projection.cellCoefficient(celli, deltaT)*deltaT >= 1
        )
        {
            forced[celli] = bodyOf[celli];
        }
    }
    labelList nbrForced;
    syncTools::swapBoundaryCellList(mesh, forced, nbrForced);

    const labelUList& own = mesh.owner();
    const labelUList& nei = mesh.neighbour();
    const vectorField& Sf = mesh.Sf();
    const vectorField& Cf = mesh.Cf();
    const scalarField& w = mesh.weights();
    const label nInternal = mesh.nInternalFaces();
    const polyBoundaryMesh& patches = mesh.boundaryMesh();
    const cellList& cells = mesh.cells();
    const bool wallFaces = projection.forcing().sealedWalls;

    // A face between forced cells of two bodies is a film of no
    // thickness: its pressure is whatever makes the two rigid
    // velocities meet there (of the order of K times their difference),
    // not a fluid stress. Its force is taken out of the reaction, the part
    // of the pressure gradient that the penalty balances in those cells
    // (Gauss: sum over a body's cells of grad p V = sum over the faces
    // around them of p_f S_f). What the film carries is the contact's.
    // Faces between a body's forced cell and a fixed-velocity boundary
    // face (a wall patch) are the same explicit coupling (a cube pushed
    // against a side wall blows up within a few steps), but there the
    // film pressure also stands in for the squeeze flow the mesh does not
    // resolve: taken out, a sphere in a viscous oil rebounds from the
    // bottom elastically (case test restart). They are taken out only
    // with sealedWalls on, until the lubrication correction replaces
    // that squeeze-flow part (issue 15).
    //
    // What the film carries from the fluid around it is kept: the face's
    // pressure is taken out relative to the pressure around the body, a
    // linear fit p0 + G.(x - c) of the unforced cells' pressures over the
    // faces between its forced cells and unforced ones (weights: face
    // areas), not relative to zero. Zero is only the solver's gauge
    // (pRefCell in a closed tank): taking a face's whole pressure out gave
    // each of two touching cubes falling in water the gauge's offset times
    // the gap's area, 3e-4 N outwards (2% of their weight in water), and
    // they drifted apart. The gradient keeps the gap's face from losing
    // the vertical pressure gradient that the outer faces feel (a torque).
    const label nBodies = dem.bodies().size();
    List<scalar> aSum(nBodies, Zero), pSum(nBodies, Zero);
    List<vector> xSum(nBodies, Zero), pxSum(nBodies, Zero);
    List<symmTensor> xxSum(nBodies, Zero);
    // The pressure across each coupled patch, once (for the fit and for
    // the sealed faces)
    PtrList<scalarField> pNbr(patches.size());
    {
        forAll(patches, patchi)
        {
            if (patches[patchi].coupled())
            {
                pNbr.set(patchi, p.boundaryField()[patchi].patchNeighbourField().ptr());
            }
        }
        for (const label celli : projection.touched())
        {
            const label i = forced[celli];
            if (i < 0) continue;
            const point& xb = v(dem.bodies()[i].pose.position());
            for (const label facei : cells[celli])
            {
                scalar pn = 0, a = 0;
                point xf;
                if (facei < nInternal)
                {
                    const label nb = own[facei] == celli ? nei[facei] : own[facei];
                    if (forced[nb] >= 0) continue;
                    pn = p[nb];
                    a = mag(Sf[facei]);
                    xf = Cf[facei];
                }
                else
                {
                    const label patchi = patches.whichPatch(facei);
                    if (!patches[patchi].coupled() || nbrForced[facei - nInternal] >= 0)
                    {
                        continue;
                    }
                    const label pfi = facei - patches[patchi].start();
                    pn = pNbr[patchi][pfi];
                    a = mag(mesh.Sf().boundaryField()[patchi][pfi]);
                    xf = mesh.Cf().boundaryField()[patchi][pfi];
                }
                const vector r = xf - xb;
                aSum[i] += a;
                pSum[i] += a*pn;
                xSum[i] += a*r;
                pxSum[i] += a*pn*r;
                xxSum[i] += a*sqr(r);
            }
        }
        immersedDEMParallel::sumOverProcessors(aSum);
        immersedDEMParallel::sumOverProcessors(pSum);
        immersedDEMParallel::sumOverProcessors(xSum);
        immersedDEMParallel::sumOverProcessors(pxSum);
        immersedDEMParallel::sumOverProcessors(xxSum);
    }
    // The fit p = pm + G.(r - rm) per body, once (zero when no face of it
    // meets the fluid)
    scalarField pMean(nBodies, Zero);
    vectorField rMean(nBodies, Zero), gradient(nBodies, Zero);
    for (label i = 0; i < nBodies; ++i)
    {
        if (aSum[i] <= 0) continue;
        pMean[i] = pSum[i]/aSum[i];
        rMean[i] = xSum[i]/aSum[i];
        // Covariance of the face positions; regularised so that a
        // direction the faces do not span (2D) gets no gradient
        symmTensor C = xxSum[i]/aSum[i] - sqr(rMean[i]);
        C += 1e-6*tr(C)*symmTensor(I) + symmTensor(I)*VSMALL;
        gradient[i] = inv(C) & (pxSum[i]/aSum[i] - pMean[i]*rMean[i]);
    }
    auto pAround = [&](const label i, const point& x) -> scalar
    {
        if (aSum[i] <= 0) return 0;
        const vector r = x - v(dem.bodies()[i].pose.position());
        return pMean[i] + (gradient[i] & (r - rMean[i]));
    };

    auto remove = [&](const label i, const vector& S, const scalar pf, const point& x)
    {
        const vector dF = (pf - pAround(i, x))*S;
        const vector r = x - v(dem.bodies()[i].pose.position());
        penalty[i] += dF;
        penaltyMoment[i] += r ^ dF;
    };
    for (const label celli : projection.touched())
    {
        const label i = forced[celli];
        if (i < 0) continue;
        for (const label facei : cells[celli])
        {
            if (facei < nInternal)
            {
                const bool isOwner = own[facei] == celli;
                const label n = isOwner ? nei[facei] : own[facei];
                if (forced[n] < 0 || forced[n] == i) continue;
                const scalar pf =
                    w[facei]*p[own[facei]] + (1 - w[facei])*p[nei[facei]];
                remove(i, isOwner ? Sf[facei] : -Sf[facei], pf, Cf[facei]);
                continue;
            }
            const label patchi = patches.whichPatch(facei);
            const label pfi = facei - patches[patchi].start();
            const fvPatchScalarField& pb = p.boundaryField()[patchi];
            const vector& S = mesh.Sf().boundaryField()[patchi][pfi];
            const point& x = mesh.Cf().boundaryField()[patchi][pfi];
            if (patches[patchi].coupled())
            {
                const label n = nbrForced[facei - nInternal];
                if (n < 0 || n == i) continue;
                const scalar wf = mesh.weights().boundaryField()[patchi][pfi];
                const scalar pf = wf*p[celli] + (1 - wf)*pNbr[patchi][pfi];
                remove(i, S, pf, x);
            }
            else if (wallFaces && U.boundaryField()[patchi].fixesValue())
            {
                remove(i, S, pb[pfi], x);
            }
        }
    }
}


const immersedDEM::fluidImpedance::bodySize&
Foam::immersedFluidCoupling::sizeOf(const demSolver& dem, const label i)
{
    if (sized_[i])
    {
        return sizes_[i];
    }
    const rigidBody& b = dem.bodies()[i];
    const triangleSoup surface = b.geometry->surface();
    scalar area = 0;
    for (const auto& f : surface.faces)
    {
        const vec3& p0 = surface.points[f[0]];
        area += 0.5*(surface.points[f[1]] - p0).cross(surface.points[f[2]] - p0).norm();
    }
    fluidImpedance::bodySize& s = sizes_[i];
    s.volume = b.geometry->volume();
    s.area = area;
    s.circumscribedRadius = b.geometry->boundingRadius();
    s.depth = 0;

    // A 2D body (one translation locked, and the rotations about the
    // other two axes): per unit depth along the locked axis, which is
    // fixed in the body's frame (it turns only about it)
    int locked = -1;
    if (b.lockTranslation.sum() == 1)
    {
        for (int k = 0; k < 3; ++k)
        {
            if
            (
                b.lockTranslation[k]
             && b.lockRotation[(k + 1) % 3] && b.lockRotation[(k + 2) % 3]
            )
            {
                locked = k;
            }
        }
    }
    if (locked >= 0 && !surface.points.empty())
    {
        const vec3 e = b.pose.vectorToBody(vec3::Unit(locked));
        scalar lo = GREAT, hi = -GREAT, R2 = 0;
        for (const vec3& p : surface.points)
        {
            const scalar z = p.dot(e);
            lo = min(lo, z);
            hi = max(hi, z);
            R2 = max(R2, (p - z*e).squaredNorm());
        }
        if (hi > lo)
        {
            s.depth = hi - lo;
            const scalar section = s.volume/s.depth;
            s.volume = section;
            s.area = max(area - 2*section, scalar(0))/s.depth;
            s.circumscribedRadius = std::sqrt(R2);
        }
    }
    sized_[i] = true;
    return s;
}


void Foam::immersedFluidCoupling::fluidLoads
(
    const immersedBoundaryProjection& projection,
    demSolver& dem,
    const volVectorField& U,
    scalar deltaT,
    const settings& s
)
{
    const scalar rho = s.rho;
    const clockTime timer;
    setInnerMomentum(projection, dem, U);
    List<vector> P, PM, M, L;
    fluidSums(projection, dem, U, deltaT, P, PM, M, L);
    auto& bodies = dem.bodies();
    // Bodies in contact at the end of the last DEM step (pairs with a
    // contact history)
    List<bool> inContact(bodies.size(), false);
    for (const auto& p : dem.pairsInContact())
    {
        if (p.first < inContact.size()) inContact[p.first] = true;
        if (p.second < inContact.size()) inContact[p.second] = true;
    }
    // The bodies' volume-equivalent radii (in 2D of their sections), and
    // the others within reach of a body's shell, for its solid fraction
    const label n = bodies.size();
    List<scalar> equivalentRadius(n, scalar(0));
    forAll(equivalentRadius, j)
    {
        if (dem.isWall(j)) continue;
        const fluidImpedance::bodySize& sj = sizeOf(dem, j);
        equivalentRadius[j] = sj.depth > 0
            ? std::sqrt(sj.volume/constant::mathematical::pi)
            : std::cbrt(3*sj.volume/(4*constant::mathematical::pi));
    }
    std::vector<std::pair<double, double>> near;
    auto neighbours = [&](const label i) -> const std::vector<std::pair<double, double>>&
    {
        near.clear();
        const vec3& xi = bodies[i].pose.position();
        for (label j = 0; j < n; ++j)
        {
            if (j == i || dem.isWall(j)) continue;
            const double d = (bodies[j].pose.position() - xi).norm();
            if (d < 2*equivalentRadius[i] + equivalentRadius[j])
            {
                near.emplace_back(d, equivalentRadius[j]);
            }
        }
        return near;
    };
    forAll(M, i)
    {
        if (dem.isWall(i)) continue;
        rigidBody& b = bodies[i];
        const scalar Vb = b.geometry->volume();
        // The fluid's time scheme: second order from the second step of a
        // body's history on (OpenFOAM's backward is Euler in its first)
        const bool second = s.backward && history_[i] >= 1 && previousDeltaT_ > 0;
        const immersedForcing::timeDerivative ddt = second
            ? immersedForcing::timeDerivative::backward(deltaT, previousDeltaT_)
            : immersedForcing::timeDerivative::euler(deltaT);
        const vec3 innerRate =
            ddt.of(c(M[i]), c(innerMomentum_[i]), c(innerMomentum0_[i]));
        const vec3 innerAngularRate =
            ddt.of(c(L[i]), c(innerAngularMomentum_[i]), c(innerAngularMomentum0_[i]));
        const vec3 F = immersedForcing::fluidForce
        (
            rho, c(P[i]), innerRate, Vb, dem.settings().gravity
        );
        const vec3 T = immersedForcing::fluidTorque(rho, c(PM[i]), innerAngularRate);
        if (debug)
        {
            Info<< "immersedFluidCoupling loads " << word(b.name)
                << " t " << U.time().value()
                << " penalty " << rho*P[i]
                << " innerRate " << v(rho*innerRate)
                << " v " << v(b.velocity) << endl;
        }
        // The fluid's answer to a change of motion over the next step
        // (fluidImpedance.H), with the added mass the other bodies around
        // confine
        fluidImpedance::bodySize size = sizeOf(dem, i);
        size.cellSize = b.fluidCellSize;
        size.solidFraction = fluidImpedance::surroundingFraction
        (
            equivalentRadius[i], neighbours(i), size.depth > 0
        );
        fluidImpedance::coefficients z =
            fluidImpedance::estimate(size, rho, s.nu, deltaT);
        // The added mass the fluid solver shows (the change of force
        // against the change of acceleration; measuredAddedMass), for the
        // contact rule below. The smallest change of acceleration worth
        // measuring: 1e-2 m/s2, over the body's size for rotation
        const scalar unitMass = rho*Vb;
        const scalar unitInertia = rho/b.density*b.inertia().sum()/3;
        const scalar aFloor = 1e-2;
        addedMass_[i].record
        (
            F, (b.velocity - c(previousVelocity_[i]))/deltaT, sqr(aFloor)
        );
        addedInertia_[i].record
        (
            T, (b.angularVelocity - c(previousAngularVelocity_[i]))/deltaT,
            sqr(aFloor)/pow(Vb, 2.0/3.0)
        );
        // The body goes on from its course of the last step (reference
        // accelerations from it, as the fluid's scheme saw them: second
        // order once its velocity two steps back is known)
        const immersedForcing::timeDerivative dv =
            second && history_[i] >= 2
          ? ddt : immersedForcing::timeDerivative::euler(deltaT);
        vec3 a =
            dv.of(b.velocity, c(previousVelocity_[i]), c(previousVelocity0_[i]));
        vec3 alpha = dv.of
        (
            b.angularVelocity,
            c(previousAngularVelocity_[i]),
            c(previousAngularVelocity0_[i])
        );
        // Which rule: a body in a bed (in contact now, or with contacts in
        // more than one of the last CFD steps, or in two apart) takes the
        // contact rule; a free body the implicit coupling, unless the
        // fluid solver's significant answer exceeds its stable range
        // (M > m + 2 m_hat: fluidImpedance.H)
        const scalar cap = 100;
        bool held = inContact[i] || !isolatedImpact(recentContacts_[i]);
        if
        (
            !held
         && addedMass_[i].value(true) > b.mass() + 2*z.addedMass
         && z.addedMass < cap*unitMass
        )
        {
            held = true;
        }
        if (held)
        {
            // The contact rule. The body moves within the step by its
            // contacts, far faster than the fluid can answer, and its
            // velocity at the step's end is a sample of that motion: no
            // added mass carries it on. The damper m_a/deltaT (I_a/deltaT)
            // on its departure from the course extrapolated from the last
            // steps takes the fluid's answer to it within the step, m_a the
            // larger of rho V and the measured answer (the answer among
            // touching bodies exceeds any per-body estimate), and lets a
            // body at rest on a wall or in a bed stay at rest. A body that
            // landed within the step (in contact now, free at the step
            // before) changed its velocity by an impact, which does not go
            // on: its course is not extrapolated from it
            const scalar ma =
                addedMass_[i].stabilisation(b.mass(), unitMass, cap*unitMass);
            const scalar Ia = addedInertia_[i].stabilisation
            (
                b.inertia().sum()/3, unitInertia, cap*unitInertia
            );
            if (inContact[i] && !wasInContact_[i])
            {
                a = vec3::Zero();
                alpha = vec3::Zero();
            }
            b.fluid = fluidLoad::held
            (
                F, T, ma, Ia, std::min(z.nominalAddedMass, ma), deltaT,
                dem.time(), b.velocity, a, b.angularVelocity, alpha
            );
        }
        else
        {
            // The implicit coupling: the added mass carries the course on
            // and meets the fluid's answer to it, -m_a a; a bounce within
            // the step keeps its rebound
            b.fluid = fluidLoad::coupled
            (
                F, T, z, dem.time(), b.velocity, a, b.angularVelocity, alpha
            );
        }
        // Free of contacts at the step's start: an impact within the step
        // restarts the dampers' course (the contact moves the body with
        // its own added mass, far faster than the fluid; the damper would
        // take its rebound back towards the course before it)
        b.fluid.impactRestartsCourse = inContact[i] ? 0 : 1;
        if (debug)
        {
            Info<< "IFC " << word(b.name) << " t " << U.time().value()
                << " dt " << deltaT
                << " F " << v(F) << " T " << v(T)
                << " v " << v(b.velocity) << " w " << v(b.angularVelocity)
                << " a " << v(a)
                << " m " << b.mass() << " mhat " << z.addedMass
                << " c " << z.damping << " phi " << size.solidFraction
                << " con " << inContact[i] << wasInContact_[i]
                << " held " << held << " M " << addedMass_[i].value() << endl;
        }
        previousVelocity0_[i] = previousVelocity_[i];
        previousAngularVelocity0_[i] = previousAngularVelocity_[i];
        previousVelocity_[i] = v(b.velocity);
        previousAngularVelocity_[i] = v(b.angularVelocity);
        innerMomentum0_[i] = innerMomentum_[i];
        innerAngularMomentum0_[i] = innerAngularMomentum_[i];
        innerMomentum_[i] = M[i];
        innerAngularMomentum_[i] = L[i];
        ++history_[i];
        wasInContact_[i] = inContact[i];
    }
    previousDeltaT_ = deltaT;
    seconds_ += timer.elapsedTime();
}


Foam::scalar Foam::immersedFluidCoupling::takeSeconds()
{
    const scalar s = seconds_;
    seconds_ = 0;
    return s;
}


void Foam::immersedFluidCoupling::bodiesChanged
(
    const demSolver& dem,
    const std::vector<int>& kept,
    const label firstNew
)
{
    const label n = dem.bodies().size();
    // Kept bodies' entries to their new places; new bodies' set to fill
    auto remap = [&](auto& l, const auto& fill)
    {
        typename std::decay<decltype(l)>::type m(n, fill);
        for (label i = 0; i < firstNew; ++i)
        {
            m[i] = l[kept.empty() ? i : kept[i]];
        }
        l.transfer(m);
    };
    remap(innerMomentum_, vector::zero);
    remap(innerAngularMomentum_, vector::zero);
    remap(innerMomentum0_, vector::zero);
    remap(innerAngularMomentum0_, vector::zero);
    remap(previousVelocity_, vector::zero);
    remap(previousAngularVelocity_, vector::zero);
    remap(previousVelocity0_, vector::zero);
    remap(previousAngularVelocity0_, vector::zero);
    remap(history_, label(0));
    remap(wasInContact_, false);
    remap(recentContacts_, allSteps);
    remap(addedMass_, measuredAddedMass());
    remap(addedInertia_, measuredAddedMass());
    remap(sizes_, fluidImpedance::bodySize());
    remap(sized_, false);
    for (label i = firstNew; i < n; ++i)
    {
        previousVelocity_[i] = v(dem.bodies()[i].velocity);
        previousAngularVelocity_[i] = v(dem.bodies()[i].angularVelocity);
    }
}


void Foam::immersedFluidCoupling::setNewInnerMomentum
(
    const immersedBoundaryProjection& projection,
    const demSolver& dem,
    const volVectorField& U,
    const label first
)
{
    if (first >= label(dem.bodies().size()))
    {
        return;
    }
    List<vector> P, PM, M, MA;
    fluidSums(projection, dem, U, 0, P, PM, M, MA);
    for (label i = first; i < M.size(); ++i)
    {
        innerMomentum_[i] = M[i];
        innerAngularMomentum_[i] = MA[i];
    }
}


void Foam::immersedFluidCoupling::writeBody(Ostream& os, const label i) const
{
    os.writeEntry("previousVelocity", previousVelocity_[i]);
    os.writeEntry("previousAngularVelocity", previousAngularVelocity_[i]);
    os.writeEntry("innerMomentum", innerMomentum_[i]);
    os.writeEntry("innerAngularMomentum", innerAngularMomentum_[i]);
    os.writeEntry("previousVelocity0", previousVelocity0_[i]);
    os.writeEntry("previousAngularVelocity0", previousAngularVelocity0_[i]);
    os.writeEntry("innerMomentum0", innerMomentum0_[i]);
    os.writeEntry("innerAngularMomentum0", innerAngularMomentum0_[i]);
    os.writeEntry("history", history_[i]);
    os.writeEntry("previousDeltaT", previousDeltaT_);
    os.writeEntry("inContact", wasInContact_[i]);
    os.writeEntry("recentContacts", recentContacts_[i]);
    measuredAddedMass::fields(addedMass_[i], measuredWriter{os, "addedMass"});
    measuredAddedMass::fields(addedInertia_[i], measuredWriter{os, "addedInertia"});
}


void Foam::immersedFluidCoupling::readBody(const dictionary& d, const label i)
{
    previousVelocity_[i] = d.get<vector>("previousVelocity");
    previousAngularVelocity_[i] = d.get<vector>("previousAngularVelocity");
    innerMomentum_[i] = d.get<vector>("innerMomentum");
    innerAngularMomentum_[i] = d.get<vector>("innerAngularMomentum");
    innerMomentumSet_ = true;
    // (written before the second-order history: a history of one step,
    // first order at the next)
    previousVelocity0_[i] = d.getOrDefault<vector>("previousVelocity0", previousVelocity_[i]);
    previousAngularVelocity0_[i] =
        d.getOrDefault<vector>("previousAngularVelocity0", previousAngularVelocity_[i]);
    innerMomentum0_[i] = d.getOrDefault<vector>("innerMomentum0", innerMomentum_[i]);
    innerAngularMomentum0_[i] =
        d.getOrDefault<vector>("innerAngularMomentum0", innerAngularMomentum_[i]);
    history_[i] = d.getOrDefault<label>("history", 0);
    previousDeltaT_ = max(previousDeltaT_, d.getOrDefault<scalar>("previousDeltaT", 0));
    wasInContact_[i] = d.getOrDefault<bool>("inContact", true);
    // (written before it: as a new body)
    recentContacts_[i] = d.getOrDefault<label>("recentContacts", allSteps);
    // (written before the measurement: it starts again from nothing)
    addedMass_[i].reset();
    addedInertia_[i].reset();
    measuredAddedMass::fields(addedMass_[i], measuredReader{d, "addedMass"});
    measuredAddedMass::fields(addedInertia_[i], measuredReader{d, "addedInertia"});
}


bool Foam::immersedFluidCoupling::isolatedImpact(const label steps)
{
    // One step with contacts, or two in a row (an impact across the end
    // of a step: at 16 cells per diameter the wet bounce's contact often
    // is): one run of set bits, at most two long
    const std::bitset<32> b(steps);
    const std::bitset<32> runStarts(steps & ~(steps >> 1));
    return b.count() <= 1 || (b.count() == 2 && runStarts.count() == 1);
}


void Foam::immersedFluidCoupling::noteContacts(demSolver& dem)
{
    const std::vector<char>& touched = dem.touched();
    forAll(recentContacts_, i)
    {
        const bool t = size_t(i) < touched.size() && touched[i];
        recentContacts_[i] = ((recentContacts_[i] << 1) | label(t)) & allSteps;
    }
    dem.clearTouched();
}
