#include "couplingMemory.H"

#include <bitset>


bool immersedDEM::couplingMemory::isolatedImpact(const int steps)
{
    // One run of set bits, at most two long (at 16 cells per diameter the
    // wet bounce's contact often crosses the end of a step)
    const std::bitset<32> b(steps);
    const std::bitset<32> runStarts(steps & ~(steps >> 1));
    return b.count() <= 1 || (b.count() == 2 && runStarts.count() == 1);
}


void immersedDEM::couplingMemory::remember
(
    const vec3& velocity,
    const vec3& angularVelocity,
    const vec3& momentum,
    const vec3& angularMomentum,
    const bool inContactNow
)
{
    previousVelocity0 = previousVelocity;
    previousAngularVelocity0 = previousAngularVelocity;
    previousVelocity = velocity;
    previousAngularVelocity = angularVelocity;
    innerMomentum0 = innerMomentum;
    innerAngularMomentum0 = innerAngularMomentum;
    innerMomentum = momentum;
    innerAngularMomentum = angularMomentum;
    ++history;
    wasInContact = inContactNow;
}
