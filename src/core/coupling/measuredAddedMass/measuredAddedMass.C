#include "measuredAddedMass.H"

#include <algorithm>
#include <cmath>

namespace immersedDEM
{

void measuredAddedMass::record
(
    const vec3& F,
    const vec3& a,
    const double floor
)
{
    if (skip_ > 0)
    {
        skip_ -= 1;
    }
    else if (recorded_ >= 1)
    {
        const vec3 dF = F - lastForce_;
        const vec3 da = a - lastAcceleration_;
        sumFa_ = forget*sumFa_ - dF.dot(da);
        sumaa_ = forget*sumaa_ + da.squaredNorm();
        // The correlation, over a longer memory, and whether it tells
        // anything: Fisher's z = atanh(rho) sqrt(n - 3) at least
        // minSignificance, n the memory's effective number of steps.
        // Random force noise against random changes of acceleration
        // reaches rho = 0.7 now and then over a few steps, not over 40
        corrFa_ = forgetCorrelation*corrFa_ - dF.dot(da);
        corraa_ = forgetCorrelation*corraa_ + da.squaredNorm();
        corrFF_ = forgetCorrelation*corrFF_ + dF.squaredNorm();
        corrW1_ = forgetCorrelation*corrW1_ + 1;
        corrW2_ = forgetCorrelation*forgetCorrelation*corrW2_ + 1;
        const double n = corrW1_*corrW1_/corrW2_;
        const double rho =
            corrFa_ > 0 && corraa_*corrFF_ > 0
          ? std::min(corrFa_/std::sqrt(corraa_*corrFF_), 1 - 1e-12)
          : 0;
        const bool significant =
            n > 3 && std::atanh(rho)*std::sqrt(n - 3) >= minSignificance;
        // Only changes of force that follow the changes of acceleration
        // tell M
        if (sumaa_ > floor)
        {
            value_ = std::max(0.0, sumFa_/sumaa_);
            if (significant) significantValue_ = value_;
        }
    }
    lastForce_ = F;
    lastAcceleration_ = a;
    recorded_ = 1;
}


double measuredAddedMass::stabilisation
(
    const double m,
    const double floor,
    const double cap,
    const bool significantOnly
) const
{
    const double M = value(significantOnly);
    return M > m ? std::max(floor, std::min(M, cap)) : floor;
}

} // End namespace immersedDEM
