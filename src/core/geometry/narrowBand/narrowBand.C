#include "narrowBand.H"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace immersedDEM
{

namespace
{

// Groups of at most this many points are settled or queried point by point
constexpr size_t leafSize = 8;

struct walk
{
    const shape& s;
    const bodyPose& pose;
    const std::vector<vec3>& x;
    const std::vector<double>& reach;
    std::vector<narrowBand::value>& out;
    long queries = 0;

    // The points order[begin, end); parent: the closest point of the
    // group above (its point bounds the distance of every query here)
    void group(std::vector<size_t>& order, size_t begin, size_t end, const surfacePoint* parent)
    {
        vec3 lo = vec3::Constant(std::numeric_limits<double>::max());
        vec3 hi = -lo;
        double reachMax = 0;
        for (size_t k = begin; k < end; ++k)
        {
            lo = lo.cwiseMin(x[order[k]]);
            hi = hi.cwiseMax(x[order[k]]);
            reachMax = std::max(reachMax, reach[order[k]]);
        }
        const vec3 q = 0.5*(lo + hi);
        const surfacePoint sq = parent
            ? s.closest(pose, q, (q - parent->point).norm())
            : s.closest(pose, q);
        ++queries;
        double spread = 0;
        for (size_t k = begin; k < end; ++k)
        {
            spread = std::max(spread, (x[order[k]] - q).norm());
        }
        if (std::abs(sq.distance) - spread > reachMax)
        {
            // Settled: every point has phi's sign and |phi| > its reach
            for (size_t k = begin; k < end; ++k)
            {
                narrowBand::value& v = out[order[k]];
                v.exact = false;
                v.phi = sq.distance > 0
                    ? std::abs(sq.distance) - spread : spread - std::abs(sq.distance);
            }
            return;
        }
        if (end - begin <= leafSize)
        {
            // Point by point: settled by q where they can be, else queried
            for (size_t k = begin; k < end; ++k)
            {
                const size_t i = order[k];
                narrowBand::value& v = out[i];
                const double far = (x[i] - q).norm();
                if (std::abs(sq.distance) - far > reach[i])
                {
                    v.exact = false;
                    v.phi = sq.distance > 0
                        ? std::abs(sq.distance) - far : far - std::abs(sq.distance);
                    continue;
                }
                v.sp = s.closest(pose, x[i], (x[i] - sq.point).norm());
                ++queries;
                v.phi = v.sp.distance;
                v.exact = true;
            }
            return;
        }
        // Halve the longest side of the points' box
        int axis = 0;
        (hi - lo).maxCoeff(&axis);
        const double mid = q[axis];
        const auto split = std::partition
        (
            order.begin() + begin, order.begin() + end,
            [&](size_t i) { return x[i][axis] < mid; }
        );
        size_t m = size_t(split - order.begin());
        if (m == begin || m == end)
        {
            // All on one side (coincident points): halve the list
            m = begin + (end - begin)/2;
        }
        group(order, begin, m, &sq);
        group(order, m, end, &sq);
    }
};

} // End anonymous namespace


std::vector<narrowBand::value> narrowBand::signedDistances
(
    const shape& s, const bodyPose& pose,
    const std::vector<vec3>& x, const std::vector<double>& reach,
    long* queries
)
{
    std::vector<value> out(x.size());
    if (x.empty()) return out;
    std::vector<size_t> order(x.size());
    std::iota(order.begin(), order.end(), size_t(0));
    walk w{s, pose, x, reach, out};
    w.group(order, 0, x.size(), nullptr);
    if (queries) *queries += w.queries;
    return out;
}

} // End namespace immersedDEM
