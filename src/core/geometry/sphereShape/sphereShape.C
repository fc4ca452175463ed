#include "sphereShape.H"
#include "coreError.H"
#include "primitiveMeshes.H"

#include <cmath>

namespace immersedDEM
{

sphereShape::sphereShape(double R)
:
    shape(staticKind),
    R_(R),
    volume_(4.0/3.0*M_PI*R*R*R),
    moments_(vec3::Constant(0.4*volume_*R*R))
{
    if (!(std::isfinite(R) && R > 0))
    {
        throw coreError("sphere radius must be positive and finite, not " + std::to_string(R));
    }
}


axisAlignedBox sphereShape::localBox() const
{
    return axisAlignedBox(vec3::Constant(-R_), vec3::Constant(R_));
}


axisAlignedBox sphereShape::worldBox(const bodyPose& pose) const
{
    return axisAlignedBox(pose.position().array() - R_, pose.position().array() + R_);
}


surfacePoint sphereShape::closest(const vec3& p) const
{
    surfacePoint sp;
    const double r = p.norm();
    // At the centre every direction is closest: pick +x, deterministically
    sp.normal = r > 0 ? vec3(p/r) : vec3(vec3::UnitX());
    sp.point = R_*sp.normal;
    sp.distance = r - R_;
    sp.curvature = (mat3::Identity() - sp.normal*sp.normal.transpose())/R_;
    return sp;
}


triangleSoup sphereShape::surface() const
{
    return primitiveMeshes::icosphere(R_, 3);
}

} // End namespace immersedDEM
