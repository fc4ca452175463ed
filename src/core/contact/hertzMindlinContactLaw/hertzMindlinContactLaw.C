#include "hertzMindlinContactLaw.H"
#include "restitutionCalibration.H"

#include <cmath>

namespace immersedDEM
{

contactOutput hertzMindlinContactLaw::evaluate(const contactInput& in, contactHistory& h) const
{
    return force(in, h, restitutionCalibration::damping(in.material.restitution, 1.5));
}


double hertzMindlinContactLaw::contactTime
(
    const pairMaterial& m, double effectiveMass, double effectiveRadius,
    double, double v
) const
{
    const double E = m.effectiveModulus;
    return 2.87*std::pow(effectiveMass*effectiveMass/(effectiveRadius*E*E*v), 0.2);
}

} // End namespace immersedDEM
