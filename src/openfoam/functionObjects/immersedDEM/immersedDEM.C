#include "immersedDEM.H"
#include "immersedDEMState.H"
#include "dictionaryChecks.H"
#include "demOutput.H"
#include "coreError.H"
#include "clockTime.H"
#include "addToRunTimeSelectionTable.H"

namespace Foam
{
namespace functionObjects
{
    defineTypeNameAndDebug(immersedDEM, 0);
    addToRunTimeSelectionTable(functionObject, immersedDEM, dictionary);
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
    Ca_(1),
    UName_("U")
{
    read(dict);
    if (Pstream::master())
    {
        const fileName dir =
            time_.globalPath()/"postProcessing"/name
           /time_.timeName(time_.startTime().value());
        try
        {
            output_.reset(new ::immersedDEM::demOutput(dir));
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
            "rhoInf", "U", "addedMassCoefficient", "maxSubSteps", "writeContacts"
        }
    );
    contactsEverySubStep_ =
        immersedDEMChecks::oneOfOrDefault(dict, "writeContacts", {"step", "subStep"}, "step") == "subStep";
    maxSubSteps_ = immersedDEMChecks::positiveOrDefault(dict, "maxSubSteps", 1e5);
    rhoInf_ = immersedDEMChecks::positive(dict, "rhoInf");
    Ca_ = immersedDEMChecks::inRangeOrDefault(dict, "addedMassCoefficient", 0, 100, 1);
    UName_ = dict.getOrDefault<word>("U", "U");
    return true;
}


bool Foam::functionObjects::immersedDEM::execute()
{
    const scalar deltaT = time_.deltaTValue();

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
        state_.fluidLoads(*U, rhoInf_, deltaT, Ca_);
    }
    else if (!warnedNoForcing_)
    {
        WarningInFunction
            << "Function object " << name() << ": no immersedBoundaryForce"
            << " fvOption in constant/fvOptions: the bodies do not feel the"
            << " fluid and the fluid does not see them" << endl;
        warnedNoForcing_ = true;
    }

    // A DEM step far below the CFD step is a stiff material or a tiny
    // body; past this many sub-steps per CFD step the run would only look
    // hung
    const scalar demDeltaT = state_.dem().timeStep();
    if (deltaT/demDeltaT > maxSubSteps_)
    {
        FatalErrorInFunction
            << "Function object " << name() << ", time " << time_.timeName()
            << ": the DEM step " << demDeltaT << " s would take "
            << ceil(deltaT/demDeltaT) << " sub-steps for the CFD step "
            << deltaT << " s, more than maxSubSteps " << maxSubSteps_
            << " (system/controlDict). Reduce the CFD step, soften the"
            << " materials, set time { deltaT ...; } in "
            << state_.properties().objectPath() << " or raise maxSubSteps"
            << exit(FatalError);
    }

    label nSteps = 0;
    const clockTime demTimer;
    try
    {
        if (output_ && contactsEverySubStep_)
        {
            // The DEM's time, not the CFD's: rows inside the CFD step
            nSteps = state_.dem().advance
            (
                deltaT,
                [this]()
                {
                    output_->writeContacts(state_.dem().time(), state_.dem());
                }
            );
        }
        else
        {
            nSteps = state_.dem().advance(deltaT);
        }
    }
    catch (const ::immersedDEM::coreError& err)
    {
        FatalErrorInFunction
            << "Function object " << name() << ", time " << time_.timeName()
            << ": " << err.what() << exit(FatalError);
    }
    const scalar demSeconds = demTimer.elapsedTime();

    state_.project();

    scalar largest = 0;
    for (const auto& c : state_.dem().contacts())
    {
        largest = max(largest, c.region.volume);
    }
    scalar projectionSeconds = 0, forcingSeconds = 0;
    state_.takeTimings(projectionSeconds, forcingSeconds);
    Log << type() << ' ' << name() << ": t " << time_.timeName()
        << ", bodies " << state_.nBodies()
        << ", contacts " << state_.dem().contacts().size()
        << ", DEM steps " << nSteps
        << ", largest overlap " << largest << " m3"
        << ", seconds: projection " << projectionSeconds
        << " DEM " << demSeconds
        << " forcing " << forcingSeconds << endl;

    if (output_)
    {
        output_->writeBodies(time_.value(), state_.dem());
        if (!contactsEverySubStep_)
        {
            output_->writeContacts(time_.value(), state_.dem());
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
    state_.writeRestart(time_.timePath());
    if (output_)
    {
        output_->writeVTK(time_.value(), state_.dem());
    }
    return true;
}
