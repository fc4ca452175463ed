#include "immersedDEMPeriodic.H"
#include "cyclicPolyPatch.H"
#include "processorCyclicPolyPatch.H"
#include "coreConversion.H"
#include "coreError.H"

using namespace Foam;


::immersedDEM::periodicBox Foam::immersedDEMPeriodic::fromMesh
(
    const polyMesh& mesh,
    const dictionary& dict,
    const bool log
)
{
    ::immersedDEM::periodicBox box;
    const polyBoundaryMesh& patches = mesh.boundaryMesh();
    const pointField& points = mesh.points();
    const vectorField& Sf = mesh.faceAreas();

    // Every processor holds every patch of the whole mesh (decomposePar
    // keeps them, a cyclic's faces across processors on processorCyclic
    // patches referring to it): the same directions in the same order
    forAll(patches, patchi)
    {
        const cyclicPolyPatch* cp = isA<cyclicPolyPatch>(patches[patchi]);
        if (!cp || !cp->owner()) continue;

        // The patch's area vector, its faces here and on processorCyclic
        // patches included, summed over the processors
        vector S = sum(vectorField(Sf, identity(cp->size(), cp->start())));
        bool rotational =
            cp->transform() == coupledPolyPatch::ROTATIONAL
         || (cp->size() > 0 && !cp->parallel());
        forAll(patches, pj)
        {
            const processorCyclicPolyPatch* pc =
                isA<processorCyclicPolyPatch>(patches[pj]);
            if (pc && pc->referPatchID() == patchi)
            {
                S += sum(vectorField(Sf, identity(pc->size(), pc->start())));
            }
        }
        reduce(S, sumOp<vector>());
        reduce(rotational, orOp<bool>());
        if (rotational)
        {
            FatalIOErrorInFunction(dict)
                << "Cyclic patch '" << cp->name() << "' is rotational: the"
                << " bodies of " << dict.name() << " can cross translational"
                << " cyclic patches only (transform translational, or the"
                << " default with the patches a translation apart)" << nl
                << exit(FatalIOError);
        }
        vector L = Zero;
        if (cp->transform() == coupledPolyPatch::TRANSLATIONAL)
        {
            L = cp->separationVector();
        }
        else
        {
            const scalar a = mag(S);
            if (a < VSMALL)
            {
                FatalIOErrorInFunction(dict)
                    << "Cyclic patch '" << cp->name() << "' has no area on"
                    << " any processor: its translation cannot be found. Give"
                    << " it transform translational; separationVector (...);"
                    << " in constant/polyMesh/boundary" << nl
                    << exit(FatalIOError);
            }
            const vector n = S/a;
            scalar lo = GREAT, hi = -GREAT;
            for (const point& p : points)
            {
                const scalar t = p & n;
                lo = min(lo, t);
                hi = max(hi, t);
            }
            reduce(lo, minOp<scalar>());
            reduce(hi, maxOp<scalar>());
            L = (hi - lo)*n;
            // (either sign is the same period; the positive one reads best)
            if (cmptSum(L) < 0) L = -L;
            L += vector::zero;  // (no -0 in the log)
        }
        try
        {
            box.addDirection(coreConversion::toCore(L), cp->name());
        }
        catch (const ::immersedDEM::coreError& err)
        {
            FatalIOErrorInFunction(dict)
                << "In " << dict.name() << ": " << err.what() << nl
                << exit(FatalIOError);
        }
    }
    if (!box.active())
    {
        return box;
    }

    // The primary cell's corner: the mesh's lowest extent along each
    // direction (a box-shaped domain)
    ::immersedDEM::vec3 origin = ::immersedDEM::vec3::Zero();
    for (int k = 0; k < box.directions(); ++k)
    {
        const vector e = coreConversion::toFoam(box.period(k))/box.length(k);
        scalar lo = GREAT;
        for (const point& p : points) lo = min(lo, p & e);
        reduce(lo, minOp<scalar>());
        origin += lo*coreConversion::toCore(e);
    }
    box.setOrigin(origin);
    if (!log)
    {
        return box;
    }

    Info<< "    periodic for the bodies:";
    for (int k = 0; k < box.directions(); ++k)
    {
        Info<< " " << word(box.name(k)) << " (period "
            << coreConversion::toFoam(box.period(k)) << " m)";
    }
    Info<< endl;
    return box;
}
