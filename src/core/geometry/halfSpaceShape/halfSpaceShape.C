#include "halfSpaceShape.H"
#include "coreError.H"

#include <limits>

namespace immersedDEM
{

bodyPose halfSpaceShape::poseOf(const vec3& point, const vec3& normal)
{
    if (!(normal.norm() > 0))
    {
        throw coreError("plane wall: the normal must not be a zero vector");
    }
    return bodyPose(point, quat::FromTwoVectors(vec3::UnitZ(), normal.normalized()));
}


double halfSpaceShape::volume() const
{
    // A wall has no mass properties: it never moves by forces. Zero, not
    // infinity, so no arithmetic on it can raise a floating-point trap
    // (OpenFOAM runs with them enabled)
    return 0;
}


vec3 halfSpaceShape::principalMoments() const
{
    return vec3::Zero();
}


axisAlignedBox halfSpaceShape::localBox() const
{
    return axisAlignedBox(vec3(-extent, -extent, -extent), vec3(extent, extent, 0));
}


surfacePoint halfSpaceShape::closest(const vec3& p) const
{
    surfacePoint sp;
    sp.point = vec3(p.x(), p.y(), 0);
    sp.normal = vec3::UnitZ();
    sp.distance = p.z();
    return sp;
}


triangleSoup halfSpaceShape::surface() const
{
    const double s = outputSize;
    triangleSoup t;
    t.points = {{-s, -s, 0}, {s, -s, 0}, {s, s, 0}, {-s, s, 0}};
    t.faces = {{0, 1, 2}, {0, 2, 3}};
    return t;
}

} // End namespace immersedDEM
