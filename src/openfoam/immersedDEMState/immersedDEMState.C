#include "immersedDEMState.H"
#include "immersedDEMReader.H"
#include "uniformDimensionedFields.H"

namespace Foam
{
    defineTypeNameAndDebug(immersedDEMState, 0);
}


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
        properties_, mesh.time().constant()/"triSurface", g.value()
    );
    Info<< "immersedDEM: " << nBodies() << " bodies, "
        << dem_->materials().size() << " materials" << nl << endl;
}


Foam::immersedDEMState::~immersedDEMState() = default;


Foam::label Foam::immersedDEMState::nBodies() const
{
    label n = 0;
    for (size_t i = 0; i < dem_->bodies().size(); ++i)
    {
        if (!dem_->isWall(int(i))) ++n;
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
