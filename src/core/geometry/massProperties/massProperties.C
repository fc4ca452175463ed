#include "massProperties.H"

#include <Eigen/Eigenvalues>

namespace immersedDEM
{

namespace
{

// A reference point near the body keeps the tetrahedron sums well
// conditioned for a body far from the file's origin.
vec3 referencePoint(const triangleSoup& soup)
{
    vec3 o = vec3::Zero();
    if (!soup.points.empty())
    {
        for (const vec3& p : soup.points)
        {
            o += p;
        }
        o /= double(soup.points.size());
    }
    return o;
}

} // End anonymous namespace


double massProperties::signedVolume(const triangleSoup& soup)
{
    const vec3 o = referencePoint(soup);
    double sixV = 0;
    for (const triFace& f : soup.faces)
    {
        const vec3 a = soup.points[f[0]] - o;
        const vec3 b = soup.points[f[1]] - o;
        const vec3 c = soup.points[f[2]] - o;
        sixV += a.dot(b.cross(c));
    }
    return sixV/6.0;
}


massProperties massProperties::of(const triangleSoup& soup)
{
    const vec3 o = referencePoint(soup);

    // Tetrahedron (o, a, b, c) with det = a.(b x c):
    //   volume      det/6
    //   1st moment  det/24 (a + b + c)
    //   2nd moment  det/120 (aa' + bb' + cc' + ss'),  s = a + b + c
    double sixV = 0;
    vec3 first = vec3::Zero();
    mat3 second = mat3::Zero();

    for (const triFace& f : soup.faces)
    {
        const vec3 a = soup.points[f[0]] - o;
        const vec3 b = soup.points[f[1]] - o;
        const vec3 c = soup.points[f[2]] - o;
        const double det = a.dot(b.cross(c));
        const vec3 s = a + b + c;

        sixV += det;
        first += det*s;
        second += det*(a*a.transpose() + b*b.transpose() + c*c.transpose() + s*s.transpose());
    }

    massProperties mp;
    mp.volume = sixV/6.0;
    if (mp.volume == 0)
    {
        return mp;
    }

    const vec3 cRel = (first/24.0)/mp.volume;
    mp.centroid = o + cRel;

    // Second moment about the centroid (parallel axis), then inertia
    const mat3 C = second/120.0 - mp.volume*cRel*cRel.transpose();
    mp.inertia = C.trace()*mat3::Identity() - C;
    mp.inertia = 0.5*(mp.inertia + mp.inertia.transpose());

    Eigen::SelfAdjointEigenSolver<mat3> eig(mp.inertia);
    mp.principalMoments = eig.eigenvalues();
    mp.principalAxes = eig.eigenvectors();
    if (mp.principalAxes.determinant() < 0)
    {
        mp.principalAxes.col(2) = -mp.principalAxes.col(2);
    }

    return mp;
}

} // End namespace immersedDEM
