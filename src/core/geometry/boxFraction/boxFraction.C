#include "boxFraction.H"

#include <algorithm>
#include <cmath>

namespace immersedDEM
{

namespace
{

// Volume of [lo, hi] on the inside of the plane d + n.(x - c) <= 0
double planeVolume
(
    const vec3& lo, const vec3& hi, const vec3& c, double d, const vec3& n
)
{
    constexpr int k = 8;
    int ax = 0;
    n.cwiseAbs().maxCoeff(&ax);
    const int u = (ax + 1) % 3, w = (ax + 2) % 3;
    const vec3 span = hi - lo;
    const double du = span[u]/k, dw = span[w]/k;
    double volume = 0;
    for (int i = 0; i < k; ++i)
    {
        for (int j = 0; j < k; ++j)
        {
            vec3 x = c;
            x[u] = lo[u] + (i + 0.5)*du;
            x[w] = lo[w] + (j + 0.5)*dw;
            // d + n.(x - c) + n_ax (t - c_ax) <= 0 along the column
            const double q = -(d + n.dot(x - c));
            double a = lo[ax], b = hi[ax];
            if (std::abs(n[ax]) < 1e-12)
            {
                if (q < 0) b = a;
            }
            else if (n[ax] > 0)
            {
                b = std::min(b, c[ax] + q/n[ax]);
            }
            else
            {
                a = std::max(a, c[ax] + q/n[ax]);
            }
            volume += std::max(0.0, b - a)*du*dw;
        }
    }
    return volume;
}


double fraction
(
    const shape& s, const bodyPose& pose, const vec3& lo, const vec3& hi,
    int levels, long& queries
)
{
    const vec3 c = 0.5*(lo + hi);
    const double r = 0.5*(hi - lo).norm();
    const surfacePoint sp = s.closest(pose, c);
    ++queries;
    if (sp.distance >= r) return 0;
    if (sp.distance <= -r) return 1;
    if (levels > 0)
    {
        double sum = 0;
        for (int k = 0; k < 8; ++k)
        {
            vec3 a = lo, b = c;
            for (int d = 0; d < 3; ++d)
            {
                if ((k >> d) & 1) { a[d] = c[d]; b[d] = hi[d]; }
            }
            sum += fraction(s, pose, a, b, levels - 1, queries);
        }
        return sum/8;
    }
    const double V = (hi - lo).prod();
    return std::min(1.0, planeVolume(lo, hi, c, sp.distance, sp.normal)/V);
}

} // End anonymous namespace


double boxFraction::of
(
    const shape& s, const bodyPose& pose,
    const vec3& lo, const vec3& hi,
    int levels, long* queries
)
{
    long q = 0;
    const double f = fraction(s, pose, lo, hi, levels, q);
    if (queries) *queries += q;
    return f;
}

} // End namespace immersedDEM
