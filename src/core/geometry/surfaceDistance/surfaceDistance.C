#include "surfaceDistance.H"

#include <cmath>
#include <algorithm>
#include <limits>
#include <unordered_map>

namespace immersedDEM
{

namespace
{

std::uint64_t edgeKey(int a, int b)
{
    return (std::uint64_t(std::max(a, b)) << 32) | std::uint64_t(std::min(a, b));
}

} // End anonymous namespace


surfaceDistance::surfaceDistance(const triangleSoup& s)
:
    faces_(s.faces),
    bvh_(s)
{
    const size_t nF = s.faces.size();
    faceNormal_.resize(nF);
    edgeNormal_.resize(nF);
    vertexNormal_.assign(s.points.size(), vec3::Zero());
    std::unordered_map<std::uint64_t, vec3> edgeSum;
    edgeSum.reserve(3*nF);
    // Each edge's faces' normals (the first, and whether any other meets
    // it at more than the crease angle) and how many faces it has
    struct edgeFaces { vec3 first; int count = 0; bool crease = false; };
    std::unordered_map<std::uint64_t, edgeFaces> edgeOf;
    edgeOf.reserve(3*nF);
    const double cosCrease = std::cos(creaseAngleDegrees*M_PI/180);
    std::vector<std::array<double, 3>> cornerAngle(nF);
    for (size_t fi = 0; fi < nF; ++fi)
    {
        const triFace& f = s.faces[fi];
        const vec3 n = (s.points[f[1]] - s.points[f[0]])
            .cross(s.points[f[2]] - s.points[f[0]]).normalized();
        faceNormal_[fi] = n;
        for (int k = 0; k < 3; ++k)
        {
            const vec3& p0 = s.points[f[k]];
            const vec3 e1 = (s.points[f[(k + 1) % 3]] - p0).normalized();
            const vec3 e2 = (s.points[f[(k + 2) % 3]] - p0).normalized();
            const double angle = std::acos(std::max(-1.0, std::min(1.0, e1.dot(e2))));
            cornerAngle[fi][k] = angle;
            vertexNormal_[f[k]] += angle*n;
            // Not operator[]: it would leave a new (Eigen) vec3 uninitialised
            edgeSum.emplace(edgeKey(f[k], f[(k + 1) % 3]), vec3::Zero()).first->second += n;
            edgeFaces& e = edgeOf[edgeKey(f[k], f[(k + 1) % 3])];
            if (e.count == 0) e.first = n;
            else if (e.first.dot(n) < cosCrease) e.crease = true;
            ++e.count;
        }
    }
    for (const auto& e : edgeOf)
    {
        if (e.second.crease || e.second.count != 2)
        {
            const int a = int(e.first >> 32), b = int(e.first & 0xffffffffu);
            creases_.push_back({s.points[a], s.points[b]});
        }
    }
    // A fixed order (the map's is not): by the edges' corners
    std::sort
    (
        creases_.begin(), creases_.end(),
        [](const std::array<vec3, 2>& x, const std::array<vec3, 2>& y)
        {
            for (int i = 0; i < 2; ++i)
                for (int d = 0; d < 3; ++d)
                    if (x[i][d] != y[i][d]) return x[i][d] < y[i][d];
            return false;
        }
    );
    if (!creases_.empty())
    {
        creaseNodes_.reserve(creases_.size());
        buildCreases(0, int(creases_.size()));
    }
    for (vec3& n : vertexNormal_) n.normalize();
    for (size_t fi = 0; fi < nF; ++fi)
    {
        const triFace& f = s.faces[fi];
        for (int k = 0; k < 3; ++k)
        {
            edgeNormal_[fi][k] = edgeSum[edgeKey(f[k], f[(k + 1) % 3])].normalized();
        }
    }
    computeCurvature(s, cornerAngle);
}


int surfaceDistance::buildCreases(int begin, int end)
{
    const int index = int(creaseNodes_.size());
    creaseNodes_.push_back({});
    vec3 lo = vec3::Constant(std::numeric_limits<double>::max()), hi = -lo;
    for (int i = begin; i < end; ++i)
    {
        for (const vec3& x : creases_[i])
        {
            lo = lo.cwiseMin(x);
            hi = hi.cwiseMax(x);
        }
    }
    creaseNodes_[index].lo = lo;
    creaseNodes_[index].hi = hi;
    if (end - begin <= 4)
    {
        creaseNodes_[index].first = begin;
        creaseNodes_[index].right = -1;
        creaseNodes_[index].count = end - begin;
        return index;
    }
    int axis = 0;
    (hi - lo).maxCoeff(&axis);
    const int mid = (begin + end)/2;
    std::nth_element
    (
        creases_.begin() + begin, creases_.begin() + mid, creases_.begin() + end,
        [axis](const std::array<vec3, 2>& x, const std::array<vec3, 2>& y)
        {
            return x[0][axis] + x[1][axis] < y[0][axis] + y[1][axis];
        }
    );
    const int left = buildCreases(begin, mid);
    const int right = buildCreases(mid, end);
    creaseNodes_[index].first = left;
    creaseNodes_[index].right = right;
    creaseNodes_[index].count = 0;
    return index;
}


bool surfaceDistance::creaseWithin(const vec3& p, double r) const
{
    if (creaseNodes_.empty()) return false;
    const double r2 = r*r;
    int stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top)
    {
        const creaseNode& nd = creaseNodes_[stack[--top]];
        const vec3 d = (nd.lo - p).cwiseMax(p - nd.hi).cwiseMax(0.0);
        if (d.squaredNorm() > r2) continue;
        if (nd.count)
        {
            for (int i = nd.first; i < nd.first + nd.count; ++i)
            {
                const vec3& a = creases_[i][0];
                const vec3 ab = creases_[i][1] - a;
                const double L2 = ab.squaredNorm();
                const double t = L2 > 0 ? std::min(1.0, std::max(0.0, (p - a).dot(ab)/L2)) : 0;
                if ((a + t*ab - p).squaredNorm() <= r2) return true;
            }
            continue;
        }
        stack[top++] = nd.first;
        stack[top++] = nd.right;
    }
    return false;
}


void surfaceDistance::computeCurvature
(
    const triangleSoup& s,
    const std::vector<std::array<double, 3>>& cornerAngle
)
{
    const size_t nF = s.faces.size();
    // The corners at each point: (face, corner index)
    std::vector<std::vector<std::pair<int, int>>> pointCorners(s.points.size());
    for (size_t fi = 0; fi < nF; ++fi)
    {
        for (int k = 0; k < 3; ++k) pointCorners[s.faces[fi][k]].emplace_back(int(fi), k);
    }
    const double cosCrease = std::cos(creaseAngleDegrees*M_PI/180);

    points_ = s.points;
    pointFaces_.assign(s.points.size(), {});
    for (size_t fi = 0; fi < nF; ++fi)
    {
        for (int k = 0; k < 3; ++k) pointFaces_[s.faces[fi][k]].push_back(int(fi));
    }
    // The face across each edge: the one other face holding both points
    faceAcross_.assign(nF, {-1, -1, -1});
    for (size_t fi = 0; fi < nF; ++fi)
    {
        const triFace& f = s.faces[fi];
        for (int e = 0; e < 3; ++e)
        {
            const int a = f[e], b = f[(e + 1) % 3];
            int across = -1, count = 0;
            for (const int g : pointFaces_[a])
            {
                if (g == int(fi)) continue;
                const triFace& fg = s.faces[g];
                if (fg[0] == b || fg[1] == b || fg[2] == b)
                {
                    across = g;
                    ++count;
                }
            }
            faceAcross_[fi][e] = count == 1 ? across : -1;
        }
    }

    faceCurvature_.assign(nF, mat3::Zero());
    for (size_t fi = 0; fi < nF; ++fi)
    {
        const triFace& f = s.faces[fi];
        const vec3& nf = faceNormal_[fi];
        std::array<vec3, 3> cn;
        for (int k = 0; k < 3; ++k)
        {
            vec3 sum = vec3::Zero();
            for (const auto& gc : pointCorners[f[k]])
            {
                const vec3& ng = faceNormal_[gc.first];
                if (ng.dot(nf) >= cosCrease)
                {
                    sum += cornerAngle[gc.first][gc.second]*ng;
                }
            }
            cn[k] = sum.norm() > 0 ? vec3(sum.normalized()) : nf;
        }
        // Tangent frame (u, v) of the face; S = [a b; b c] in it
        const vec3 u = (s.points[f[1]] - s.points[f[0]]).normalized();
        const vec3 v = nf.cross(u);
        Eigen::Matrix<double, 6, 3> M = Eigen::Matrix<double, 6, 3>::Zero();
        Eigen::Matrix<double, 6, 1> r;
        for (int k = 0; k < 3; ++k)
        {
            const int i = (k + 1) % 3, j = (k + 2) % 3;
            const vec3 e = s.points[f[j]] - s.points[f[i]];
            const vec3 dn = cn[j] - cn[i];
            const double eu = e.dot(u), ev = e.dot(v);
            M.row(2*k) << eu, ev, 0;
            M.row(2*k + 1) << 0, eu, ev;
            r(2*k) = dn.dot(u);
            r(2*k + 1) = dn.dot(v);
        }
        const vec3 abc = M.colPivHouseholderQr().solve(r);
        if (abc.allFinite())
        {
            faceCurvature_[fi] = abc(0)*u*u.transpose()
              + abc(1)*(u*v.transpose() + v*u.transpose())
              + abc(2)*v*v.transpose();
        }
    }

    // Each corner's: its point's faces on its face's side of a crease
    cornerCurvature_.assign(nF, {mat3::Zero(), mat3::Zero(), mat3::Zero()});
    for (size_t fi = 0; fi < nF; ++fi)
    {
        const vec3& nf = faceNormal_[fi];
        for (int k = 0; k < 3; ++k)
        {
            mat3 sum = mat3::Zero();
            double weight = 0;
            for (const auto& gc : pointCorners[s.faces[fi][k]])
            {
                if (faceNormal_[gc.first].dot(nf) >= cosCrease)
                {
                    const double w = cornerAngle[gc.first][gc.second];
                    sum += w*faceCurvature_[gc.first];
                    weight += w;
                }
            }
            cornerCurvature_[fi][k] = weight > 0 ? mat3(sum/weight) : faceCurvature_[fi];
        }
    }
}


mat3 surfaceDistance::smoothCurvature(const vec3& p) const
{
    const triangleBVH::hit h = bvh_.closest(p);
    if (h.face < 0)
    {
        return mat3::Zero();
    }
    // On an edge or at a corner: of the faces meeting there, the one
    // facing p most (the lowest index of equals)
    int face = h.face;
    const vec3 d = p - h.point;
    if (h.feature != 0 && d.squaredNorm() > 0)
    {
        auto better = [&](const int g)
        {
            const double a = faceNormal_[g].dot(d), b = faceNormal_[face].dot(d);
            if (a > b || (a == b && g < face)) face = g;
        };
        if (h.feature >= 4)
        {
            const int g = faceAcross_[h.face][h.feature - 4];
            if (g >= 0) better(g);
        }
        else
        {
            for (const int g : pointFaces_[faces_[h.face][h.feature - 1]]) better(g);
        }
    }
    // The closest point's barycentric weights in that face (it lies on
    // it: on its edge or corner if it is another face than the hit's)
    const triFace& f = faces_[face];
    const vec3& a = points_[f[0]];
    const vec3 e1 = points_[f[1]] - a, e2 = points_[f[2]] - a, q = h.point - a;
    const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2);
    const double q1 = q.dot(e1), q2 = q.dot(e2);
    const double det = d11*d22 - d12*d12;
    if (!(det > 0))
    {
        return faceCurvature_[face];
    }
    double w1 = std::clamp((d22*q1 - d12*q2)/det, 0.0, 1.0);
    double w2 = std::clamp((d11*q2 - d12*q1)/det, 0.0, 1.0);
    double w0 = std::max(0.0, 1 - w1 - w2);
    const double sum = w0 + w1 + w2;
    w0 /= sum;
    w1 /= sum;
    w2 /= sum;
    return w0*cornerCurvature_[face][0] + w1*cornerCurvature_[face][1] + w2*cornerCurvature_[face][2];
}


surfacePoint surfaceDistance::closest(const vec3& p, double maxDistSqr, vec3* pseudoOut) const
{
    triangleBVH::hit h = bvh_.closest(p, maxDistSqr);
    if (h.face < 0)
    {
        h = bvh_.closest(p);
    }
    return pointOf(p, h, pseudoOut);
}


bool surfaceDistance::closestNear
(
    const vec3& p, double maxDistSqr, surfacePoint& sp, vec3* pseudoOut
) const
{
    const triangleBVH::hit h = bvh_.closest(p, maxDistSqr);
    if (h.face < 0)
    {
        return false;
    }
    sp = pointOf(p, h, pseudoOut);
    return true;
}


surfacePoint surfaceDistance::pointOf
(
    const vec3& p, const triangleBVH::hit& h, vec3* pseudoOut
) const
{
    const triFace& f = faces_[h.face];
    const vec3& pseudo =
        h.feature == 0 ? faceNormal_[h.face]
      : h.feature <= 3 ? vertexNormal_[f[h.feature - 1]]
      : edgeNormal_[h.face][h.feature - 4];

    surfacePoint sp;
    sp.point = h.point;
    const vec3 d = p - h.point;
    const double dist = std::sqrt(h.distSqr);
    const bool in = d.dot(pseudo) < 0;
    sp.distance = in ? -dist : dist;
    sp.curvature = faceCurvature_[h.face];
    // Outward: along p - closest, its sign fixed by the side
    sp.normal = dist > 0 ? vec3((in ? -d : d)/dist) : pseudo;
    if (pseudoOut)
    {
        *pseudoOut = pseudo;
    }
    return sp;
}

} // End namespace immersedDEM
