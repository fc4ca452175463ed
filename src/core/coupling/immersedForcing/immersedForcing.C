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


vec3 fluidForce
(
    const double rho,
    const vec3& P,
    const vec3& M,
    const vec3& M0,
    const double deltaT,
    const double volume,
    const vec3& g
)
{
    return rho*(P + (M - M0)/deltaT) - rho*volume*g;
}


vec3 fluidTorque
(
    const double rho,
    const vec3& PM,
    const vec3& L,
    const vec3& L0,
    const double deltaT
)
{
    return rho*(PM + (L - L0)/deltaT);
}

} // End namespace immersedForcing
} // End namespace immersedDEM
