#include "shape.H"

#include <algorithm>
#include <map>

namespace immersedDEM
{

axisAlignedBox shape::worldBox(const bodyPose& pose) const
{
    return pose.toWorld(localBox());
}


double shape::flatFaceOf(const triangleSoup& s)
{
    // Union-find over edge-adjacent triangles whose normals agree within
    // 1e-4 rad (single-precision STL coordinates leave ~1e-7)
    const size_t n = s.faces.size();
    std::vector<vec3> an(n);
    std::vector<int> parent(n);
    for (size_t f = 0; f < n; ++f)
    {
        const triFace& t = s.faces[f];
        an[f] = 0.5*(s.points[t[1]] - s.points[t[0]]).cross(s.points[t[2]] - s.points[t[0]]);
        parent[f] = int(f);
    }
    auto root = [&](int f)
    {
        while (parent[f] != f) f = parent[f] = parent[parent[f]];
        return f;
    };
    std::map<std::pair<int, int>, int> edgeFace;
    for (size_t f = 0; f < n; ++f)
    {
        const triFace& t = s.faces[f];
        for (int k = 0; k < 3; ++k)
        {
            const int a = t[k], b = t[(k + 1)%3];
            const auto key = std::make_pair(std::min(a, b), std::max(a, b));
            const auto it = edgeFace.find(key);
            if (it == edgeFace.end())
            {
                edgeFace.emplace(key, int(f));
                continue;
            }
            const vec3& m = an[it->second];
            const double la = an[f].norm(), lb = m.norm();
            if (la > 0 && lb > 0 && an[f].dot(m) > (1 - 5e-9)*la*lb)
            {
                parent[root(int(f))] = root(it->second);
            }
        }
    }
    std::vector<double> area(n, 0);
    double largest = 0;
    for (size_t f = 0; f < n; ++f)
    {
        const int r = root(int(f));
        area[r] += an[f].norm();
        largest = std::max(largest, area[r]);
    }
    return largest;
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


bool shape::closestNear
(
    const bodyPose& pose, const vec3& p, double radius, double distanceBound,
    surfacePoint& sp
) const
{
    surfacePoint body;
    if (!closestNear(pose.toBody(p), radius, distanceBound, body))
    {
        return false;
    }
    sp = toWorld(pose, body);
    return true;
}

} // End namespace immersedDEM
