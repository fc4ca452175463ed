#include "immersedDEMState.H"
#include "immersedDEMReader.H"
#include "uniformDimensionedFields.H"
#include "boxFraction.H"
#include "indexedOctree.H"
#include "treeDataCell.H"
#include "treeBoundBox.H"

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
        << dem_->materials().size() << " materials" << endl;
    const label n = project();
    Info<< "immersedDEM: projected on " << returnReduce(n, sumOp<label>())
        << " cells" << nl << endl;
}


Foam::label Foam::immersedDEMState::project()
{
    using namespace immersedDEM;

    scalarField& lambda = lambda_.primitiveFieldRef();
    vectorField& Uib = Uib_.primitiveFieldRef();
    lambda = 0;
    Uib = Zero;

    const indexedOctree<treeDataCell>& tree = mesh_.cellTree();
    const pointField& points = mesh_.points();
    const labelListList& cellPoints = mesh_.cellPoints();
    const vectorField& C = mesh_.cellCentres();

    label nCells = 0;
    const auto& bodies = dem_->bodies();
    for (size_t bi = 0; bi < bodies.size(); ++bi)
    {
        if (dem_->isWall(int(bi))) continue;
        const rigidBody& b = bodies[bi];
        const axisAlignedBox wb = b.geometry->worldBox(b.pose);
        const treeBoundBox bb
        (
            point(wb.min.x(), wb.min.y(), wb.min.z()),
            point(wb.max.x(), wb.max.y(), wb.max.z())
        );
        for (const label i : tree.findBox(bb))
        {
            const label celli = tree.shapes().cellLabels()[i];
            // The cell's bounding box stands in for the cell (exact for
            // the axis-aligned hexahedra of blockMesh and snappyHexMesh)
            vec3 lo = vec3::Constant(GREAT), hi = vec3::Constant(-GREAT);
            for (const label pi : cellPoints[celli])
            {
                const vec3 p = immersedDEMReader::toCore(points[pi]);
                lo = lo.cwiseMin(p);
                hi = hi.cwiseMax(p);
            }
            const scalar f = boxFraction::of(*b.geometry, b.pose, lo, hi, 1);
            if (f > lambda[celli])
            {
                if (lambda[celli] == 0) ++nCells;
                lambda[celli] = f;
                Uib[celli] = immersedDEMReader::toFoam
                (
                    b.pointVelocity(immersedDEMReader::toCore(C[celli]))
                );
            }
        }
    }
    lambda_.correctBoundaryConditions();
    Uib_.correctBoundaryConditions();
    return nCells;
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
