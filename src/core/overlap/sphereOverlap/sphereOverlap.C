#include "sphereOverlap.H"
#include "sphereShape.H"
#include "halfSpaceShape.H"
#include "coreError.H"

#include <cmath>

namespace immersedDEM
{

contactGeometry sphereOverlap::lens(const vec3& c1, double R1, const vec3& c2, double R2)
{
    contactGeometry g;
    contactRegion r;
    if (lensRegion(c1, R1, c2, R2, r))
    {
        g.regions.push_back(r);
    }
    return g;
}


contactGeometry sphereOverlap::cap(const vec3& p, const vec3& n, const vec3& c, double R)
{
    contactGeometry g;
    contactRegion r;
    if (capRegion(p, n, c, R, r))
    {
        g.regions.push_back(r);
    }
    return g;
}


contactGeometry sphereOverlap::evaluate
(
    const shape& A, const bodyPose& pA,
    const shape& B, const bodyPose& pB,
    const overlapSettings&
) const
{
    const auto* a = shapeAs<sphereShape>(A);
    const auto* b = shapeAs<sphereShape>(B);
    const auto* wa = shapeAs<halfSpaceShape>(A);
    const auto* wb = shapeAs<halfSpaceShape>(B);
    if (wa && b)
    {
        return cap(pA.position(), pA.vectorToWorld(vec3::UnitZ()), pB.position(), b->radius());
    }
    if (a && wb)
    {
        contactGeometry g =
            cap(pB.position(), pB.vectorToWorld(vec3::UnitZ()), pA.position(), a->radius());
        for (contactRegion& r : g.regions) r.normal = -r.normal;
        return g;
    }
    if (!a || !b)
    {
        throw coreError
        (
            "Overlap method 'sphere' needs two spheres or a sphere and a plane, not " + A.type()
          + " and " + B.type() + "; use virtualMesh"
        );
    }
    return lens(pA.position(), a->radius(), pB.position(), b->radius());
}

} // End namespace immersedDEM
