#include "sphereOverlap.H"
#include "sphereShape.H"
#include "halfSpaceShape.H"
#include "coreError.H"

#include <cmath>

namespace immersedDEM
{

bool sphereOverlap::lensRegion
(
    const vec3& c1, double R1, const vec3& c2, double R2, contactRegion& r,
    double* distance
)
{
    const vec3 d12 = c2 - c1;
    const double d2 = d12.squaredNorm();
    const double R12 = R1 + R2;
    if (d2 >= R12*R12)
    {
        return false;
    }
    const double d = std::sqrt(d2);
    if (d >= R12)
    {
        return false;
    }
    if (distance)
    {
        *distance = d;
    }
    r = contactRegion();
    r.normal = d > 0 ? vec3(d12/d) : vec3(vec3::UnitX());

    if (d <= std::abs(R1 - R2))
    {
        // One ball inside the other
        const bool oneSmaller = R1 <= R2;
        const double Rs = oneSmaller ? R1 : R2;
        r.volume = 4.0/3.0*M_PI*Rs*Rs*Rs;
        r.point = oneSmaller ? c1 : c2;
        r.area = 0;
        return true;
    }

    // The discs' plane at distance x from c1 along the centre line
    const double x = (d2 + R1*R1 - R2*R2)/(2*d);
    const double h1 = R1 - x;           // cap of ball 1 beyond the plane
    const double h2 = R2 - (d - x);     // cap of ball 2 before the plane
    const double V1 = capVolume(R1, h1);
    const double V2 = capVolume(R2, h2);
    // Centroid of a cap of height hc from its ball's centre:
    // 3(2R-hc)^2/(4(3R-hc)); both over one division
    const double s1 = 2*R1 - h1, s2 = 2*R2 - h2;
    const double q1 = 3*R1 - h1, q2 = 3*R2 - h2;
    const double quarter = 0.75/(q1*q2);
    const double z1 = s1*s1*q2*quarter;
    const double z2 = s2*s2*q1*quarter;
    r.volume = V1 + V2;
    r.point = (V1*(c1 + z1*r.normal) + V2*(c2 - z2*r.normal))*(1/r.volume);
    r.area = M_PI*std::max(0.0, R1*R1 - x*x);
    return true;
}


bool sphereOverlap::capRegion
(
    const vec3& p, const vec3& n, const vec3& c, double R, contactRegion& r
)
{
    const double dist = n.dot(c - p);
    if (dist >= R)
    {
        return false;
    }
    r = contactRegion();
    r.normal = n;
    if (dist <= -R)
    {
        r.volume = 4.0/3.0*M_PI*R*R*R;
        r.point = c;
        return true;
    }
    const double hc = R - dist;
    r.volume = capVolume(R, hc);
    const double s = 2*R - hc;
    r.point = c - (0.75*s*s/(3*R - hc))*n;
    r.area = M_PI*(R*R - dist*dist);
    return true;
}


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
