#include "shape.H"

namespace immersedDEM
{

axisAlignedBox shape::worldBox(const bodyPose& pose) const
{
    return pose.toWorld(localBox());
}


surfacePoint shape::closest(const bodyPose& pose, const vec3& p) const
{
    surfacePoint sp = closest(pose.toBody(p));
    sp.point = pose.toWorld(sp.point);
    sp.normal = pose.vectorToWorld(sp.normal);
    return sp;
}


surfacePoint shape::closest
(
    const bodyPose& pose, const vec3& p, double distanceBound
) const
{
    surfacePoint sp = closest(pose.toBody(p), distanceBound);
    sp.point = pose.toWorld(sp.point);
    sp.normal = pose.vectorToWorld(sp.normal);
    return sp;
}

} // End namespace immersedDEM
