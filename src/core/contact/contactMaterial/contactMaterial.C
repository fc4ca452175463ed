#include "contactMaterial.H"
#include "coreError.H"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace immersedDEM
{

void contactMaterial::check() const
{
    auto bad = [&](const std::string& what, double v, const std::string& range)
    {
        std::ostringstream msg;
        msg << "Material '" << name << "': " << what << " is " << v
            << "; it must be " << range;
        throw coreError(msg.str());
    };
    // Stiffer than any solid (diamond: 1.2e12 Pa) is a typing error, and
    // would make the automatic DEM step vanish
    if (!(youngsModulus > 0 && youngsModulus <= maxYoungsModulus))
        bad("youngsModulus", youngsModulus, "in (0, 1e13] Pa");
    if (!(poissonsRatio >= 0 && poissonsRatio <= 0.5))
        bad("poissonsRatio", poissonsRatio, "in [0, 0.5]");
    if (!(restitution > 0 && restitution <= 1))
        bad("restitution", restitution, "in (0, 1]");
    if (!(friction >= 0 && std::isfinite(friction)))
        bad("friction", friction, ">= 0");
    if (!(rollingFriction >= 0 && std::isfinite(rollingFriction)))
        bad("rollingFriction", rollingFriction, ">= 0");
}


pairMaterial pairMaterial::of(const contactMaterial& a, const contactMaterial& b)
{
    auto compliance = [](const contactMaterial& m)
    {
        return (1 - m.poissonsRatio*m.poissonsRatio)/m.youngsModulus;
    };
    auto shearCompliance = [](const contactMaterial& m)
    {
        return 2*(2 - m.poissonsRatio)*(1 + m.poissonsRatio)/m.youngsModulus;
    };
    pairMaterial p;
    p.effectiveModulus = 1/(compliance(a) + compliance(b));
    p.effectiveShearModulus = 1/(shearCompliance(a) + shearCompliance(b));
    p.restitution = std::min(a.restitution, b.restitution);
    p.friction = std::min(a.friction, b.friction);
    p.rollingFriction = std::min(a.rollingFriction, b.rollingFriction);
    p.poissonsRatio = 0.5*(a.poissonsRatio + b.poissonsRatio);
    return p;
}

} // End namespace immersedDEM
