#include "immersedDEM.H"
#include "immersedDEMState.H"
#include "dictionaryChecks.H"
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
    rhoInf_(0)
{
    read(dict);
}


bool Foam::functionObjects::immersedDEM::read(const dictionary& dict)
{
    fvMeshFunctionObject::read(dict);
    immersedDEMChecks::allowOnly
    (
        dict,
        {
            "type", "libs", "enabled", "log", "region", "timeStart", "timeEnd",
            "executeControl", "executeInterval", "writeControl", "writeInterval",
            "rhoInf"
        }
    );
    rhoInf_ = immersedDEMChecks::positive(dict, "rhoInf");
    return true;
}


bool Foam::functionObjects::immersedDEM::execute()
{
    ++nExecuted_;
    Log << type() << ' ' << name() << ": time " << time_.timeName()
        << ", bodies " << state_.nBodies()
        << ", step " << nExecuted_ << endl;
    return true;
}


bool Foam::functionObjects::immersedDEM::write()
{
    return true;
}
