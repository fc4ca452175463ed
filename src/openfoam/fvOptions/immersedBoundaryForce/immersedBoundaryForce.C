#include "immersedBoundaryForce.H"
#include "immersedDEMState.H"
#include "dictionaryChecks.H"
#include "fvMatrices.H"
#include "fvmSup.H"
#include "addToRunTimeSelectionTable.H"
#include "clockTime.H"

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
    state_(immersedDEMState::New(mesh)),
    penalty_(1000)
{
    read(dict);
}


bool Foam::fv::immersedBoundaryForce::read(const dictionary& dict)
{
    if (!option::read(dict))
    {
        return false;
    }
    immersedDEMChecks::allowOnly(dict, {"type", "active", "fields", "penalty", "name"});
    fieldNames_ = dict.getOrDefault<wordList>("fields", wordList{"U"});
    if (fieldNames_.size() != 1)
    {
        FatalIOErrorInFunction(dict)
            << "Keyword 'fields' in " << dict.name()
            << " must name one velocity field, not " << fieldNames_ << nl
            << exit(FatalIOError);
    }
    applied_.setSize(fieldNames_.size(), false);
    penalty_ = immersedDEMChecks::positiveOrDefault(dict, "penalty", 1000);
    state_.setPenalty(penalty_);
    return true;
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
    tK.ref().field() = state_.forcingCoefficient(mesh_.time().deltaTValue());
    return tK;
}


void Foam::fv::immersedBoundaryForce::addSup
(
    fvMatrix<vector>& eqn,
    const label fieldi
)
{
    state_.projectIfMeshChanged();
    state_.setInnerMomentum(eqn.psi());
    const clockTime timer;
    const volScalarField::Internal KLambda(penaltyCoefficient());
    eqn += KLambda*state_.Uib()() - fvm::Sp(KLambda, eqn.psi());
    state_.addForcingSeconds(timer.elapsedTime());
}


void Foam::fv::immersedBoundaryForce::addSup
(
    const volScalarField& rho,
    fvMatrix<vector>& eqn,
    const label fieldi
)
{
    state_.projectIfMeshChanged();
    state_.setInnerMomentum(eqn.psi());
    const clockTime timer;
    const volScalarField::Internal rhoKLambda(rho()*penaltyCoefficient());
    eqn += rhoKLambda*state_.Uib()() - fvm::Sp(rhoKLambda, eqn.psi());
    state_.addForcingSeconds(timer.elapsedTime());
}
