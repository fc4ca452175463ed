#include "overlapVolumeContactLaw.H"
#include "restitutionCalibration.H"

#include <algorithm>
#include <cmath>

namespace immersedDEM
{

contactOutput overlapVolumeContactLaw::evaluate(const contactInput& in, contactHistory& h) const
{
    const contactRegion& r = in.region;
    const double Y = in.material.effectiveModulus;
    const double lc = in.characteristicLength;
    const double vApproach = -in.relativeVelocity.dot(r.normal);
    h.approach = std::max(0.0, h.approach + vApproach*in.dt);

    const double k = Y*r.area/lc;
    double q = 2;
    if (r.volume > 0 && h.approach > 0)
    {
        q = std::min(3.0, std::max(1.0, r.area*h.approach/r.volume));
    }
    const double c = restitutionCalibration::damping(in.material.restitution, q);

    contactOutput out;
    out.normalForce = std::max
    (
        0.0, Y*r.volume/lc + c*std::sqrt(in.effectiveMass*k)*vApproach
    );
    const double nu = in.material.poissonsRatio;
    const double kt = k*2*(1 - nu)/(2 - nu);
    // The tangential spring gets a dashpot of the same damping ratio as the
    // normal one: without it a contact's tangential (and rolling) vibrations
    // below the Coulomb limit never decay and a pile never comes to rest
    out.tangentialForce = tangentialForce
    (
        in, h, kt, c*std::sqrt(in.effectiveMass*kt), out.normalForce, out.sliding
    );
    out.force = out.normalForce*r.normal + out.tangentialForce;
    h.maxNormalForce = std::max(h.maxNormalForce, out.normalForce);
    return out;
}


double overlapVolumeContactLaw::contactTime
(
    const pairMaterial& m, double effectiveMass, double effectiveRadius,
    double characteristicLength, double v
) const
{
    const double K = M_PI*m.effectiveModulus*effectiveRadius/characteristicLength;
    return 2.8044*std::cbrt(3*effectiveMass/(2*K*v));
}

} // End namespace immersedDEM
