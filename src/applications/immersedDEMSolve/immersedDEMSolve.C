/*---------------------------------------------------------------------------*\
Application
    immersedDEMSolve

Group
    grpImmersedDEMApplications

Description
    Runs the DEM of constant/immersedDEMProperties with no fluid: the same
    bodies, insertions, walls, contact models and outputs as a coupled case
    (gravity from constant/g if present), so a coupled case's own dictionary
    runs as it is: its mesh is read when it has one (walls of type patch),
    and the function objects of its controlDict (the coupled immersedDEM)
    are not run (-withFunctionObjects runs them). The case's
    system/controlDict gives the time: startTime, endTime, deltaT (the
    output interval of the tables; the DEM takes its own sub-steps within
    it) and the write controls (the VTK of the bodies).

    Log: the DEM step and what set it; progress (simulated time, DEM steps
    per second, estimated time left) every -progress seconds of wall time
    (default 5); at the end the seconds per part and the largest overlap
    and speed seen.

    Outputs, in postProcessing/immersedDEMSolve/<startTime>/: bodies.dat,
    contacts.dat and VTK/bodies_<time>.vtk with VTK/bodies.vtk.series.
    Nothing goes into the case's time folders, so the coupled run that
    follows starts where its controlDict says (with -withFunctionObjects,
    OpenFOAM writes their state at each write time).

    Parallel (mpirun -np N immersedDEMSolve -parallel): every rank holds
    every body and the ranks share out the pair evaluations; the loads are
    added in the order of the pairs, so the trajectories are the serial
    run's, bit for bit. A case without a mesh needs no decomposition; a
    case with one (walls of type patch) is decomposed first (decomposePar),
    each rank reading its part of the walls. The master writes the outputs.

Usage
    immersedDEMSolve [-case dir] [-progress seconds] [-withFunctionObjects]
        [-parallel]
\*---------------------------------------------------------------------------*/

#include "argList.H"
#include "Time.H"
#include "IOdictionary.H"
#include "uniformDimensionedFields.H"
#include "dimensionedVector.H"
#include "dimensionSets.H"
#include "OSspecific.H"
#include "polyMesh.H"
#include "Switch.H"

#include "immersedDEMReader.H"
#include "pstreamCommunicator.H"
#include "demWorkLine.H"
#include "immersedDEMStreams.H"
#include "demOutput.H"
#include "runSummary.H"
#include "coreError.H"
#include "timeStepExplanation.H"

#include <algorithm>
#include <cmath>
#include <chrono>
#include <memory>

using namespace Foam;

static label nWalls(const immersedDEM::demSolver& dem)
{
    label n = 0;
    for (size_t i = 0; i < dem.bodies().size(); ++i)
    {
        if (dem.isWall(int(i))) ++n;
    }
    return n;
}

int main(int argc, char *argv[])
{
    argList::addNote
    (
        "Run the bodies of constant/immersedDEMProperties with no fluid"
    );
    // Parallel: a case without a mesh runs undecomposed (no processor
    // folders); a case with a mesh is checked below
    argList::noCheckProcessorDirectories();
    // The coupled function object of a coupled case's controlDict needs
    // the fluid: not run here unless asked for
    argList::noFunctionObjects(true);
    argList::addOption
    (
        "progress", "seconds",
        "Wall-clock interval of the progress lines (default 5)"
    );

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

    using wallClock = std::chrono::steady_clock;
    auto seconds = [](wallClock::time_point a, wallClock::time_point b)
    {
        return std::chrono::duration<double>(b - a).count();
    };
    const auto wallStart = wallClock::now();
    const scalar progressInterval = args.getOrDefault<scalar>("progress", 5);
    if (!(progressInterval > 0))
    {
        FatalErrorInFunction
            << "Option -progress " << progressInterval << ": it must be > 0 seconds"
            << exit(FatalError);
    }

    // The case's mesh, if it has one: walls of type patch take its faces
    // (in parallel each processor's part; the reader gathers them)
    auto hasMesh = [&runTime](const fileName& caseDir)
    {
        return
            isFile(caseDir/runTime.constant()/polyMesh::meshSubDir/"faces")
         || isDir(caseDir/runTime.timeName()/polyMesh::meshSubDir);
    };
    std::unique_ptr<polyMesh> mesh;
    const bool meshHere = hasMesh(runTime.path());
    if (Pstream::parRun())
    {
        // Every rank the same: all read their part, or none does
        const bool meshGlobal = hasMesh(runTime.globalPath());
        bool all = meshHere, any = meshHere;
        reduce(all, andOp<bool>());
        reduce(any, orOp<bool>());
        if (any && !all)
        {
            FatalErrorInFunction
                << "Case " << runTime.globalPath() << ": some processor folders"
                << " have a mesh and some do not; decompose the case again"
                << " (decomposePar -force) for " << Pstream::nProcs()
                << " processors" << exit(FatalError);
        }
        if (!any && meshGlobal)
        {
            FatalErrorInFunction
                << "Case " << runTime.globalPath() << " has a mesh ("
                << runTime.constant()/polyMesh::meshSubDir << ") but no processor"
                << " folders with its parts: run decomposePar first (its walls"
                << " of type patch come from the decomposed mesh), or run"
                << " serially" << exit(FatalError);
        }
    }
    if (meshHere)
    {
        Info<< "Reading the mesh for walls of type patch" << endl;
        mesh.reset
        (
            new polyMesh
            (
                IOobject
                (
                    polyMesh::defaultRegion, runTime.timeName(), runTime,
                    IOobject::MUST_READ
                )
            )
        );
    }

    Info<< "Reading " << properties.objectPath() << endl;
    const fileName surfaceDir = runTime.globalPath()/runTime.constant()/"triSurface";
    std::vector<immersedDEM::bodyStream> newStreams;
    auto dem = immersedDEMReader::read
    (
        properties, surfaceDir, g.value(), mesh.get(), &newStreams
    );
    dem->setTime(runTime.value());
    if (Pstream::parRun())
    {
        Info<< "The DEM's pair evaluations shared by " << Pstream::nProcs()
            << " processors" << endl;
        dem->setCommunicator
        (
            std::make_shared<immersedDEMParallel::pstreamCommunicator>()
        );
    }
    immersedDEMReader::initialOverlaps(*dem, properties.objectPath());
    immersedDEMReader::reportMessages(*dem);
    // Insertion over time and removal: the bodies due at the start now,
    // then after every output interval
    immersedDEMStreams streams
    (
        properties, surfaceDir, std::move(newStreams), mesh.get(), *dem
    );
    if (streams.active())
    {
        streams.update(*dem, runTime.value());
    }
    const scalar setupSeconds = seconds(wallStart, wallClock::now());

    const fileName outDir =
        runTime.globalPath()/"postProcessing"/"immersedDEMSolve"/runTime.timeName();
    // The outputs: the master's (every rank holds the same bodies)
    std::unique_ptr<immersedDEM::demOutput> out;
    try
    {
        dem->computeContacts();
        if (Pstream::master())
        {
            // A rerun writes bodies_<startTime>.dat next to an earlier
            // run's bodies.dat (OpenFOAM's writeFile convention), never
            // appends to it
            out.reset(new immersedDEM::demOutput(outDir, runTime.timeName()));
            Info<< "Writing " << out->bodiesFile() << " and "
                << out->contactsFile() << endl;
            out->writeBodies(runTime.value(), *dem);
            out->writeContacts(runTime.value(), *dem);
            out->writeVTK(runTime.value(), *dem);
        }
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

    scalar outputSeconds = seconds(wallStart, wallClock::now()) - setupSeconds;
    scalar demSeconds = 0;

    // Extremes seen, for the summary
    immersedDEM::runSummary summary;
    summary.track(*dem);

    const scalar t0 = runTime.value();
    const scalar tEnd = runTime.endTime().value();
    auto lastReport = wallClock::now();
    // Steps per second: whole numbers from 100 on, two decimals below
    // (a slow run shows 1.63, not 1)
    auto stepRate = [](const scalar r)
    {
        return r >= 100 ? scalar(label(r)) : std::round(100*r)/100;
    };
    const auto loopStart = lastReport;
    long stepsAtReport = 0, steps = 0;
    auto progress = [&]()
    {
        summary.track(*dem);
        ++steps;
        const auto now = wallClock::now();
        const scalar since = seconds(lastReport, now);
        if (since < progressInterval) return;
        const scalar t = dem->time();
        const scalar elapsed = seconds(loopStart, now);
        const scalar rate = (t - t0)/max(elapsed, VSMALL);
        Info<< "Progress: t = " << t << " s of " << tEnd << " ("
            << label(100*(t - t0)/max(tEnd - t0, VSMALL)) << "%), "
            << stepRate((steps - stepsAtReport)/since) << " DEM steps/s, "
            << dem->bodies().size() << " bodies and walls, "
            << dem->contacts().size() << " contacts, ETA "
            << label((tEnd - t)/max(rate, VSMALL)) << " s (wall "
            << label(elapsed) << " s)" << endl;
        lastReport = now;
        stepsAtReport = steps;
    };

    // Time::loop runs the function objects and, at every write time,
    // writes their state (uniform/functionObjects/functionObjectProperties)
    // into a time folder of the case, even with the function objects off:
    // a coupled run with startFrom latestTime would then start from a
    // folder with no fields. Without function objects, the time is
    // advanced by hand and nothing is written into the case's time folders
    const bool withFunctionObjects = runTime.functionObjects().status();
    auto nextStep = [&runTime, withFunctionObjects]() -> bool
    {
        if (withFunctionObjects)
        {
            return runTime.loop();
        }
        if (runTime.value() >= runTime.endTime().value() - 0.5*runTime.deltaTValue())
        {
            return false;
        }
        ++runTime;
        return true;
    };

    Info<< "\nStarting time loop\n" << endl;
    while (nextStep())
    {
        label nSteps = 0;
        auto a = wallClock::now();
        try
        {
            nSteps = dem->advance(runTime.deltaTValue(), progress);
        }
        catch (const immersedDEM::coreError& err)
        {
            FatalErrorInFunction
                << "Time " << runTime.timeName() << ": " << err.what() << exit(FatalError);
        }
        if (streams.active())
        {
            streams.update(*dem, runTime.value());
        }
        if (mesh)
        {
            // A body that left the mesh (and removal did not take out)
            const labelList in = immersedDEMStreams::inMesh(*mesh, *dem);
            forAll(in, i)
            {
                if (in[i]) continue;
                const auto& bi = dem->bodies()[i];
                FatalErrorInFunction
                    << "Time " << runTime.timeName() << ": body '"
                    << bi.name.c_str() << "' left the mesh (centre "
                    << immersedDEMReader::toFoam(bi.pose.position())
                    << ", velocity " << immersedDEMReader::toFoam(bi.velocity)
                    << " m/s, mesh bounds " << mesh->bounds() << "). If bodies"
                    << " may leave, add removal { leavingMesh yes; } to "
                    << properties.objectPath() << "; if this one should not"
                    << " have, see the log above for what drove it out"
                    << exit(FatalError);
            }
        }
        auto b = wallClock::now();
        demSeconds += seconds(a, b);
        scalar largest = 0;
        for (const auto& c : dem->contacts())
        {
            largest = std::max(largest, c.region.volume);
        }
        Info<< "Time = " << runTime.timeName()
            << "  DEM steps " << nSteps
            << ", bodies " << (dem->bodies().size() - nWalls(*dem))
            << ", contacts " << dem->contacts().size()
            << ", largest overlap " << largest << " m3"
            << ", kinetic energy " << dem->kineticEnergy() << " J"
            << ", DEM step "
            << immersedDEM::timeStepExplanation::lastStep(*dem).c_str() << endl;
        immersedDEMReader::reportMessages(*dem);

        if (out)
        {
            out->writeBodies(runTime.value(), *dem);
            out->writeContacts(runTime.value(), *dem);
            if (runTime.writeTime())
            {
                out->writeVTK(runTime.value(), *dem);
            }
        }
        outputSeconds += seconds(b, wallClock::now());
    }

    const auto& w = dem->work();
    immersedDEM::runSummary::seconds parts;
    parts.setup = setupSeconds;
    immersedDEM::runSummary::demParts(*dem, demSeconds, parts);
    parts.output = outputSeconds;
    parts.total = seconds(wallStart, wallClock::now());
    Info<< nl << immersedDEMParallel::demWorkLine(*dem).c_str() << nl << nl
        << summary.text(parts, runTime.value() - t0, w.steps, false).c_str() << nl
        << nl << "ExecutionTime = " << runTime.elapsedCpuTime() << " s"
        << nl << "End\n" << endl;

    return 0;
}
