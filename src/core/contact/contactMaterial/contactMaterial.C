#include "contactMaterial.H"
#include "coreError.H"

#include <algorithm>
#include <cmath>

namespace immersedDEM
{

void contactMaterial::check() const
{
    auto bad = [&](const std::string& what, double v, const std::string& range)
    {
        throw coreError
        (
            "Material '" + name + "': " + what + " is " + std::to_string(v)
          + "; it must be " + range
        );
    };
    if (!(youngsModulus > 0 && std::isfinite(youngsModulus)))
        bad("youngsModulus", youngsModulus, "> 0");
    if (!(poissonsRatio >= 0 && poissonsRatio <= 0.5))
        bad("poissonsRatio", poissonsRatio, "in [0, 0.5]");
    if (!(restitution > 0 && restitution <= 1))
        bad("restitution", restitution, "in (0, 1]");
    if (!(friction >= 0 && std::isfinite(friction)))
        bad("friction", friction, ">= 0");
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
    p.poissonsRatio = 0.5*(a.poissonsRatio + b.poissonsRatio);
    return p;
}

} // End namespace immersedDEM
