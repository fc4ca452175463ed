#include "fluidLoad.H"

namespace immersedDEM
{

fluidLoad fluidLoad::stabilised
(
    const vec3& F,
    const vec3& T,
    const double addedMass,
    const double nominalAddedMass,
    const bool inertia,
    const double addedInertia,
    const double deltaT,
    const double t,
    const vec3& v,
    const vec3& vPrevious,
    const vec3& w,
    const vec3& wPrevious
)
{
    fluidLoad l;
    l.force = F;
    if (inertia)
    {
        l.addedMass = addedMass;
        l.nominalAddedMass = nominalAddedMass;
    }
    else
    {
        l.damping = addedMass/deltaT;
    }
    l.referenceVelocity = v;
    l.referenceAcceleration = (v - vPrevious)/deltaT;
    l.referenceTime = t;
    l.torque = T;
    l.angularDamping = addedInertia/deltaT;
    l.referenceAngularVelocity = w;
    l.referenceAngularAcceleration = (w - wPrevious)/deltaT;
    return l;
}

} // End namespace immersedDEM
