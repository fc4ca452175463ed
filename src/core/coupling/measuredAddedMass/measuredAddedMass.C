#include "measuredAddedMass.H"

#include <algorithm>

namespace immersedDEM
{

void measuredAddedMass::record(const vec3& F, const vec3& a, const double floor)
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
        if (sumaa_ > floor)
        {
            value_ = std::max(0.0, sumFa_/sumaa_);
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
    const double cap
) const
{
    return value_ > m ? std::max(floor, std::min(value_, cap)) : floor;
}

} // End namespace immersedDEM
