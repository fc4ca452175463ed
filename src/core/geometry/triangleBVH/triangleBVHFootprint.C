#include "triangleBVH.H"

#include <algorithm>
#include <cmath>
#include <limits>

namespace immersedDEM
{

template<class Visit>
void triangleBVH::forSlotsBelow(const vec3& n, const double level, Visit visit) const
{
    const vec3 absN = n.cwiseAbs();
    std::vector<int> stack{0};
    while (!stack.empty())
    {
        const node& nd = nodes_[stack.back()];
        stack.pop_back();
        if (n.dot(0.5*(nd.lo + nd.hi)) - absN.dot(0.5*(nd.hi - nd.lo)) > level)
        {
            continue;
        }
        if (!nd.count)
        {
            stack.push_back(nd.first);
            stack.push_back(nd.right);
            continue;
        }
        for (int s = nd.first; s < nd.first + nd.count; ++s)
        {
            visit(s);
        }
    }
}


bool triangleBVH::meanCornerBelow
(
    const vec3& n, double low, double band, vec3& mean
) const
{
    if (nodes_.empty() || !(band > 0))
    {
        return false;
    }
    const double level = low + band;
    // A corner is stored once per triangle at it: each counted once
    std::vector<std::array<double, 3>> found;
    forSlotsBelow(n, level, [&](const int s)
    {
        for (const vec3& x : corners_[s])
        {
            if (n.dot(x) < level)
            {
                found.push_back({x.x(), x.y(), x.z()});
            }
        }
    });
    std::sort(found.begin(), found.end());
    found.erase(std::unique(found.begin(), found.end()), found.end());
    vec3 sum = vec3::Zero();
    double weight = 0;
    for (const auto& c : found)
    {
        const vec3 x(c[0], c[1], c[2]);
        const double w = std::max(0.0, 1 - (n.dot(x) - low)/band);
        sum += w*x;
        weight += w;
    }
    if (!(weight > 0))
    {
        return false;
    }
    mean = sum/weight;
    return true;
}


triangleBVH::footprint triangleBVH::footprintBelow
(
    const vec3& n, double low, double band
) const
{
    footprint f;
    if (nodes_.empty() || !(band > 0))
    {
        return f;
    }
    // Weighted sums of area, first and second moments (about the first
    // corner found, for round-off: the face is small against the body)
    double A = 0, H = 0;
    vec3 first = vec3::Zero();
    mat3 second = mat3::Zero();
    bool originSet = false;
    vec3 origin = vec3::Zero();
    forSlotsBelow(n, low + band, [&](const int s)
    {
        const auto& t = corners_[s];
        double w = 1;
        for (const vec3& x : t)
        {
            w = std::min(w, 1 - (n.dot(x) - low)/band);
        }
        if (!(w > 0))
        {
            return;
        }
        if (!originSet)
        {
            origin = t[0];
            originSet = true;
        }
        // Facing the other body: the outward normal within a few
        // degrees of -n, the weight fading to zero at 0.05 rad (a
        // curved surface's facets do not make a flat film)
        const vec3 normal = (t[1] - t[0]).cross(t[2] - t[0]);
        const double twiceArea = normal.norm();
        if (!(twiceArea > 0))
        {
            return;
        }
        const double cosine = -n.dot(normal)/twiceArea;
        w = std::min(w, 1 - (1 - cosine)/(1 - std::cos(0.05)));
        if (!(w > 0))
        {
            return;
        }
        const vec3 a = t[0] - origin, b = t[1] - origin, c = t[2] - origin;
        const double area = 0.5*twiceArea;
        const vec3 sum = a + b + c;
        // Int x x^T dA over a triangle = A/12 (sum of v v^T + s s^T)
        A += w*area;
        H += w*area*((n.dot(t[0]) + n.dot(t[1]) + n.dot(t[2]))/3 - low);
        first += w*area*sum/3;
        second += w*area/12*(a*a.transpose() + b*b.transpose() + c*c.transpose() + sum*sum.transpose());
    });
    if (!(A > 0))
    {
        return f;
    }
    const vec3 m = first/A;
    f.area = A;
    f.centroid = origin + m;
    f.spread = second/A - m*m.transpose();
    f.height = H/A;
    return f;
}


double triangleBVH::minAlong(const vec3& n) const
{
    double best = std::numeric_limits<double>::max();
    if (nodes_.empty())
    {
        return best;
    }
    const vec3 absN = n.cwiseAbs();
    auto lower = [&](const node& nd)
    {
        return n.dot(0.5*(nd.lo + nd.hi)) - absN.dot(0.5*(nd.hi - nd.lo));
    };
    int stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top)
    {
        const node& nd = nodes_[stack[--top]];
        if (lower(nd) >= best)
        {
            continue;
        }
        if (nd.count)
        {
            for (int s = nd.first; s < nd.first + nd.count; ++s)
            {
                for (const vec3& x : corners_[s])
                {
                    best = std::min(best, n.dot(x));
                }
            }
            continue;
        }
        const int l = nd.first, r = nd.right;
        if (lower(nodes_[l]) <= lower(nodes_[r]))
        {
            stack[top++] = r;
            stack[top++] = l;
        }
        else
        {
            stack[top++] = l;
            stack[top++] = r;
        }
    }
    return best;
}

} // End namespace immersedDEM
