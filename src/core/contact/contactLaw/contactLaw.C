#include "contactLaw.H"
#include "coreError.H"
#include "overlapVolumeContactLaw.H"
#include "hertzMindlinContactLaw.H"
#include "potentialContactLaw.H"

#include <cmath>
#include <functional>
#include <map>

namespace immersedDEM
{

namespace
{

const std::map<std::string, std::function<std::unique_ptr<contactLaw>()>>& table()
{
    static const std::map<std::string, std::function<std::unique_ptr<contactLaw>()>> t
    {
        {"volume", []{ return std::unique_ptr<contactLaw>(new overlapVolumeContactLaw()); }},
        {"hertzMindlin", []{ return std::unique_ptr<contactLaw>(new hertzMindlinContactLaw()); }},
        {"potential", []{ return std::unique_ptr<contactLaw>(new potentialContactLaw()); }}
    };
    return t;
}

} // End anonymous namespace


std::vector<std::string> contactLaw::types()
{
    std::vector<std::string> names;
    for (const auto& e : table()) names.push_back(e.first);
    return names;
}


std::unique_ptr<contactLaw> contactLaw::New(const std::string& type)
{
    const auto it = table().find(type);
    if (it == table().end())
    {
        std::string valid;
        for (const std::string& n : types()) valid += (valid.empty() ? "" : " ") + n;
        throw coreError
        (
            "Unknown contact law '" + type + "'; valid laws are (" + valid + ")"
        );
    }
    return it->second();
}


double contactLaw::twistingCouple
(
    const contactInput& in,
    contactHistory& h,
    const double normalForce,
    const double spin,
    const double spinInertia
)
{
    const double area = in.region.area;
    if (!(area > 0) || !(normalForce > 0) || !(spinInertia > 0) || !(in.dt > 0))
    {
        h.twist = 0;
        return 0;
    }
    const double a = std::sqrt(area/M_PI);
    const double stable = spinInertia*(0.5/in.dt)*(0.5/in.dt);
    const double k =
        std::min(16.0/3.0*in.material.effectiveShearModulus*a*a*a, stable);
    const double c = 2*std::sqrt(k*spinInertia);
    h.twist += spin*in.dt;
    // Sliding when the spring alone exceeds the limit: it holds the
    // limit, undamped (damping the sliding spin besides would make the
    // spring run backwards, and the friction viscous); sticking: the
    // spring and its damper, at most the limit
    const double limit = 2.0/3.0*in.material.friction*normalForce*a;
    const double spring = -k*h.twist;
    if (std::abs(spring) > limit)
    {
        h.twist = k > 0 ? std::copysign(limit, h.twist)/k : 0;
        return std::copysign(limit, spring);
    }
    const double couple = spring - c*spin;
    return std::abs(couple) > limit ? std::copysign(limit, couple) : couple;
}

} // End namespace immersedDEM
