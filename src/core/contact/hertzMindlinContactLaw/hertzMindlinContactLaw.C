#include "hertzMindlinContactLaw.H"
#include "restitutionCalibration.H"

#include <algorithm>
#include <cmath>

namespace immersedDEM
{

contactOutput hertzMindlinContactLaw::evaluate(const contactInput& in, contactHistory& h) const
{
    const double delta = std::max(0.0, in.overlapDepth);
    const double R = in.effectiveRadius;
    const double E = in.material.effectiveModulus;
    const double G = in.material.effectiveShearModulus;
    const double vApproach = -in.relativeVelocity.dot(in.region.normal);
    h.approach = std::max(0.0, h.approach + vApproach*in.dt);

    // Stiffnesses Sn = 2 E sqrt(R delta), St = 8 G sqrt(R delta); the
    // dampings c sqrt(m S)
    const double root = std::sqrt(R*delta);
    const double St = 8*G*root;
    const double c = restitutionCalibration::damping(in.material.restitution, 1.5);
    const double mRoot = in.effectiveMass*root;

    contactOutput out;
    out.normalForce = std::max
    (
        0.0,
        4.0/3.0*E*delta*root + c*std::sqrt(2*E*mRoot)*vApproach
    );
    out.tangentialForce = tangentialForce
    (
        in, h, St, c*std::sqrt(8*G*mRoot), out.normalForce, out.sliding
    );
    out.force = out.normalForce*in.region.normal + out.tangentialForce;
    h.maxNormalForce = std::max(h.maxNormalForce, out.normalForce);
    return out;
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
