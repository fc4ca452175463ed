#include "bodyFluidSums.H"
#include "immersedBoundaryProjection.H"
#include "coreConversion.H"
#include "parallelSum.H"
#include "syncTools.H"
#include "surfaceFields.H"
#include "transformFvPatchFields.H"

using namespace immersedDEM;


namespace
{

using namespace Foam;

//- A boundary that no fluid passes: a fixed velocity (a no-slip or
//  moving wall, an inlet) or a fixed normal component (slip, symmetry,
//  partial slip)
bool sealsBodies(const fvPatchVectorField& Ub)
{
    return Ub.fixesValue() || isA<transformFvPatchVectorField>(Ub);
}

constexpr auto v = &coreConversion::toFoam;
constexpr auto c = &coreConversion::toCore;

//- The pressure around each body: a linear fit p0 + G.(x - c) of the
//  pressures of the fluid cells next to its forced cells, over the faces
//  between them (weights: face areas). Zero for a body none of whose faces
//  meets the fluid.
//
//  Why not zero: zero is only the solver's gauge (pRefCell in a closed
//  tank). Taking a sealed face's whole pressure out gave each of two
//  touching cubes falling in water the gauge's offset times the gap's
//  area, outwards, and they drifted apart. Why the gradient: the gap's
//  face keeps the vertical pressure gradient that the outer faces feel
//  (a torque).
class surroundingPressure
{
    const demSolver& dem_;
    List<scalar> aSum_;
    scalarField pMean_;
    vectorField rMean_;
    vectorField gradient_;

public:

    //- forced: each cell's forced body (-1: none), nbrForced the same
    //  across the coupled patches' faces; pNbr the pressure across them
    surroundingPressure
    (
        const immersedBoundaryProjection& projection,
        const demSolver& dem,
        const volScalarField& p,
        const labelList& forced,
        const labelList& nbrForced,
        const PtrList<scalarField>& pNbr
    )
    :
        dem_(dem),
        aSum_(dem.bodies().size(), Zero),
        pMean_(dem.bodies().size(), Zero),
        rMean_(dem.bodies().size(), Zero),
        gradient_(dem.bodies().size(), Zero)
    {
        const fvMesh& mesh = p.mesh();
        const labelUList& own = mesh.owner();
        const labelUList& nei = mesh.neighbour();
        const vectorField& Sf = mesh.Sf();
        const vectorField& Cf = mesh.Cf();
        const label nInternal = mesh.nInternalFaces();
        const polyBoundaryMesh& patches = mesh.boundaryMesh();
        const cellList& cells = mesh.cells();

        const label nBodies = dem.bodies().size();
        List<scalar> pSum(nBodies, Zero);
        List<vector> xSum(nBodies, Zero), pxSum(nBodies, Zero);
        List<symmTensor> xxSum(nBodies, Zero);
        for (const label celli : projection.touched())
        {
            const label i = forced[celli];
            if (i < 0) continue;
            const point xb =
                v(dem.bodies()[i].pose.position()) + projection.bodyShift(celli);
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
                aSum_[i] += a;
                pSum[i] += a*pn;
                xSum[i] += a*r;
                pxSum[i] += a*pn*r;
                xxSum[i] += a*sqr(r);
            }
        }
        immersedDEMParallel::sumOverProcessors(aSum_);
        immersedDEMParallel::sumOverProcessors(pSum);
        immersedDEMParallel::sumOverProcessors(xSum);
        immersedDEMParallel::sumOverProcessors(pxSum);
        immersedDEMParallel::sumOverProcessors(xxSum);

        // The fit p = pm + G.(r - rm) per body
        for (label i = 0; i < nBodies; ++i)
        {
            if (aSum_[i] <= 0) continue;
            pMean_[i] = pSum[i]/aSum_[i];
            rMean_[i] = xSum[i]/aSum_[i];
            // Covariance of the face positions; regularised so that a
            // direction the faces do not span (2D) gets no gradient
            symmTensor C = xxSum[i]/aSum_[i] - sqr(rMean_[i]);
            C += 1e-6*tr(C)*symmTensor(I) + symmTensor(I)*VSMALL;
            gradient_[i] = inv(C) & (pxSum[i]/aSum_[i] - pMean_[i]*rMean_[i]);
        }
    }

    //- Around body i at x
    scalar at(const label i, const point& x) const
    {
        if (aSum_[i] <= 0) return 0;
        const vector r = x - v(dem_.bodies()[i].pose.position());
        return pMean_[i] + (gradient_[i] & (r - rMean_[i]));
    }
};

} // End anonymous namespace


Foam::bodyFluidSums::bodyFluidSums
(
    const immersedBoundaryProjection& projection,
    const demSolver& dem,
    const volVectorField& U,
    const scalar deltaT,
    const word& pName
)
{
    const label n = dem.bodies().size();
    for
    (
        List<vector>* l
      : {&penalty, &penaltyMoment, &momentum, &angularMomentum, &outflow, &angularOutflow}
    )
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
        const vector r =
            C[celli] - projection.bodyShift(celli) - v(dem.bodies()[i].pose.position());
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
            const vector rj =
                C[celli] - projection.secondShift(celli)
              - v(dem.bodies()[j].pose.position());
            momentum[j] += mj;
            angularMomentum[j] += rj ^ mj;
        }
    }
    // The inner fluid leaving the mesh (or entering it) through the
    // boundary faces of the bodies' cells that are not coupled: each
    // face's flux times the part of the face inside the body. That part
    // is the face's own, not its cell's lambda: a body entering the
    // outlet's cells from upstream covers none of the outlet yet, and
    // lambda would count its outflow half a cell early (the body pushed
    // out by rho U^2 A h/2: +10% of its speed at 8 cells per diameter).
    // It ramps over the face's size across the surface (signed distance
    // of the face centre), so that it grows smoothly as the surface
    // crosses the face
    // (deltaT 0: the momenta only, as at the start of a step)
    const surfaceScalarField* phi =
        deltaT > 0 ? mesh.findObject<surfaceScalarField>("phi") : nullptr;
    if (phi)
    {
        const polyBoundaryMesh& patches = mesh.boundaryMesh();
        const auto inside = [&](const label i, const point& x, const scalar size)
        {
            const rigidBody& b = dem.bodies()[i];
            const scalar d = b.geometry->signedDistance(b.pose, c(x));
            return min(max(0.5 - d/size, scalar(0)), scalar(1));
        };
        forAll(patches, patchi)
        {
            const polyPatch& pp = patches[patchi];
            const scalarField& phiP = phi->boundaryField()[patchi];
            // (an empty patch's fields have no values: a 2D slab's sides)
            if (pp.coupled() || phiP.size() != pp.size()) continue;
            const vectorField& UP = U.boundaryField()[patchi];
            const vectorField& CfP = mesh.Cf().boundaryField()[patchi];
            const scalarField& magSfP = mesh.magSf().boundaryField()[patchi];
            const labelUList& faceCells = pp.faceCells();
            forAll(faceCells, k)
            {
                if (phiP[k] == 0) continue;
                const label celli = faceCells[k];
                const scalar size = std::sqrt(magSfP[k]);
                for (const bool second : {false, true})
                {
                    const label i = second ? secondOf[celli] : bodyOf[celli];
                    if (i < 0) continue;
                    const point x = CfP[k]
                      - (second ? projection.secondShift(celli) : projection.bodyShift(celli));
                    const scalar f = inside(i, x, size);
                    if (f <= 0) continue;
                    const vector m = f*phiP[k]*UP[k];
                    outflow[i] += m;
                    angularOutflow[i] += (x - v(dem.bodies()[i].pose.position())) ^ m;
                }
            }
        }
    }
    const volScalarField* p = mesh.findObject<volScalarField>(pName);
    if (deltaT > 0 && p)
    {
        removeSealedFacePressure(projection, dem, U, deltaT, *p);
    }
    for
    (
        List<vector>* l
      : {&penalty, &penaltyMoment, &momentum, &angularMomentum, &outflow, &angularOutflow}
    )
    {
        immersedDEMParallel::sumOverProcessors(*l);
    }
}


void Foam::bodyFluidSums::removeSealedFacePressure
(
    const immersedBoundaryProjection& projection,
    const demSolver& dem,
    const volVectorField& U,
    const scalar deltaT,
    const volScalarField& p
)
{
    const fvMesh& mesh = U.mesh();

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

    // The force a sealed face's pressure puts on the body is taken out of
    // the reaction: it is the part of the pressure gradient that the
    // penalty balances in those cells (Gauss: sum over a body's cells of
    // grad p V = sum over the faces around them of p_f S_f). Faces between
    // a body's forced cell and a fixed-velocity boundary face (a wall
    // patch) are the same explicit coupling (a cube pushed against a side
    // wall blows up within a few steps), but there the film pressure also
    // stands in for the squeeze flow the mesh does not resolve: taken out,
    // a sphere in a viscous oil rebounds from the bottom elastically (case
    // test restart). They are taken out only with sealedWalls on, until
    // the lubrication correction replaces that squeeze-flow part. A
    // slip or symmetry patch fixes the normal velocity as a no-slip wall
    // does, so its faces are sealed the same way: left in, a light sphere
    // rising against a slip top was pushed back down by them at three
    // times its buoyancy, and was thrown out at 0.5 m/s in two bounces.

    // The pressure across each coupled patch, once (for the fit and for
    // the sealed faces)
    PtrList<scalarField> pNbr(patches.size());
    forAll(patches, patchi)
    {
        if (patches[patchi].coupled())
        {
            pNbr.set(patchi, p.boundaryField()[patchi].patchNeighbourField().ptr());
        }
    }
    const surroundingPressure around(projection, dem, p, forced, nbrForced, pNbr);

    // (weight: the share of the face's pressure taken out)
    auto remove =
        [&](const label i, const vector& S, const scalar pf, const point& x, const scalar weight = 1)
    {
        const vector dF = weight*(pf - around.at(i, x))*S;
        const vector r = x - v(dem.bodies()[i].pose.position());
        penalty[i] += dF;
        penaltyMoment[i] += r ^ dF;
    };
    for (const label celli : projection.touched())
    {
        // A cell on its way to being forced (0 < K deltaT < 1: a fluid
        // cell next to a body's surface) has that share of its wall faces'
        // pressure taken out, so that the share grows with K as the
        // surface comes near instead of jumping from 0 to 1 when K deltaT
        // reaches 1. Taken out at once, the squeeze pressure on a ring of
        // wall faces left a sphere's load in one step, and its force
        // against the gap went in a sawtooth
        // (validation/studies/lubricationWall)
        const bool isForced = forced[celli] >= 0;
        const label i = isForced ? forced[celli] : bodyOf[celli];
        const scalar share =
            isForced ? 1 : projection.cellCoefficient(celli, deltaT)*deltaT;
        if (!isForced && (!wallFaces || i < 0 || !(share > 0))) continue;
        // (faces seen from the image of the body that set the cell)
        const vector sh = projection.bodyShift(celli);
        for (const label facei : cells[celli])
        {
            if (facei < nInternal)
            {
                if (!isForced) continue;
                const bool isOwner = own[facei] == celli;
                const label n = isOwner ? nei[facei] : own[facei];
                if (forced[n] < 0 || forced[n] == i) continue;
                const scalar pf =
                    w[facei]*p[own[facei]] + (1 - w[facei])*p[nei[facei]];
                remove(i, isOwner ? Sf[facei] : -Sf[facei], pf, Cf[facei] - sh);
                continue;
            }
            const label patchi = patches.whichPatch(facei);
            const label pfi = facei - patches[patchi].start();
            const fvPatchScalarField& pb = p.boundaryField()[patchi];
            const vector& S = mesh.Sf().boundaryField()[patchi][pfi];
            const point& x = mesh.Cf().boundaryField()[patchi][pfi];
            if (patches[patchi].coupled())
            {
                if (!isForced) continue;
                const label n = nbrForced[facei - nInternal];
                if (n < 0 || n == i) continue;
                const scalar wf = mesh.weights().boundaryField()[patchi][pfi];
                const scalar pf = wf*p[celli] + (1 - wf)*pNbr[patchi][pfi];
                remove(i, S, pf, x - sh);
            }
            else if (wallFaces && sealsBodies(U.boundaryField()[patchi]))
            {
                remove(i, S, pb[pfi], x - sh, share);
            }
        }
    }
}
