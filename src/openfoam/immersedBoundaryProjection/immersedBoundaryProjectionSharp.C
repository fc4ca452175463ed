// immersedBoundaryProjection: the sharp surface (centres inside follow the
// body, the fluid cells next to them take the wall-shear coefficient) and
// the forcing coefficient K of each cell

#include "immersedBoundaryProjection.H"
#include "coreConversion.H"
#include "surfaceFields.H"

using namespace immersedDEM;


namespace
{

constexpr auto v = &Foam::coreConversion::toFoam;
constexpr auto c = &Foam::coreConversion::toCore;

} // End anonymous namespace


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


void Foam::immersedBoundaryProjection::projectSharp
(
    const rigidBody& b,
    const label bi,
    const bodyPose& pose,
    const vec3& shift,
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
                if (shiftOf_.size()) shiftOf_[celli] = v(shift);
                Uib[celli] = v(b.pointVelocity(c(C[celli]) - shift));
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
