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


// Volume of [lo, hi] inside the quadric n.(x - p) + 1/2 y^T K y <= 0, y the
// tangential part of x - p (the surface's second-order model at its point
// p), integrated exactly along 8 x 8 columns of the axis nearest n
double quadricVolume
(
    const vec3& lo, const vec3& hi, const vec3& p, const vec3& n, const mat3& curvature
)
{
    constexpr int k = 8;
    int ax = 0;
    n.cwiseAbs().maxCoeff(&ax);
    const int u = (ax + 1) % 3, w = (ax + 2) % 3;
    const mat3 P = mat3::Identity() - n*n.transpose();
    const mat3 A = P*curvature*P;
    const vec3 span = hi - lo;
    const double du = span[u]/k, dw = span[w]/k;
    // f(t) = a t^2 + b t + c along a column, t the coordinate along ax;
    // with y = x - p, y_ax = t - p_ax and (s_u, s_w) the column's offsets
    // from p: b and c are polynomials in s_u, s_w (no matrix per column)
    const double a = 0.5*A(ax, ax);
    const double pa = p[ax];
    const double b0 = n[ax] - A(ax, ax)*pa;
    const double c0 = -n[ax]*pa + 0.5*A(ax, ax)*pa*pa;
    const double t0 = lo[ax], t1 = hi[ax];
    double volume = 0;
    for (int i = 0; i < k; ++i)
    {
        const double su = lo[u] + (i + 0.5)*du - p[u];
        const double bu = b0 + A(ax, u)*su;
        const double cu = c0 + n[u]*su + 0.5*A(u, u)*su*su - A(ax, u)*pa*su;
        for (int j = 0; j < k; ++j)
        {
            const double sw = lo[w] + (j + 0.5)*dw - p[w];
            const double b = bu + A(ax, w)*sw;
            const double c = cu + n[w]*sw + 0.5*A(w, w)*sw*sw - A(ax, w)*pa*sw + A(u, w)*su*sw;
            double length = 0;
            if (std::abs(a)*span[ax] <= 1e-9*std::abs(b))
            {
                // Linear: b t + c <= 0
                if (std::abs(b) < 1e-300)
                {
                    length = c <= 0 ? t1 - t0 : 0;
                }
                else
                {
                    const double r = -c/b;
                    length = b > 0
                        ? std::max(0.0, std::min(t1, r) - t0)
                        : std::max(0.0, t1 - std::max(t0, r));
                }
            }
            else
            {
                const double D = b*b - 4*a*c;
                if (D < 0)
                {
                    length = a > 0 ? 0 : t1 - t0;
                }
                else
                {
                    const double q = -0.5*(b + (b >= 0 ? 1 : -1)*std::sqrt(D));
                    double r0 = q/a, r1 = q != 0 ? c/q : r0;
                    if (r0 > r1) std::swap(r0, r1);
                    const double between =
                        std::max(0.0, std::min(t1, r1) - std::max(t0, r0));
                    length = a > 0 ? between : (t1 - t0) - between;
                }
            }
            volume += length*du*dw;
        }
    }
    return volume;
}


// The fraction of [lo, hi] given the closest surface point sp of a point x
// in it (r: the largest distance from x to a corner of the box). Each
// piece's query is bounded by its distance to sp's point (the surface is
// at most that far), which lets a mesh prune its search to the triangles
// near it; the result does not depend on the bound
double fractionGiven
(
    const shape& s, const bodyPose& pose, const vec3& lo, const vec3& hi,
    int levels, const vec3& x, const surfacePoint& sp, double r, long& queries
)
{
    if (sp.distance >= r) return 0;
    if (sp.distance <= -r) return 1;
    const vec3 c = 0.5*(lo + hi);
    if (levels > 0)
    {
        const double rPiece = 0.25*(hi - lo).norm();
        double sum = 0;
        for (int k = 0; k < 8; ++k)
        {
            vec3 a = lo, b = c;
            for (int d = 0; d < 3; ++d)
            {
                if ((k >> d) & 1) { a[d] = c[d]; b[d] = hi[d]; }
            }
            const vec3 m = 0.5*(a + b);
            const surfacePoint spPiece = s.closest(pose, m, (m - sp.point).norm());
            ++queries;
            sum += fractionGiven(s, pose, a, b, levels - 1, m, spPiece, rPiece, queries);
        }
        return sum/8;
    }
    const double V = (hi - lo).prod();
    return std::min(1.0, planeVolume(lo, hi, x, sp.distance, sp.normal)/V);
}

} // End anonymous namespace


double boxFraction::quadric
(
    const vec3& lo, const vec3& hi, const vec3& x, const surfacePoint& sp
)
{
    const vec3 far = (hi - x).cwiseAbs().cwiseMax((x - lo).cwiseAbs());
    const double r = far.norm();
    if (sp.distance >= r) return 0;
    if (sp.distance <= -r) return 1;
    const double V = (hi - lo).prod();
    return std::min
    (
        1.0,
        std::max(0.0, quadricVolume(lo, hi, sp.point, sp.normal, sp.curvature)/V)
    );
}


double boxFraction::fromQuery
(
    const shape& s, const bodyPose& pose,
    const vec3& lo, const vec3& hi,
    const vec3& x, const surfacePoint& sp, long* queries
)
{
    const vec3 far = (hi - x).cwiseAbs().cwiseMax((x - lo).cwiseAbs());
    const double r = far.norm();
    if (sp.distance >= r) return 0;
    if (sp.distance <= -r) return 1;
    if (!s.creaseWithin(pose, x, r))
    {
        return quadric(lo, hi, x, sp);
    }
    return given(s, pose, lo, hi, 1, x, sp, queries);
}


double boxFraction::of
(
    const shape& s, const bodyPose& pose,
    const vec3& lo, const vec3& hi,
    int levels, long* queries
)
{
    const vec3 c = 0.5*(lo + hi);
    const surfacePoint sp = s.closest(pose, c);
    long q = 1;
    const double f =
        fractionGiven(s, pose, lo, hi, levels, c, sp, 0.5*(hi - lo).norm(), q);
    if (queries) *queries += q;
    return f;
}


double boxFraction::given
(
    const shape& s, const bodyPose& pose,
    const vec3& lo, const vec3& hi, int levels,
    const vec3& x, const surfacePoint& sp, long* queries
)
{
    // The largest distance from x to a corner of the box
    const vec3 far = (hi - x).cwiseAbs().cwiseMax((x - lo).cwiseAbs());
    long q = 0;
    const double f = fractionGiven(s, pose, lo, hi, levels, x, sp, far.norm(), q);
    if (queries) *queries += q;
    return f;
}

} // End namespace immersedDEM
