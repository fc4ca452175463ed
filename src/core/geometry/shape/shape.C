#include "shape.H"

namespace immersedDEM
{

axisAlignedBox shape::worldBox(const bodyPose& pose) const
{
    return pose.toWorld(localBox());
}


namespace
{

surfacePoint toWorld(const bodyPose& pose, surfacePoint sp)
{
    sp.point = pose.toWorld(sp.point);
    sp.normal = pose.vectorToWorld(sp.normal);
    sp.curvature = pose.rotation()*sp.curvature*pose.rotation().transpose();
    return sp;
}

} // End anonymous namespace


surfacePoint shape::closest(const bodyPose& pose, const vec3& p) const
{
    return toWorld(pose, closest(pose.toBody(p)));
}


surfacePoint shape::closest
(
    const bodyPose& pose, const vec3& p, double distanceBound
) const
{
    return toWorld(pose, closest(pose.toBody(p), distanceBound));
}

} // End namespace immersedDEM
