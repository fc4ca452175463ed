#include "fluidImpedance.H"
#include <algorithm>
#include <cmath>

namespace immersedDEM
{
namespace fluidImpedance
{

namespace
{
constexpr double pi = 3.14159265358979323846;
}


double besselRatio10(const double q)
{
    // Past q = 50 the asymptotic series of K1/K0 (relative error below
    // 1e-8 there); below, the functions themselves
    if (q > 50)
    {
        const double x = 1/q;
        return 1 + x*(0.5 + x*(-0.125 + x*(0.125 - x*0.1171875)));
    }
    return std::cyl_bessel_k(1.0, q)/std::cyl_bessel_k(0.0, q);
}


double lens(const double R, const double r, const double d, const bool depth2D)
{
    if (!(R > 0) || !(r > 0) || d >= R + r)
    {
        return 0;
    }
    const double small = std::min(R, r);
    if (d <= std::abs(R - r))
    {
        return depth2D ? pi*small*small : 4.0/3*pi*small*small*small;
    }
    if (depth2D)
    {
        // Two circular segments
        const double a1 = std::acos((d*d + R*R - r*r)/(2*d*R));
        const double a2 = std::acos((d*d + r*r - R*R)/(2*d*r));
        return R*R*(a1 - std::sin(2*a1)/2) + r*r*(a2 - std::sin(2*a2)/2);
    }
    const double s = R + r - d;
    return pi*s*s*(d*d + 2*d*r - 3*r*r + 2*d*R + 6*r*R - 3*R*R)/(12*d);
}


double surroundingFraction
(
    const double a,
    const std::vector<std::pair<double, double>>& others,
    const bool depth2D
)
{
    if (!(a > 0))
    {
        return 0;
    }
    const double R = 2*a;
    const double shell = depth2D
        ? pi*(R*R - a*a)
        : 4.0/3*pi*(R*R*R - a*a*a);
    double filled = 0;
    for (const auto& o : others)
    {
        // (what of the other lies within the shell, not within a)
        filled +=
            lens(R, o.second, o.first, depth2D) - lens(a, o.second, o.first, depth2D);
    }
    return std::min(std::max(filled/shell, 0.0), 1.0);
}


coefficients estimate
(
    const bodySize& size,
    const double rho,
    const double nu,
    const double deltaT
)
{
    coefficients c;
    if (!(deltaT > 0) || !(rho > 0) || !(size.volume > 0))
    {
        return c;
    }
    const double s = 1/deltaT;
    const double mu = rho*std::max(nu, 0.0);
    // The forcing reaches half a cell beyond the surface
    const double grow = 0.5*std::max(size.cellSize, 0.0);
    const double R = std::max(size.circumscribedRadius, 0.0) + grow;

    if (size.depth > 0)
    {
        // 2D, per unit length times the depth
        const double L = size.depth;
        const double a =
            std::max(size.area/(2*pi), std::sqrt(size.volume/pi)) + grow;
        const double aV = std::sqrt(size.volume/pi) + grow;
        const double Rc = std::max(R, a);
        const double phi = std::min(std::max(size.solidFraction, 0.0), 0.6);
        c.addedMass = rho*pi*a*a*L*(1 + phi)/(1 - phi);
        c.nominalAddedMass = rho*size.volume*L;
        // Added moment: the fluid between the equivalent disc and the
        // circumscribed one, (pi/2) rho (R^4 - aV^4)
        c.addedInertia = 0.5*pi*rho*(std::pow(Rc, 4) - std::pow(aV, 4))*L;
        if (mu > 0)
        {
            const double q = a*std::sqrt(s/nu);
            const double k10 = besselRatio10(q);
            c.damping = 4*pi*mu*q*k10*L;
            c.angularDamping = 2*pi*mu*a*a*(2 + q/k10)*L;
        }
        return c;
    }

    // 3D
    const double a = std::max
    (
        std::sqrt(std::max(size.area, 0.0)/(4*pi)),
        std::cbrt(3*size.volume/(4*pi))
    ) + grow;
    const double aV = std::cbrt(3*size.volume/(4*pi)) + grow;
    const double Rc = std::max(R, a);
    const double phi = std::min(std::max(size.solidFraction, 0.0), 0.6);
    c.addedMass = 0.5*rho*(4.0/3)*pi*a*a*a*(1 + 2*phi)/(1 - phi);
    c.nominalAddedMass = 0.5*rho*size.volume;
    // (8/15) pi rho (R^5 - aV^5): the moments of the two balls
    c.addedInertia = (8.0/15)*pi*rho*(std::pow(Rc, 5) - std::pow(aV, 5));
    if (mu > 0)
    {
        const double q = a*std::sqrt(s/nu);
        c.damping = 6*pi*mu*a*(1 + q);
        c.angularDamping = 8*pi*mu*a*a*a*(1 + q*q/(3*(1 + q)));
    }
    return c;
}

} // End namespace fluidImpedance
} // End namespace immersedDEM
