#include "periodicBox.H"
#include "coreError.H"

#include <cmath>
#include <limits>
#include <sstream>

namespace immersedDEM
{

void periodicBox::addDirection(const vec3& L, const std::string& name)
{
    const double len = L.norm();
    if (!(len > 0) || !std::isfinite(len))
    {
        throw coreError
        (
            "Periodic direction '" + name + "': its period vector is zero or"
            " not finite; a translational cyclic patch needs the translation"
            " onto its neighbour (separationVector)"
        );
    }
    for (int k = 0; k < n_; ++k)
    {
        if (std::abs(L.dot(period_[k])) > 1e-9*len*length_[k])
        {
            // The same direction twice (both halves of a cyclic pair, or two
            // pairs with one translation) is one direction
            if ((L.cross(period_[k])).norm() <= 1e-9*len*length_[k]) return;
            std::ostringstream msg;
            msg << "Periodic directions '" << name_[k] << "' and '" << name
                << "' are not orthogonal: the bodies' periodicity supports"
                << " mutually orthogonal translations only (a box-shaped"
                << " periodic domain)";
            throw coreError(msg.str());
        }
    }
    if (n_ == 3)
    {
        throw coreError("More than three periodic directions ('" + name + "')");
    }
    period_[n_] = L;
    unit_[n_] = L/len;
    length_[n_] = len;
    name_[n_] = name;
    ++n_;
}


double periodicBox::shortestPeriod() const
{
    double l = std::numeric_limits<double>::infinity();
    for (int k = 0; k < n_; ++k) l = std::min(l, length_[k]);
    return l;
}


vec3 periodicBox::nearestShift(const vec3& from, const vec3& to) const
{
    vec3 s = vec3::Zero();
    if (n_ == 0) return s;
    const vec3 d = to - from;
    for (int k = 0; k < n_; ++k)
    {
        const double m = std::round(d.dot(unit_[k])/length_[k]);
        if (m != 0) s -= m*period_[k];
    }
    return s;
}


periodicBox::periods periodicBox::wrap(vec3& x) const
{
    periods n{0, 0, 0};
    for (int k = 0; k < n_; ++k)
    {
        const double t = (x - origin_).dot(unit_[k])/length_[k];
        const double m = std::floor(t);
        if (m != 0)
        {
            n[k] = long(m);
            x -= m*period_[k];
        }
    }
    return n;
}


vec3 periodicBox::translation(const periods& n) const
{
    vec3 s = vec3::Zero();
    for (int k = 0; k < n_; ++k)
    {
        if (n[k] != 0) s += double(n[k])*period_[k];
    }
    return s;
}


std::vector<vec3> periodicBox::imageShifts(const axisAlignedBox& box) const
{
    if (n_ == 0) return {vec3::Zero()};
    const vec3 c = 0.5*(box.min + box.max) - origin_;
    const vec3 h = 0.5*(box.max - box.min);
    std::vector<vec3> result{vec3::Zero()};
    for (int k = 0; k < n_; ++k)
    {
        // The box's extent along the direction, from the cell's corner
        const double mid = c.dot(unit_[k]);
        const double half = h.dot(unit_[k].cwiseAbs());
        const double lo = mid - half, hi = mid + half;
        std::vector<vec3> next;
        for (const int m : {-1, 0, 1})
        {
            if (lo + m*length_[k] < length_[k] && hi + m*length_[k] > 0)
            {
                for (const vec3& s : result)
                {
                    next.push_back(s + double(m)*period_[k]);
                }
            }
        }
        result.swap(next);
    }
    return result;
}


void periodicBox::check(const std::string& body, double d, double reach) const
{
    for (int k = 0; k < n_; ++k)
    {
        if (length_[k] < 2*(d + reach))
        {
            std::ostringstream msg;
            msg.precision(4);
            msg << "Body '" << body << "' (bounding diameter " << d << " m) is"
                << " too large for the period " << length_[k] << " m of the"
                << " periodic direction '" << name_[k] << "': a period must be"
                << " at least twice the largest bounding diameter plus the"
                << " contacts' reach (" << 2*(d + reach) << " m here), so that"
                << " a body meets one image of another only. Make the"
                << " periodic domain longer, or the bodies smaller";
            throw coreError(msg.str());
        }
    }
}

} // End namespace immersedDEM
