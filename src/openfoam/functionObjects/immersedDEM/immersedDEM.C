#include "immersedDEM.H"
#include "immersedDEMState.H"
#include "dictionaryChecks.H"
#include "demOutput.H"
#include "demWorkLine.H"
#include "runSummary.H"
#include "coreError.H"
#include "clockTime.H"
#include "timeStepExplanation.H"
#include "immersedDEMReader.H"
#include "addToRunTimeSelectionTable.H"
#include <cmath>
#include <cstdio>
#include <string>

namespace
{

// A figure of the per-step line to 4 significant digits, whatever the log
// stream's precision (controlDict's writePrecision: 17 in the cases that
// restart bit for bit, which printed 0.17549714500000002)
std::string figure(const double x)
{
    char b[32];
    std::snprintf(b, sizeof b, "%.4g", x);
    return b;
}

} // End anonymous namespace

namespace Foam
{
namespace functionObjects
{
    defineTypeNameAndDebug(immersedDEM, 0);
    addToRunTimeSelectionTable(functionObject, immersedDEM, dictionary);
}
}

const Foam::word Foam::functionObjects::immersedDEM::registrationName
(
    "immersedDEM:functionObject"
);


void Foam::functionObjects::immersedDEM::registerInRegion(const dictionary& dict)
{
    if (const IOdictionary* other = mesh_.findObject<IOdictionary>(registrationName))
    {
        // Both would advance the same bodies: twice the DEM per CFD step
        FatalIOErrorInFunction(dict)
            << "Function objects '" << other->get<word>("name") << "' and '"
            << name() << "' in " << time_.controlDict().name()
            << " are both of type immersedDEM for region " << mesh_.name()
            << ": each would advance the same bodies. Keep one" << nl
            << exit(FatalIOError);
    }
    registration_.reset
    (
        new IOdictionary
        (
            IOobject
            (
                registrationName, time_.constant(), mesh_,
                IOobject::NO_READ, IOobject::NO_WRITE, true
            )
        )
    );
    registration_->add("name", name());
}


void Foam::functionObjects::immersedDEM::checkBodies(const scalar deltaT)
{
    const auto& bodies = state_.dem().bodies();
    const label n = bodies.size();

    // The size of the smallest cell each body covers (the cells its
    // projection set: the cost follows the bodies); GREAT where none
    const immersedBoundaryProjection& projection = state_.projection();
    const labelList& bodyOf = projection.bodyOf();
    const scalarField& V = mesh_.V();
    List<scalar> h(n, GREAT);
    for (const label celli : projection.touched())
    {
        const label bi = bodyOf[celli];
        if (bi >= 0 && bi < n)
        {
            h[bi] = min(h[bi], cbrt(V[celli]));
        }
    }
    Pstream::listCombineGather(h, minEqOp<scalar>());
    Pstream::listCombineScatter(h);

    // The lubrication's activation distance is measured in these cells
    for (label i = 0; i < n; ++i)
    {
        state_.dem().bodies()[i].fluidCellSize = h[i] < GREAT ? h[i] : 0;
    }

    const List<scalar>& projectedVolume = projection.projectedVolume();
    if (debug)
    {
        // (DebugSwitches { immersedDEM 1; }: each body's projected volume
        // every step, e.g. across periodic boundaries)
        Info<< "immersedDEM: time " << time_.timeName() << ';';
        projection.reportProjectedVolumes(state_.dem());
    }
    for (label i = 0; i < n; ++i)
    {
        const ::immersedDEM::rigidBody& b = bodies[i];
        if (state_.dem().isWall(i))
        {
            continue;
        }
        const ::immersedDEM::vec3& p = b.pose.position();
        const vector x(p.x(), p.y(), p.z());

        // Outside: (next to) nothing of it projected on the mesh. The
        // fluid no longer sees it, and the DEM alone would carry it on
        // through nothing: an error, unless removal takes such bodies out
        // (then it is gone before this check)
        if
        (
            i < projectedVolume.size()
         && projectedVolume[i] < 1e-6*b.geometry->volume()
        )
        {
            FatalErrorInFunction
                << "Function object " << name() << ", time " << time_.timeName()
                << ": body '" << b.name.c_str() << "' left the mesh (centre "
                << x << ", velocity " << coreConversion::toFoam(b.velocity)
                << " m/s, mesh bounds " << mesh_.bounds() << "): the fluid no"
                << " longer sees it. If bodies may leave, add"
                << " removal { leavingMesh yes; } to "
                << immersedDEMChecks::caseFile(state_.properties()) << "; if this one should"
                << " not have, see the log above for what drove it out"
                << exit(FatalError);
        }
        // Partly outside (cut by an outlet, an inlet or a symmetry plane
        // that is not one of its walls): the part outside is not in the
        // fluid. Crossing an outlet or an inlet the body keeps its inner
        // fluid's momentum (bodyFluidSums' outflow) and is removed once its
        // centre has left, but the fluid's load on the part outside is
        // missing (one cut in half by a symmetry plane falls 30% too fast).
        // Said once, with the remedy, until it is back inside
        const scalar inside =
            i < projectedVolume.size()
          ? projectedVolume[i]/b.geometry->volume() : 1;
        if (b.dynamic() && inside < 0.9)
        {
            if (warnedOutside_.insert(b.name).second)
            {
                WarningInFunction
                    << "Function object " << name() << ", time "
                    << time_.timeName() << ": body '" << b.name.c_str()
                    << "' is only " << label(std::round(1000*inside))/10
                    << '.' << label(std::round(1000*inside))%10
                    << "% inside the fluid"
                    << " mesh (centre " << x << ", mesh bounds "
                    << mesh_.bounds() << "). The fluid has no load on the"
                    << " part outside. Crossing an outlet or an inlet that is"
                    << " expected; elsewhere start bodies inside the mesh,"
                    << " and model a symmetry plane a body may touch as one"
                    << " of its walls (in "
                    << immersedDEMChecks::caseFile(state_.properties()) << ")"
                    << endl;
            }
        }
        else if (inside > 0.95)
        {
            warnedOutside_.erase(b.name);
        }
        if (h[i] >= GREAT || !(deltaT > 0))
        {
            continue;
        }

        // Body Courant number against the smallest cell it covers
        const scalar r = b.geometry->boundingRadius();
        const scalar speed = b.velocity.norm() + b.angularVelocity.norm()*r;
        const scalar Co = speed*deltaT/h[i];
        if (!(Co <= maxBodyCourant_))
        {
            FatalErrorInFunction
                << "Function object " << name() << ", time " << time_.timeName()
                << ": body '" << b.name.c_str() << "' moves more than "
                << maxBodyCourant_ << " cell per CFD step: speed " << speed
                << " m/s (|v| + |omega| r), cell size " << h[i]
                << " m (the smallest it covers), CFD step " << deltaT
                << " s: body Courant number " << Co << ". The fluid cannot"
                << " follow it. Reduce deltaT (or maxCo with adjustTimeStep"
                << " yes), or, if the speed is wrong, see the log above for"
                << " what drove it; maxBodyCourant (system/controlDict, this"
                << " function object) allows more" << exit(FatalError);
        }
    }
}


void Foam::functionObjects::immersedDEM::checkRun(const scalar deltaT)
{
    // The scales of the start: the first step, and the largest of the
    // fluid's speed, the bodies' speeds and the speed of a free fall over
    // the mesh's size
    const auto& bodies = state_.dem().bodies();
    const volVectorField* U = mesh_.findObject<volVectorField>(UName_);
    if (!(referenceDeltaT_ > 0))
    {
        referenceDeltaT_ = deltaT;
        scalar s = U ? gMax(mag(U->primitiveField())) : 0;
        forAll(bodies, i)
        {
            s = max(s, scalar(bodies[i].velocity.norm()));
        }
        const scalar g = state_.settingsRead().gravity.norm();
        s = max(s, sqrt(2*g*mag(mesh_.bounds().span())));
        referenceSpeed_ = s;
    }
    if (deltaT < 1e-6*referenceDeltaT_)
    {
        FatalErrorInFunction
            << "Function object " << name() << ", time " << time_.timeName()
            << ": the CFD step has collapsed to " << deltaT << " s, below"
            << " 1e-6 of the first step " << referenceDeltaT_ << " s: the run"
            << " has gone bad (velocities of the fluid or the bodies far"
            << " beyond the case's scales). See the log above for the first"
            << " body or field that grew" << exit(FatalError);
    }
    const scalar bound = 100*max(referenceSpeed_, SMALL);
    forAll(bodies, i)
    {
        if (state_.dem().isWall(i)) continue;
        // (its surface's fastest point: spin counts)
        const scalar v =
            bodies[i].velocity.norm()
          + bodies[i].angularVelocity.norm()*bodies[i].geometry->boundingRadius();
        if (!(v <= bound))
        {
            FatalErrorInFunction
                << "Function object " << name() << ", time " << time_.timeName()
                << ": body '" << bodies[i].name.c_str() << "' moves at " << v
                << " m/s (abs(v) + abs(omega) r), more than 100 times the case's speed scale "
                << referenceSpeed_ << " m/s (the largest of the fluid's and"
                << " the bodies' speeds at the start and of a free fall over"
                << " the mesh): the run has gone bad. See the log above for"
                << " where its speed grew" << exit(FatalError);
        }
    }
}


Foam::functionObjects::immersedDEM::immersedDEM
(
    const word& name,
    const Time& runTime,
    const dictionary& dict
)
:
    fvMeshFunctionObject(name, runTime, dict),
    state_(immersedDEMState::New(mesh_)),
    rhoInf_(0),
    UName_("U")
{
    summary_.reset(new ::immersedDEM::runSummary());
    startTime_ = time_.value();
    read(dict);
    registerInRegion(dict);
    if (Pstream::master())
    {
        const word startTimeName = time_.timeName(time_.startTime().value());
        const fileName dir =
            time_.globalPath()/"postProcessing"/name/startTimeName;
        try
        {
            output_.reset(new ::immersedDEM::demOutput(dir, startTimeName));
            Info<< type() << ' ' << name << ": writing "
                << output_->bodiesFile().c_str() << " and "
                << output_->contactsFile().c_str() << endl;
            output_->writeBodies(time_.value(), state_.dem());
            output_->writeVTK(time_.value(), state_.dem());
        }
        catch (const ::immersedDEM::coreError& err)
        {
            FatalErrorInFunction
                << "Function object " << name << ": " << err.what()
                << exit(FatalError);
        }
    }
    {
        // OpenFOAM turns an error while a function object is constructed
        // into a warning and runs on without it; a body the fluid cannot
        // follow from the start must stop the run
        const bool throwing = FatalError.dontThrowExceptions();
        checkBodies(time_.deltaTValue());
        FatalError.throwExceptions(throwing);
    }
    summary_->track(state_.dem());
    setupSeconds_ = runClock_.elapsedTime();
}


Foam::functionObjects::immersedDEM::~immersedDEM() = default;


bool Foam::functionObjects::immersedDEM::read(const dictionary& dict)
{
    fvMeshFunctionObject::read(dict);
    immersedDEMChecks::allowOnly
    (
        dict,
        {
            "type", "libs", "enabled", "log", "region", "timeStart", "timeEnd",
            "executeControl", "executeInterval", "writeControl", "writeInterval",
            "rhoInf", "U", "nu", "maxFourier", "maxSubSteps", "writeContacts",
            "maxBodyCourant",
            // (the former stabilisation's: an error below that says so)
            "addedMassCoefficient", "measureAddedMass", "impactInertia"
        }
    );
    for (const word old : {"addedMassCoefficient", "measureAddedMass", "impactInertia"})
    {
        if (dict.found(old))
        {
            FatalIOErrorInFunction(dict)
                << "Keyword '" << old << "' in " << dict.name()
                << " belonged to the explicit coupling's stabilisation, which"
                << " is gone: the coupling now takes the fluid's answer to a"
                << " body's change of motion implicitly and needs no setting"
                << " (src/core/coupling/fluidImpedance). Remove the keyword"
                << nl << exit(FatalIOError);
        }
    }
    contactsEverySubStep_ =
        immersedDEMChecks::oneOfOrDefault(dict, "writeContacts", {"step", "subStep"}, "step") == "subStep";
    maxSubSteps_ = immersedDEMChecks::positiveOrDefault(dict, "maxSubSteps", 1e5);
    maxBodyCourant_ = immersedDEMChecks::positiveOrDefault(dict, "maxBodyCourant", 1);
    maxFourier_ = immersedDEMChecks::inRangeOrDefault(dict, "maxFourier", 0, 1e6, 4);
    rhoInf_ = immersedDEMChecks::positive(dict, "rhoInf");
    state_.setFluidDensity(rhoInf_);
    UName_ = dict.getOrDefault<word>("U", "U");
    readViscosity(dict);
    setViscosity();
    return true;
}


void Foam::functionObjects::immersedDEM::readViscosity(const dictionary& dict)
{
    // The fluid's kinematic viscosity: the keyword, or the solver's
    // laminar nu (singlePhaseTransportModel)
    if (dict.found("nu"))
    {
        nu_ = immersedDEMChecks::positive(dict, "nu");
        return;
    }
    const word transport("transportProperties");
    const IOdictionary* t = mesh_.findObject<IOdictionary>(transport);
    if (!t || !t->found("nu"))
    {
        FatalIOErrorInFunction(dict)
            << "Function object " << name() << ": the coupling needs the"
            << " fluid's kinematic viscosity, and this solver has no 'nu' in"
            << " constant/" << transport << ". Give it as 'nu' in "
            << dict.name() << nl << exit(FatalIOError);
    }
    nu_ = dimensionedScalar("nu", dimViscosity, *t).value();
    if (!(nu_ > 0))
    {
        FatalIOErrorInFunction(*t)
            << "Keyword 'nu' in " << immersedDEMChecks::caseFile(*t) << " is " << nu_
            << ": it must be > 0" << nl << exit(FatalIOError);
    }
}


void Foam::functionObjects::immersedDEM::setViscosity()
{
    // The lubrication below the resolved gap needs the fluid's dynamic
    // viscosity: rhoInf times the solver's laminar nu
    if (!state_.settingsRead().lubrication.active)
    {
        state_.dem().setFluidViscosity(0);
        return;
    }
    state_.dem().setFluidViscosity(rhoInf_*nu_);
}


bool Foam::functionObjects::immersedDEM::execute()
{
    const scalar deltaT = time_.deltaTValue();
    // (before the step's DEM: its sub-step count would fail first, with a
    // less telling message)
    checkRun(deltaT);

    if (state_.projection().forcingRegistered())
    {
        const volVectorField* U = mesh_.findObject<volVectorField>(UName_);
        if (!U)
        {
            FatalErrorInFunction
                << "Function object " << name() << ": no velocity field '"
                << UName_ << "' (keyword U in system/controlDict)"
                << exit(FatalError);
        }
        // The velocity's time scheme (backward: second order). The fluid's
        // force is taken from the solver's own rate of change of the
        // fluid's momentum, which the coupling knows for Euler and
        // backward (immersedForcing::timeDerivative); another scheme's rate
        // (CrankNicolson's carries its last one) would be read wrongly
        const word scheme
        (
            mesh_.ddtScheme("ddt(" + UName_ + ')')[0].wordToken()
        );
        if (scheme != "Euler" && scheme != "backward")
        {
            FatalErrorInFunction
                << "Function object " << name() << ": the velocity's time"
                << " scheme is '" << scheme << "' (ddtSchemes in"
                << " system/fvSchemes). The bodies' fluid force is taken from"
                << " the solver's own rate of change of the fluid's momentum,"
                << " which immersedDEM knows for Euler and backward only."
                << nl << "    Use ddtSchemes { default backward; } (second"
                << " order in time) or Euler." << exit(FatalError);
        }
        state_.fluidLoads(*U, deltaT, {rhoInf_, nu_, scheme == "backward"});
    }
    else if (!warnedNoForcing_)
    {
        // No fluid at all for the bodies: no lubrication either, so the
        // DEM is that of immersedDEMSolve on the same dictionary
        WarningInFunction
            << "Function object " << name() << ": no immersedBoundaryForce"
            << " fvOption in constant/fvOptions: the bodies do not feel the"
            << " fluid (nor its lubrication) and the fluid does not see them"
            << endl;
        state_.dem().setFluidViscosity(0);
        warnedNoForcing_ = true;
    }

    // A DEM step far below the CFD step is a stiff material or a tiny
    // body; past this many sub-steps per CFD step the run would only look
    // hung
    const ::immersedDEM::demSolver::stepChoice choice =
        state_.dem().stepFor(deltaT);
    const scalar demDeltaT = choice.deltaT;
    if (deltaT/demDeltaT > maxSubSteps_)
    {
        // Set by a body's relaxation under the fluid's damping, or by the
        // contacts and materials
        const bool damped =
            choice.a < 0 && !choice.floor && !choice.nameA.empty();
        OStringStream remedy;
        if (damped)
        {
            remedy
                << "Raise maxSubSteps or reduce the CFD step; if m/c is far"
                << " below the CFD step, the body is far lighter than the"
                << " fluid it moves or the coupling has gone bad (see the log"
                << " above for its speed and force)";
        }
        else
        {
            remedy
                << "Reduce the CFD step, soften the materials, set"
                << " time { deltaT ...; } in "
                << immersedDEMChecks::caseFile(state_.properties()) << " or raise maxSubSteps";
        }
        FatalErrorInFunction
            << "Function object " << name() << ", time " << time_.timeName()
            << ": the DEM step " << demDeltaT << " s would take "
            << ceil(deltaT/demDeltaT) << " sub-steps for the CFD step "
            << deltaT << " s, more than maxSubSteps " << maxSubSteps_
            << " (system/controlDict). The step is "
            << ::immersedDEM::timeStepExplanation::choice(choice).c_str()
            << ". " << remedy.str().c_str() << exit(FatalError);
    }

    label nSteps = 0;
    const clockTime demTimer;
    try
    {
        // After every sub-step: the extremes for the summary, and the
        // contacts' rows when asked for (the DEM's time, not the CFD's:
        // rows inside the CFD step)
        const bool rows = output_ && contactsEverySubStep_;
        state_.resumeLoads();
        nSteps = state_.dem().advance
        (
            deltaT,
            [this, rows]()
            {
                summary_->track(state_.dem());
                if (rows)
                {
                    output_->writeContacts(state_.dem().time(), state_.dem());
                }
            }
        );
    }
    catch (const ::immersedDEM::coreError& err)
    {
        FatalErrorInFunction
            << "Function object " << name() << ", time " << time_.timeName()
            << ": " << err.what() << exit(FatalError);
    }
    const scalar demSeconds = demTimer.elapsedTime();
    // Which bodies had a contact in this step (before bodies leave or
    // enter: the DEM's marks are by index)
    state_.coupling().noteContacts(state_.dem());

    // Bodies leaving (removal) and entering (insertion over time) at the
    // end of the step: projected, in the rows of this time
    const immersedDEMStreams::change change =
        state_.updateBodies(time_.value(), mesh_.findObject<volVectorField>(UName_));
    if (!change.any())
    {
        state_.project();
    }
    checkBodies(deltaT);
    // (again after the DEM: before the fluid's next step sees the bodies)
    checkRun(deltaT);
    const scalar fourierDeltaT = reportedFourier_ ? GREAT : fourierStep();
    if
    (
        fourierDeltaT < deltaT
     && !time_.controlDict().getOrDefault<bool>("adjustTimeStep", false)
    )
    {
        WarningInFunction
            << "Function object " << name() << ", time " << time_.timeName()
            << ": the CFD step " << deltaT << " s is above the step "
            << fourierDeltaT << " s at which the bodies' viscous Fourier"
            << " number nu deltaT/h^2 is maxFourier " << maxFourier_
            << ": the solver's correctors may not converge the fluid's"
            << " answer to the bodies: a free body can be thrown off, and"
            << " the flow around a fixed or prescribed one can oscillate and"
            << " grow from step to step. Reduce deltaT (or use"
            << " adjustTimeStep, which caps it), or raise the PIMPLE"
            << " dictionary's nCorrectors" << endl;
        reportedFourier_ = true;
    }

    scalar largest = 0;
    for (const auto& c : state_.dem().contacts())
    {
        largest = max(largest, c.region.volume);
    }
    scalar projectionSeconds = 0, forcingSeconds = 0;
    state_.takeTimings(projectionSeconds, forcingSeconds);
    projectionSeconds_ += projectionSeconds;
    forcingSeconds_ += forcingSeconds;
    demSeconds_ += demSeconds;
    Log << type() << ' ' << name() << ": t " << time_.timeName()
        << ", bodies " << state_.nBodies()
        << ", contacts " << state_.dem().contacts().size()
        << ", DEM steps " << nSteps
        << ", largest overlap " << figure(largest).c_str() << " m3"
        << ", seconds: projection " << figure(projectionSeconds).c_str()
        << " DEM " << figure(demSeconds).c_str()
        << " forcing " << figure(forcingSeconds).c_str()
        << " (projected bodies " << state_.projection().lastProjected() << ')'
        << ", DEM step " << ::immersedDEM::timeStepExplanation::lastStep(state_.dem()).c_str()
        << endl;
    immersedDEMReader::reportMessages(state_.dem());

    if (output_)
    {
        const clockTime outputTimer;
        output_->writeBodies(time_.value(), state_.dem());
        if (!contactsEverySubStep_)
        {
            output_->writeContacts(time_.value(), state_.dem());
        }
        outputSeconds_ += outputTimer.elapsedTime();
    }
    return true;
}


Foam::scalar Foam::functionObjects::immersedDEM::fourierStep() const
{
    // The largest CFD step at maxFourier over the bodies in the mesh,
    // free, fixed and prescribed alike (their smallest covered cell,
    // checkBodies): the forcing of a fixed body needs it as much as the
    // coupling of a free one
    scalar cap = GREAT;
    if (!(maxFourier_ > 0) || !(nu_ > 0) || !state_.projection().forcingRegistered())
    {
        return cap;
    }
    // (the cells' size in the plane of a 2D mesh: cube roots of the
    // volumes are cells of the slab's depth)
    scalar depth = 0;
    if (mesh_.nSolutionD() == 2)
    {
        const Vector<label>& d = mesh_.solutionD();
        for (direction k = 0; k < 3; ++k)
        {
            if (d[k] < 0) depth = mesh_.bounds().span()[k];
        }
    }
    const auto& bodies = state_.dem().bodies();
    forAll(bodies, i)
    {
        scalar h = bodies[i].fluidCellSize;
        if (depth > 0)
        {
            h = sqrt(h*h*h/depth);
        }
        if (!state_.dem().isWall(i) && h > 0)
        {
            cap = min(cap, maxFourier_*h*h/nu_);
        }
    }
    return cap;
}


bool Foam::functionObjects::immersedDEM::adjustTimeStep()
{
    const scalar cap = fourierStep();
    if (cap < time_.deltaTValue())
    {
        const_cast<Time&>(time_).setDeltaT(cap, false);
        if (!reportedFourier_)
        {
            Info<< type() << ' ' << name() << ": the CFD step is capped at "
                << cap << " s, where the bodies' viscous Fourier number"
                << " nu deltaT/h^2 is maxFourier " << maxFourier_
                << " (the solver's correctors converge the fluid's answer to"
                << " a body's motion below it)" << endl;
            reportedFourier_ = true;
        }
    }
    return true;
}


bool Foam::functionObjects::immersedDEM::write()
{
    if (!time_.writeTime())
    {
        return true;
    }
    const clockTime outputTimer;
    state_.writeRestart(time_.timePath());
    if (output_)
    {
        output_->writeVTK(time_.value(), state_.dem());
    }
    outputSeconds_ += outputTimer.elapsedTime();
    return true;
}


bool Foam::functionObjects::immersedDEM::end()
{
    // How often each body was projected on the mesh: once per mesh for a
    // body that does not move
    const List<label>& n = state_.projection().projections();
    Log << type() << ' ' << name() << ": projections per body:";
    forAll(n, i)
    {
        if (state_.dem().isWall(i)) continue;
        Log << ' ' << word(state_.dem().bodies()[i].name) << ' ' << n[i];
    }
    Log << endl;

    // The DEM's pair work over the run (in parallel summed over the
    // processors, each evaluating the pairs it owns)
    Log << type() << ' ' << name() << ": "
        << immersedDEMParallel::demWorkLine(state_.dem()).c_str() << endl;

    // The seconds per part over the whole run (the DEM's own split from
    // its counters), against the run's wall time since this function
    // object started
    ::immersedDEM::runSummary::seconds parts;
    parts.setup = state_.setupSeconds() + setupSeconds_;
    parts.projection = projectionSeconds_;
    ::immersedDEM::runSummary::demParts(state_.dem(), demSeconds_, parts);
    parts.forcing = forcingSeconds_;
    parts.output = outputSeconds_;
    parts.total = state_.wallSeconds();
    Log << type() << ' ' << name() << ": "
        << summary_->text
           (
               parts, time_.value() - startTime_, state_.dem().work().steps, true
           ).c_str()
        << endl;
    return true;
}
