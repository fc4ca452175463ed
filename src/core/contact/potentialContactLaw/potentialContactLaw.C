#include "potentialContactLaw.H"
#include "restitutionCalibration.H"

#include <algorithm>
#include <cmath>

namespace immersedDEM
{

double potentialContactLaw::referenceVolume(double flatFaceArea, double Rstar)
{
    const double floor = M_PI*Rstar*std::pow(eps*Rstar, 2);
    if (!(flatFaceArea > 0) || !std::isfinite(flatFaceArea))
    {
        return floor;
    }
    return std::max(floor, flatFaceArea*flatFaceArea/(4*M_PI*Rstar));
}


double potentialContactLaw::dWdV(double V, double Y, double lc, double Rstar, double V0)
{
    if (V <= 0) return 0;
    return Y*V/(2*lc*std::sqrt(M_PI*Rstar*(V + V0)));
}


double potentialContactLaw::energy(double V, double Y, double lc, double Rstar, double V0)
{
    if (V <= 0) return 0;
    // integral of u/sqrt(u + V0) = (2/3)(u + V0)^1.5 - 2 V0 (u + V0)^0.5
    const double s = std::sqrt(V + V0), s0 = std::sqrt(V0);
    const double I = (2.0/3)*(s*s*s - s0*s0*s0) - 2*V0*(s - s0);
    return Y*I/(2*lc*std::sqrt(M_PI*Rstar));
}


contactOutput potentialContactLaw::evaluate(const contactInput& in, contactHistory& h) const
{
    const contactRegion& r = in.region;
    const double Y = in.material.effectiveModulus;
    const double lc = in.characteristicLength;
    const vec3 S = r.areaVector.squaredNorm() > 0 ? r.areaVector : vec3(r.area*r.normal);
    const double Sn = S.norm();
    contactOutput out;
    if (!(Sn > 0) || !(r.volume > 0))
    {
        return out;
    }
    const vec3 n = S/Sn;
    const double vApproach = -in.relativeVelocity.dot(n);
    h.approach = std::max(0.0, h.approach + vApproach*in.dt);

    const double k = Y*Sn/lc;
    double q = 2;
    if (h.approach > 0)
    {
        q = std::min(3.0, std::max(1.0, Sn*h.approach/r.volume));
    }
    const double c = restitutionCalibration::damping(in.material.restitution, q);

    const double V0 = referenceVolume(in.flatFaceArea, in.effectiveRadius);
    // w of the pair's whole overlap (Feng's potential of the intersection
    // volume): its gradient is w'(V) times the sum of the regions' S, and
    // it stays continuous when a region splits in two or two merge (w of
    // each region's volume would jump there by w(V1 + V2) - w(V1) - w(V2))
    const double V = std::max(r.volume, in.pairVolume);
    const double wp = dWdV(V, Y, lc, in.effectiveRadius, V0);
    out.normalForce = std::max(0.0, wp*Sn + c*std::sqrt(in.effectiveMass*k)*vApproach);
    // The elastic part is w' (S, M); damping scales both (w' -> fn/|S|)
    const double scale = out.normalForce/Sn;
    out.couple = scale*r.areaMoment;

    const double nu = in.material.poissonsRatio;
    const double kt = k*2*(1 - nu)/(2 - nu);
    contactInput tin = in;
    tin.region.normal = n;
    out.tangentialForce = tangentialForce
    (
        tin, h, kt, c*std::sqrt(in.effectiveMass*kt), out.normalForce, out.sliding
    );
    out.force = scale*S + out.tangentialForce;
    h.maxNormalForce = std::max(h.maxNormalForce, out.normalForce);
    return out;
}


double potentialContactLaw::contactTime
(
    const pairMaterial& m, double effectiveMass, double effectiveRadius,
    double characteristicLength, double v
) const
{
    // On spheres the force is the volume law's Y* V/l_c = K d^2 (V >> V0;
    // below, softer: longer)
    const double K = M_PI*m.effectiveModulus*effectiveRadius/characteristicLength;
    return 2.8044*std::cbrt(3*effectiveMass/(2*K*v));
}

} // End namespace immersedDEM
