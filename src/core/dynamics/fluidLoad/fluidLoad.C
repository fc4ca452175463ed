#include "fluidLoad.H"

#include <algorithm>

namespace immersedDEM
{

namespace
{

// The load F, T over a CFD step ending at t, its course (v, a), (w, alpha)
// as the fluid saw it; no damper, no added mass yet
fluidLoad onCourse
(
    const vec3& F, const vec3& T, double t,
    const vec3& v, const vec3& a, const vec3& w, const vec3& alpha
)
{
    fluidLoad l;
    l.force = F;
    l.torque = T;
    l.referenceVelocity = v;
    l.referenceAcceleration = a;
    l.referenceTime = t;
    l.referenceAngularVelocity = w;
    l.referenceAngularAcceleration = alpha;
    return l;
}

} // End anonymous namespace


fluidLoad fluidLoad::coupled
(
    const vec3& F,
    const vec3& T,
    const fluidImpedance::coefficients& z,
    const double t,
    const vec3& v,
    const vec3& a,
    const vec3& w,
    const vec3& alpha
)
{
    fluidLoad l = onCourse(F, T, t, v, a, w, alpha);
    l.addedMass = z.addedMass;
    l.nominalAddedMass = std::min(z.nominalAddedMass, z.addedMass);
    l.damping = z.damping;
    l.addedInertia = z.addedInertia;
    l.angularDamping = z.angularDamping;
    return l;
}


fluidLoad fluidLoad::held
(
    const vec3& F,
    const vec3& T,
    const double addedMass,
    const double addedInertia,
    const double nominalAddedMass,
    const double deltaT,
    const double t,
    const vec3& v,
    const vec3& a,
    const vec3& w,
    const vec3& alpha
)
{
    fluidLoad l = onCourse(F, T, t, v, a, w, alpha);
    l.damping = addedMass/deltaT;
    l.angularDamping = addedInertia/deltaT;
    l.nominalAddedMass = nominalAddedMass;
    l.courseExtrapolated = 1;
    return l;
}

} // End namespace immersedDEM
