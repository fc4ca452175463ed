/*---------------------------------------------------------------------------*\
Application
    immersedDEMSolve

Group
    grpImmersedDEMApplications

Description
    Runs the DEM of constant/immersedDEMProperties with no fluid: the same
    bodies, walls, contact models and outputs as a coupled case (gravity
    from constant/g if present). The case's system/controlDict gives the
    time: startTime, endTime, deltaT (the output interval of the tables;
    the DEM takes its own sub-steps within it) and the write controls (the
    VTK of the bodies).

    Outputs, in postProcessing/immersedDEMSolve/<startTime>/: bodies.dat,
    contacts.dat and VTK/bodies_<time>.vtk with VTK/bodies.vtk.series.

Usage
    immersedDEMSolve [-case dir]
\*---------------------------------------------------------------------------*/

#include "argList.H"
#include "Time.H"
#include "IOdictionary.H"
#include "uniformDimensionedFields.H"
#include "dimensionedVector.H"
#include "dimensionSets.H"
#include "OSspecific.H"

#include "immersedDEMReader.H"
#include "demOutput.H"
#include "coreError.H"

#include <algorithm>
#include <cmath>

using namespace Foam;

int main(int argc, char *argv[])
{
    argList::addNote
    (
        "Run the bodies of constant/immersedDEMProperties with no fluid"
    );
    argList::noParallel();

    #include "setRootCase.H"
    #include "createTime.H"

    // The time loop must end: a step that is not positive, or so small
    // that the run would not get anywhere, is an error
    {
        const scalar dt = runTime.deltaTValue();
        const scalar span = runTime.endTime().value() - runTime.startTime().value();
        if (!(dt > 0) || !std::isfinite(dt))
        {
            FatalIOErrorInFunction(runTime.controlDict())
                << "Keyword 'deltaT' in " << runTime.controlDict().name()
                << " is " << dt << ": it must be > 0 (the interval of the"
                << " output rows; the DEM takes its own steps within it)" << nl
                << exit(FatalIOError);
        }
        const scalar maxSteps = 1e9;
        if (span/dt > maxSteps || runTime.value() + dt == runTime.value())
        {
            FatalIOErrorInFunction(runTime.controlDict())
                << "Keyword 'deltaT' in " << runTime.controlDict().name()
                << " is " << dt << ": from startTime " << runTime.startTime().value()
                << " to endTime " << runTime.endTime().value() << " that is "
                << span/dt << " steps, more than " << maxSteps
                << " (or too small to change the time at all)" << nl
                << exit(FatalIOError);
        }
    }

    const IOdictionary properties
    (
        IOobject
        (
            "immersedDEMProperties", runTime.constant(), runTime,
            IOobject::MUST_READ, IOobject::NO_WRITE
        )
    );
    const uniformDimensionedVectorField g
    (
        IOobject
        (
            "g", runTime.constant(), runTime,
            IOobject::READ_IF_PRESENT, IOobject::NO_WRITE, false
        ),
        dimensionedVector(dimAcceleration, Zero)
    );

    Info<< "Reading " << properties.objectPath() << endl;
    auto dem = immersedDEMReader::read
    (
        properties, runTime.globalPath()/runTime.constant()/"triSurface", g.value()
    );
    dem->setTime(runTime.value());

    const fileName outDir =
        runTime.globalPath()/"postProcessing"/"immersedDEMSolve"/runTime.timeName();
    std::unique_ptr<immersedDEM::demOutput> out;
    try
    {
        // A rerun writes bodies_<startTime>.dat next to an earlier run's
        // bodies.dat (OpenFOAM's writeFile convention), never appends to it
        out.reset(new immersedDEM::demOutput(outDir, runTime.timeName()));
        Info<< "Writing " << out->bodiesFile() << " and "
            << out->contactsFile() << endl;
        dem->computeContacts();
        out->writeBodies(runTime.value(), *dem);
        out->writeContacts(runTime.value(), *dem);
        out->writeVTK(runTime.value(), *dem);
    }
    catch (const immersedDEM::coreError& err)
    {
        FatalErrorInFunction << err.what() << exit(FatalError);
    }

    // Sub-steps of one output interval: within the DEM's counter
    if (runTime.deltaTValue()/dem->timeStep() > 1e9)
    {
        FatalIOErrorInFunction(runTime.controlDict())
            << "Keyword 'deltaT' in " << runTime.controlDict().name() << " is "
            << runTime.deltaTValue() << " s: with the DEM step " << dem->timeStep()
            << " s that is more than 1e9 DEM steps per output interval;"
            << " reduce deltaT" << nl << exit(FatalIOError);
    }

    Info<< "\nStarting time loop\n" << endl;
    while (runTime.loop())
    {
        label nSteps = 0;
        try
        {
            nSteps = dem->advance(runTime.deltaTValue());
        }
        catch (const immersedDEM::coreError& err)
        {
            FatalErrorInFunction
                << "Time " << runTime.timeName() << ": " << err.what() << exit(FatalError);
        }
        scalar maxVolume = 0;
        for (const auto& c : dem->contacts())
        {
            maxVolume = std::max(maxVolume, c.region.volume);
        }
        Info<< "Time = " << runTime.timeName()
            << "  DEM steps " << nSteps
            << ", contacts " << dem->contacts().size()
            << ", largest overlap " << maxVolume << " m3"
            << ", kinetic energy " << dem->kineticEnergy() << " J" << endl;

        out->writeBodies(runTime.value(), *dem);
        out->writeContacts(runTime.value(), *dem);
        if (runTime.writeTime())
        {
            out->writeVTK(runTime.value(), *dem);
        }
    }

    const auto& w = dem->work();
    Info<< "\nDEM steps " << w.steps << ", pair evaluations " << w.pairEvaluations
        << ", queries " << w.queries << ", contact time " << w.contactSeconds << " s"
        << nl << "ExecutionTime = " << runTime.elapsedCpuTime() << " s"
        << nl << "End\n" << endl;

    return 0;
}
