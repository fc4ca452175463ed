// Restart I/O of immersedFluidCoupling: each body's couplingMemory under
// its fields' names, in the body's entry of the state file
// (immersedDEMStateIO.C), and the last CFD step

#include "immersedFluidCoupling.H"
#include "restartEntries.H"

using namespace immersedDEM;


void Foam::immersedFluidCoupling::writeBody(Ostream& os, const label i) const
{
    couplingMemory::fields(memory_[i], restartEntries::writer{os});
    os.writeEntry("previousDeltaT", previousDeltaT_);
}


void Foam::immersedFluidCoupling::readBody(const dictionary& d, const label i)
{
    // A state written before some of the memory existed: what it lacks is
    // as for a body in contact with no history (the measured added mass
    // starts from nothing; without the force taken at the last step, the
    // next step takes the fluid's force as it is). The inner momenta and
    // the last velocities are always there
    couplingMemory m;
    m.wasInContact = true;
    couplingMemory::fields
    (
        m,
        restartEntries::reader
        {
            d,
            [](const word& name)
            {
                return
                    name != "previousVelocity"
                 && name != "previousAngularVelocity"
                 && name != "innerMomentum"
                 && name != "innerAngularMomentum";
            }
        }
    );
    memory_[i] = m;
    takenUnknown_[i] = !d.found("takenForce");
    innerMomentumSet_ = true;
    previousDeltaT_ = max(previousDeltaT_, d.getOrDefault<scalar>("previousDeltaT", 0));
}
