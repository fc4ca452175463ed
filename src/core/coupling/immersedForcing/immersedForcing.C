#include "immersedForcing.H"

#include <algorithm>

namespace immersedDEM
{
namespace immersedForcing
{

double diffuseCoefficient(const double l, const double deltaT, const double penalty)
{
    if (!(l > 0) || !(deltaT > 0)) return 0;
    return (l*(1 + penalty) >= penalty ? penalty : l/(1 - l))/deltaT;
}


double sharpCoefficient(const double wallK, const double deltaT, const double penalty)
{
    if (!(deltaT > 0)) return 0;
    const double KMax = penalty/deltaT;
    return wallK < 0 ? KMax : std::min(wallK, KMax);
}


double wallShearCoefficient
(
    const double nu,
    const double faceCoeff,
    const double V,
    const double phiC,
    const double phiN
)
{
    const double theta = phiC/(phiC - phiN);
    return nu*faceCoeff/V*(1 - theta)/theta;
}


timeDerivative timeDerivative::euler(const double deltaT)
{
    timeDerivative d;
    d.deltaT = deltaT;
    return d;
}


timeDerivative timeDerivative::backward(const double deltaT, const double deltaT0)
{
    timeDerivative d;
    d.deltaT = deltaT;
    d.deltaT0 = deltaT0;
    d.c = 1 + deltaT/(deltaT + deltaT0);
    d.c00 = deltaT*deltaT/(deltaT0*(deltaT + deltaT0));
    d.c0 = d.c + d.c00;
    return d;
}


vec3 fluidForce
(
    const double rho,
    const vec3& P,
    const vec3& innerRate,
    const double volume,
    const vec3& g
)
{
    return rho*(P + innerRate) - rho*volume*g;
}


vec3 fluidTorque
(
    const double rho,
    const vec3& PM,
    const vec3& innerAngularRate
)
{
    return rho*(PM + innerAngularRate);
}

} // End namespace immersedForcing
} // End namespace immersedDEM
