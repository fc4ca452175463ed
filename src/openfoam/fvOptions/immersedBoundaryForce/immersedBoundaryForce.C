#include "immersedBoundaryForce.H"
#include "immersedDEMState.H"
#include "immersedDEM.H"
#include "dictionaryChecks.H"
#include "fvMatrices.H"
#include "fvmSup.H"
#include "addToRunTimeSelectionTable.H"
#include "clockTime.H"
#include "periodicDrive.H"
#include "coreConversion.H"

namespace Foam
{
namespace fv
{
    defineTypeNameAndDebug(immersedBoundaryForce, 0);
    addToRunTimeSelectionTable(option, immersedBoundaryForce, dictionary);
}
}


Foam::fv::immersedBoundaryForce::immersedBoundaryForce
(
    const word& name,
    const word& modelType,
    const dictionary& dict,
    const fvMesh& mesh
)
:
    option(name, modelType, dict, mesh),
    state_(immersedDEMState::New(mesh))
{
    read(dict);
}


bool Foam::fv::immersedBoundaryForce::read(const dictionary& dict)
{
    if (!option::read(dict))
    {
        return false;
    }
    immersedDEMChecks::allowOnly
    (
        dict,
        {
            "type", "active", "fields", "penalty", "name", "surface", "nu",
            "sealedWalls", "balanceWeight"
        }
    );
    fieldNames_ = dict.getOrDefault<wordList>("fields", wordList{"U"});
    if (fieldNames_.size() != 1)
    {
        FatalIOErrorInFunction(dict)
            << "Keyword 'fields' in " << dict.name()
            << " must name one velocity field, not " << fieldNames_ << nl
            << exit(FatalIOError);
    }
    applied_.setSize(fieldNames_.size(), false);
    immersedBoundaryForcingSettings forcing;
    forcing.penalty =
        immersedDEMChecks::positiveOrDefault(dict, "penalty", forcing.penalty);
    // The film under a body next to a wall patch is the lubrication's when
    // it is on (then the wall faces' pressure, an explicit coupling that
    // can throw the body off the wall, is left out, as between two
    // bodies), the wall faces' pressure's when it is off
    forcing.sealedWalls = dict.getOrDefault<bool>
    (
        "sealedWalls", state_.settingsRead().lubrication.active
    );

    const word surface
    (
        dict.getOrDefault<word>("surface", forcing.sharp ? "sharp" : "diffuse")
    );
    if (surface != "sharp" && surface != "diffuse")
    {
        FatalIOErrorInFunction(dict)
            << "Keyword 'surface' in " << dict.name() << " is '" << surface
            << "': it must be sharp or diffuse" << nl
            << exit(FatalIOError);
    }
    forcing.sharp = surface == "sharp";
    if (forcing.sharp)
    {
        forcing.nu = viscosity(dict);
    }
    else if (dict.found("nu"))
    {
        FatalIOErrorInFunction(dict)
            << "Keyword 'nu' in " << dict.name()
            << " is used by the sharp surface only (surface is diffuse)" << nl
            << exit(FatalIOError);
    }
    state_.setForcing(forcing);
    // A periodic suspension: nothing but the fluid carries the bodies'
    // net weight along a periodic direction (periodicDrive.H)
    const vector g = coreConversion::toFoam(state_.settingsRead().gravity);
    balanceWeight_ = dict.getOrDefault<bool>
    (
        "balanceWeight", periodicDrive::needed(state_.dem(), g)
    );
    if (balanceWeight_ && !state_.dem().periodic().active())
    {
        FatalIOErrorInFunction(dict)
            << "Keyword 'balanceWeight' in " << dict.name() << " is on, but"
            << " the mesh has no cyclic patches: walls carry the bodies'"
            << " weight; remove it" << nl << exit(FatalIOError);
    }
    return true;
}


Foam::scalar Foam::fv::immersedBoundaryForce::viscosity
(
    const dictionary& dict
) const
{
    if (dict.found("nu"))
    {
        return immersedDEMChecks::positiveOrDefault(dict, "nu", 1);
    }
    // The laminar viscosity the solver read (singlePhaseTransportModel)
    const word transport("transportProperties");
    if (!mesh_.foundObject<IOdictionary>(transport))
    {
        FatalIOErrorInFunction(dict)
            << "The sharp surface of " << dict.name()
            << " needs the fluid's kinematic viscosity: give it as 'nu' there"
            << " (constant/" << transport << " is not loaded by this solver)"
            << nl << exit(FatalIOError);
    }
    const IOdictionary& t = mesh_.lookupObject<IOdictionary>(transport);
    if (!t.found("nu"))
    {
        FatalIOErrorInFunction(t)
            << "Keyword 'nu' is missing from " << immersedDEMChecks::caseFile(t)
            << ": the sharp surface of " << dict.name()
            << " needs the kinematic viscosity (or give 'nu' there)" << nl
            << exit(FatalIOError);
    }
    const scalar nu = dimensionedScalar("nu", dimViscosity, t).value();
    if (!(nu > 0))
    {
        FatalIOErrorInFunction(t)
            << "Keyword 'nu' in " << immersedDEMChecks::caseFile(t) << " is " << nu
            << ": it must be > 0" << nl << exit(FatalIOError);
    }
    return nu;
}


void Foam::fv::immersedBoundaryForce::requireFunctionObject()
{
    if (functionObjectFound_)
    {
        return;
    }
    // The solver's time loop constructed the function objects before the
    // first step's momentum equation
    if (!mesh_.foundObject<IOdictionary>(functionObjects::immersedDEM::registrationName))
    {
        FatalErrorInFunction
            << "fvOption '" << name_ << "' (" << typeName << ") forces the fluid"
            << " with the bodies of constant/immersedDEMProperties, but no"
            << " function object of type immersedDEM runs for region "
            << mesh_.name() << ": the bodies would never move and nothing"
            << " would be written. Add one to the functions of "
            << mesh_.time().controlDict().name() << nl
            << exit(FatalError);
    }
    functionObjectFound_ = true;
}


Foam::tmp<Foam::volScalarField::Internal>
Foam::fv::immersedBoundaryForce::penaltyCoefficient() const
{
    tmp<volScalarField::Internal> tK
    (
        new volScalarField::Internal
        (
            IOobject("immersedBoundaryForce:K", mesh_.time().timeName(), mesh_),
            mesh_,
            dimensionedScalar(dimless/dimTime, Zero)
        )
    );
    tK.ref().field() = state_.projection().forcingCoefficient(mesh_.time().deltaTValue());
    return tK;
}


Foam::tmp<Foam::volVectorField::Internal>
Foam::fv::immersedBoundaryForce::drive(const volVectorField& U)
{
    const periodicDrive::parts f = periodicDrive::of
    (
        state_.dem(), coreConversion::toFoam(state_.settingsRead().gravity),
        state_.fluidDensity(), U, mesh_.time().deltaTValue()
    );
    if (driveLogged_ != mesh_.time().timeIndex())
    {
        driveLogged_ = mesh_.time().timeIndex();
        Info<< "immersedBoundaryForce " << name_ << ": periodic drive "
            << f.total() << " m/s2 (net weight " << f.weight
            << ", walls and mean flux " << f.flux << "; mean velocity "
            << f.meanU << " m/s)" << endl;
    }
    return tmp<volVectorField::Internal>
    (
        new volVectorField::Internal
        (
            IOobject("immersedBoundaryForce:drive", mesh_.time().timeName(), mesh_),
            mesh_,
            dimensionedVector("drive", dimVelocity/dimTime, f.total())
        )
    );
}


void Foam::fv::immersedBoundaryForce::addSup
(
    fvMatrix<vector>& eqn,
    const label fieldi
)
{
    requireFunctionObject();
    state_.projectIfMeshChanged();
    state_.setInnerMomentum(eqn.psi());
    const clockTime timer;
    const volScalarField::Internal KLambda(penaltyCoefficient());
    eqn += KLambda*state_.projection().Uib()() - fvm::Sp(KLambda, eqn.psi());
    if (balanceWeight_)
    {
        eqn += drive(eqn.psi());
    }
    state_.addForcingSeconds(timer.elapsedTime());
}


void Foam::fv::immersedBoundaryForce::addSup
(
    const volScalarField& rho,
    fvMatrix<vector>& eqn,
    const label fieldi
)
{
    requireFunctionObject();
    state_.projectIfMeshChanged();
    state_.setInnerMomentum(eqn.psi());
    const clockTime timer;
    const volScalarField::Internal rhoKLambda(rho()*penaltyCoefficient());
    eqn += rhoKLambda*state_.projection().Uib()() - fvm::Sp(rhoKLambda, eqn.psi());
    if (balanceWeight_)
    {
        eqn += rho()*drive(eqn.psi())();
    }
    state_.addForcingSeconds(timer.elapsedTime());
}
