#include "wallMeshShape.H"
#include "coreError.H"

#include <limits>

namespace immersedDEM
{

namespace
{

const triangleSoup& nonEmpty(const triangleSoup& s, const std::string& name)
{
    if (s.faces.empty())
    {
        throw coreError("Wall surface \"" + name + "\" has no triangles");
    }
    return s;
}

} // End anonymous namespace


wallMeshShape::wallMeshShape
(
    triangleSoup surface,
    const std::string& name,
    double thickness
)
:
    surface_(std::move(surface)),
    distance_(nonEmpty(surface_, name))
{
    if (!(thickness > 0))
    {
        throw coreError("Wall surface \"" + name + "\": thickness must be positive");
    }
    for (const vec3& p : surface_.points)
    {
        box_.add(p);
    }
    box_ = box_.inflated(thickness);
    for (const vec3& p : surface_.points)
    {
        radius_ = std::max(radius_, p.norm());
    }
    radius_ += thickness;
}


double wallMeshShape::volume() const
{
    // A wall has no mass properties: it never moves by forces. Zero, not
    // infinity, so no arithmetic on it can raise a floating-point trap
    // (OpenFOAM runs with them enabled)
    return 0;
}


vec3 wallMeshShape::principalMoments() const
{
    return vec3::Zero();
}


surfacePoint wallMeshShape::closest(const vec3& p, double bound) const
{
    if (!(bound < 1e100))
    {
        return distance_.closest(p);    // no bound; and no overflow below
    }
    const double b = bound*(1 + 1e-9) + 1e-12*radius_;
    return distance_.closest(p, b*b);
}

} // End namespace immersedDEM
