#include "immersedFluidCoupling.H"
#include "immersedBoundaryProjection.H"
#include "coreConversion.H"
#include "immersedForcing.H"
#include "parallelSum.H"
#include "clockTime.H"
#include "syncTools.H"
#include "surfaceFields.H"

#include <bitset>

using namespace immersedDEM;

namespace Foam
{
    defineTypeNameAndDebug(immersedFluidCoupling, 0);
}


namespace
{

constexpr auto v = &Foam::coreConversion::toFoam;
constexpr auto c = &Foam::coreConversion::toCore;

// measuredAddedMass::fields visitors: each member under prefix + its name
struct measuredWriter
{
    Foam::Ostream& os;
    const Foam::word prefix;
    void operator()(const char* name, const vec3& x) { os.writeEntry(Foam::word(prefix + name), v(x)); }
    void operator()(const char* name, const double x) { os.writeEntry(Foam::word(prefix + name), x); }
};

// Missing entries (a restart written before the measurement) keep the
// member as it is
struct measuredReader
{
    const Foam::dictionary& d;
    const Foam::word prefix;
    void operator()(const char* name, vec3& x)
    {
        x = c(d.getOrDefault<Foam::vector>(prefix + name, v(x)));
    }
    void operator()(const char* name, double& x)
    {
        x = d.getOrDefault<Foam::scalar>(prefix + name, x);
    }
};

} // End anonymous namespace


Foam::immersedFluidCoupling::immersedFluidCoupling(const demSolver& dem)
{
    const label n = dem.bodies().size();
    innerMomentum_.setSize(n, Zero);
    innerAngularMomentum_.setSize(n, Zero);
    previousVelocity_.setSize(n, Zero);
    previousAngularVelocity_.setSize(n, Zero);
    addedMass_.setSize(n);
    addedInertia_.setSize(n);
    reportedAddedMass_.setSize(n, 0);
    previousContact_.setSize(n, false);
    recentContacts_.setSize(n, allSteps);
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


void Foam::immersedFluidCoupling::fluidLoads
(
    const immersedBoundaryProjection& projection,
    demSolver& dem,
    const volVectorField& U,
    scalar deltaT,
    const settings& s
)
{
    const scalar rho = s.rho, Ca = s.Ca;
    const bool measure = s.measure;
    using impact = settings::impact;
    const clockTime timer;
    setInnerMomentum(projection, dem, U);
    List<vector> P, PM, M, L;
    fluidSums(projection, dem, U, deltaT, P, PM, M, L);
    auto& bodies = dem.bodies();
    // Bodies in contact at the end of the last DEM step (pairs with a
    // contact history). They keep the damper (fluidLoad.H); with
    // impactInertia the others (yes), or those that had one impact
    // (isolated), carry their added mass as inertia, so that an impact
    // within the next step keeps its rebound
    List<bool> inContact(bodies.size(), false);
    for (const auto& p : dem.pairsInContact())
    {
        if (p.first < inContact.size()) inContact[p.first] = true;
        if (p.second < inContact.size()) inContact[p.second] = true;
    }
    forAll(M, i)
    {
        if (dem.isWall(i)) continue;
        rigidBody& b = bodies[i];
        const scalar Vb = b.geometry->volume();
        const vec3 F = immersedForcing::fluidForce
        (
            rho, c(P[i]), c(M[i]), c(innerMomentum_[i]), deltaT, Vb,
            dem.settings().gravity
        );
        const vec3 T = immersedForcing::fluidTorque
        (
            rho, c(PM[i]), c(L[i]), c(innerAngularMomentum_[i]), deltaT
        );
        if (debug)
        {
            Info<< "immersedFluidCoupling loads " << word(b.name)
                << " t " << U.time().value()
                << " penalty " << rho*P[i]
                << " innerRate " << rho*(M[i] - innerMomentum_[i])/deltaT
                << " v " << v(b.velocity) << endl;
        }
        // The stabilisation's added mass and moment of inertia (the mean
        // principal moment): Ca's, or the measured ones when larger
        // (at most those of the keyword's largest Ca, 100)
        const scalar unitMass = rho*Vb;
        const scalar unitInertia = rho/b.density*b.inertia().sum()/3;
        scalar ma = Ca*unitMass;
        scalar Ia = Ca*unitInertia;
        // The smallest change of acceleration worth measuring: 1e-2 m/s2,
        // over the body's size for rotation
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
        // Inertia over this step (see settings::impact). A body carrying
        // its added mass as inertia takes M only from changes of force
        // that follow its changes of acceleration (measuredAddedMass: the
        // force noise of a resolved sphere read as M would carry its
        // bounce on)
        bool inertia =
            !inContact[i]
         && (
                s.impactInertia == impact::yes
             || (
                    s.impactInertia == impact::isolated
                 && isolatedImpact(recentContacts_[i])
                )
            );
        if (measure)
        {
            const scalar cap = 100;
            ma = addedMass_[i].stabilisation
            (
                b.mass(), ma, cap*unitMass,
                inertia || s.impactInertia == impact::yes
            );
            Ia = addedInertia_[i].stabilisation
            (
                b.inertia().sum()/3, Ia, cap*unitInertia
            );
            noteAddedMass(i, ma/unitMass, Ca, b.name);
        }
        // A body that landed within the step (in contact now, free of
        // contacts at the last step's end) changed its velocity by an
        // impact, which does not go on: its course is not extrapolated
        // from it (zero reference accelerations). Extrapolated, the
        // landing's deceleration became a course upwards, and the damper
        // pulled the body off what it had landed on (src/README.md,
        // coupling). A body leaving a contact keeps its reference (with
        // impactInertia yes, m_a a_ref meets the fluid's answer to the
        // push). With isolated: the nominal Ca rho V as inertia where
        // that is stable (r = (Ca rho V - M)/(m + Ca rho V) > -1: the
        // measured M within m + 2 Ca rho V; two cubes 0.1 mm apart in a
        // viscous oil blew up without this), and a body leaving a contact
        // carries nothing of its push-off on (zero reference
        // acceleration: its m_a a_ref kept a pellet leaving a bed
        // accelerating against the fluid; src/README.md, coupling)
        bool fresh = inContact[i] && !previousContact_[i];
        scalar inertiaMass = ma;
        if (inertia && s.impactInertia == impact::isolated)
        {
            inertiaMass = Ca*unitMass;
            if (ma > b.mass() + 2*inertiaMass)
            {
                inertia = false;
            }
            else
            {
                fresh = fresh || previousContact_[i];
            }
        }
        b.fluid = fluidLoad::stabilised
        (
            F, T, inertia ? inertiaMass : ma, Ca*unitMass, inertia, Ia,
            deltaT, dem.time(),
            b.velocity, fresh ? b.velocity : c(previousVelocity_[i]),
            b.angularVelocity,
            fresh ? b.angularVelocity : c(previousAngularVelocity_[i])
        );
        previousContact_[i] = inContact[i];
        previousVelocity_[i] = v(b.velocity);
        previousAngularVelocity_[i] = v(b.angularVelocity);
        innerMomentum_[i] = M[i];
        innerAngularMomentum_[i] = L[i];
    }
    reportAddedMass(Ca, U.time().value());
    seconds_ += timer.elapsedTime();
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


void Foam::immersedFluidCoupling::noteAddedMass
(
    const label i,
    const scalar coefficient,
    const scalar Ca,
    const word& name
)
{
    if (coefficient <= Ca || coefficient < 2*reportedAddedMass_[i])
    {
        return;
    }
    reportedAddedMass_[i] = coefficient;
    ++raised_;
    if (coefficient > largestRaised_)
    {
        largestRaised_ = coefficient;
        largestRaisedBody_ = name;
    }
}


void Foam::immersedFluidCoupling::reportAddedMass(const scalar Ca, const scalar t)
{
    if (raised_ > 0)
    {
        Info<< "immersedDEM: t = " << t << ": the fluid solver's added mass"
            << " measured above addedMassCoefficient " << Ca
            << " rho V (and twice the last reported) for " << raised_
            << " bodies, largest " << largestRaised_ << " rho V ("
            << largestRaisedBody_ << "); their stabilisation uses it" << endl;
    }
    raised_ = 0;
    largestRaised_ = 0;
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
    remap(previousVelocity_, vector::zero);
    remap(previousAngularVelocity_, vector::zero);
    remap(addedMass_, measuredAddedMass());
    remap(addedInertia_, measuredAddedMass());
    remap(reportedAddedMass_, scalar(0));
    remap(previousContact_, false);
    remap(recentContacts_, allSteps);
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
    os.writeEntry("inContact", previousContact_[i]);
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
    // Restart files written before it have none: in contact (the
    // extrapolation kept, as it was before)
    previousContact_[i] = d.getOrDefault<bool>("inContact", true);
    // (written before it: as a new body)
    recentContacts_[i] = d.getOrDefault<label>("recentContacts", allSteps);
    // Restart files written before the measurement have none: it starts
    // again from nothing
    addedMass_[i].reset();
    addedInertia_[i].reset();
    measuredAddedMass::fields(addedMass_[i], measuredReader{d, "addedMass"});
    measuredAddedMass::fields(addedInertia_[i], measuredReader{d, "addedInertia"});
}
