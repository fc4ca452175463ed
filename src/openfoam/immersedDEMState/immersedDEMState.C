#include "immersedDEMState.H"
#include "dictionaryChecks.H"
#include "immersedDEMReader.H"
#include "uniformDimensionedFields.H"
#include "coreConversion.H"
#include "pstreamCommunicator.H"

using namespace immersedDEM;

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
    projection_(mesh)
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
    Info<< "immersedDEM: reading " << immersedDEMChecks::caseFile(properties_) << endl;
    const fileName surfaceDir = mesh.time().globalPath()/mesh.time().constant()/"triSurface";
    std::vector<bodyStream> streams;
    dem_ = immersedDEMReader::read
    (
        properties_, surfaceDir, g.value(), &mesh, &streams, &settings_
    );
    dem_->setTime(mesh.time().value());
    // In parallel the ranks share out the DEM's pair evaluations (every
    // rank holds every body; the trajectories stay the serial run's)
    if (Pstream::parRun())
    {
        dem_->setCommunicator
        (
            std::make_shared<immersedDEMParallel::pstreamCommunicator>()
        );
    }
    streams_.reset
    (
        new immersedDEMStreams(properties_, surfaceDir, std::move(streams), &mesh, *dem_)
    );
    Info<< "immersedDEM: " << nBodies() << " bodies, "
        << dem_->materials().size() << " materials" << endl;

    coupling_.reset(new immersedFluidCoupling(*dem_));

    restarted_ = readRestart();
    if (!restarted_)
    {
        immersedDEMReader::initialOverlaps(*dem_, immersedDEMChecks::caseFile(properties_));
        immersedDEMReader::reportMessages(*dem_);
    }
    if (!restarted_ && streams_->active())
    {
        // The bodies due at the start (a restart has them: the run that
        // wrote it inserted them after its step to this time)
        const immersedDEMStreams::change c = streams_->update(*dem_, mesh.time().value());
        if (c.any())
        {
            coupling_->bodiesChanged(*dem_, c.kept, c.firstNew);
        }
    }

    setupSeconds_ = clock_.elapsedTime();
    const label nCells = project();
    Info<< "immersedDEM: projected on " << returnReduce(nCells, sumOp<label>())
        << " cells;";
    projection_.reportProjectedVolumes(*dem_);
    Info<< endl;
    const List<scalar>& projectedVolume = projection_.projectedVolume();
    forAll(projectedVolume, i)
    {
        const rigidBody& b = dem_->bodies()[i];
        // 2D: a fixed or prescribed sphere is kept whole (its section in
        // the slab is what the fluid sees)
        const bool slabSection = mesh.nSolutionD() < 3 && !b.dynamic();
        if
        (
            !dem_->isWall(i) && !slabSection
         && projectedVolume[i] < 0.5*b.geometry->volume()
        )
        {
            WarningInFunction
                << "Body '" << b.name << "' of " << immersedDEMChecks::caseFile(properties_)
                << " lies mostly outside the mesh (projected "
                << projectedVolume[i]/b.geometry->volume()
                << " of its volume): the fluid does not see it there" << endl;
        }
    }
}


Foam::immersedDEMState::~immersedDEMState() = default;


void Foam::immersedDEMState::takeTimings(scalar& projection, scalar& forcing)
{
    projection = projection_.takeSeconds();
    forcing = forcingSeconds_ + coupling_->takeSeconds();
    forcingSeconds_ = 0;
}


Foam::immersedDEMStreams::change Foam::immersedDEMState::updateBodies
(
    const scalar t,
    const volVectorField* U
)
{
    immersedDEMStreams::change c;
    if (!streams_->active())
    {
        return c;
    }
    c = streams_->update(*dem_, t);
    if (c.any())
    {
        coupling_->bodiesChanged(*dem_, c.kept, c.firstNew);
        project();
        if (U && c.nNew > 0)
        {
            coupling_->setNewInnerMomentum(projection_, *dem_, *U, c.firstNew);
        }
        const List<scalar>& pv = projection_.projectedVolume();
        for (label i = c.firstNew; i < label(dem_->bodies().size()); ++i)
        {
            const rigidBody& b = dem_->bodies()[i];
            Info<< "immersedDEM: body " << b.name.c_str() << " projected: "
                << (i < pv.size() ? pv[i] : scalar(0)) << " m3 of its "
                << b.geometry->volume() << " m3 in the mesh" << endl;
        }
    }
    return c;
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
