#include "periodicDrive.H"
#include "coreConversion.H"

using namespace Foam;


namespace
{

//- The projector on the periodic directions
tensor projector(const ::immersedDEM::periodicBox& p)
{
    tensor P = Zero;
    for (int k = 0; k < p.directions(); ++k)
    {
        const vector e = coreConversion::toFoam(p.period(k))/p.length(k);
        P += e*e;
    }
    return P;
}

} // End anonymous namespace


bool Foam::periodicDrive::needed
(
    const ::immersedDEM::demSolver& dem,
    const vector& g
)
{
    return mag(projector(dem.periodic()) & g) > SMALL*(mag(g) + VSMALL);
}


Foam::periodicDrive::parts Foam::periodicDrive::of
(
    const ::immersedDEM::demSolver& dem,
    const vector& g,
    const scalar rho,
    const volVectorField& U,
    const scalar deltaT
)
{
    const tensor P = projector(dem.periodic());
    const fvMesh& mesh = U.mesh();
    const scalarField& V = mesh.V();
    const scalar Vbox = gSum(V);

    // Every processor holds every body: the sum is the same everywhere
    scalar excess = 0;
    const auto& bodies = dem.bodies();
    for (size_t i = 0; i < bodies.size(); ++i)
    {
        if (dem.isWall(int(i)) || !bodies[i].dynamic()) continue;
        excess += (bodies[i].density/rho - 1)*bodies[i].geometry->volume();
    }
    parts f;
    f.weight = -(P & (excess/Vbox*g));
    if (deltaT > 0)
    {
        f.meanU = gSum(U.primitiveField()*V)/Vbox;
        f.flux = -(P & f.meanU)/deltaT;
    }
    // (no -0 in the log)
    f.weight += vector::zero;
    f.flux += vector::zero;
    f.meanU += vector::zero;
    return f;
}
