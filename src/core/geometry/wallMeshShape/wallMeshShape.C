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
    return std::numeric_limits<double>::infinity();
}


vec3 wallMeshShape::principalMoments() const
{
    return vec3::Constant(std::numeric_limits<double>::infinity());
}


surfacePoint wallMeshShape::closest(const vec3& p, double bound) const
{
    const double b = bound*(1 + 1e-9) + 1e-12*radius_;
    return distance_.closest(p, b*b);
}

} // End namespace immersedDEM
