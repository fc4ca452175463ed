#include "overlapTools.H"
#include "coreError.H"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace immersedDEM
{
namespace overlapTools
{

// * * * * * * * * * * * * * * * Settings  * * * * * * * * * * * * * * * * //

void checkCellSize(const std::string& engine, double h)
{
    if (!(std::isfinite(h) && h > 0))
    {
        throw coreError
        (
            engine + ": the base cell size h must be positive, not " + std::to_string(h)
        );
    }
}


void checkLevel(const std::string& engine, int level, int maxLevel)
{
    if (level < 0 || level > maxLevel)
    {
        throw coreError
        (
            engine + ": the level must be in [0, " + std::to_string(maxLevel) + "], not "
          + std::to_string(level)
        );
    }
}


// * * * * * * * * * * * * * * * * Lattice * * * * * * * * * * * * * * * * //

axisAlignedBox commonBox
(
    const shape& A, const bodyPose& pA,
    const shape& B, const bodyPose& pB
)
{
    return A.worldBox(pA).intersection(B.worldBox(pB));
}


cellRange latticeRange(const axisAlignedBox& box, double h)
{
    cellRange r;
    for (int d = 0; d < 3; ++d)
    {
        r.lo[d] = long(std::floor(box.min[d]/h));
        r.hi[d] = long(std::floor(box.max[d]/h));
    }
    return r;
}


bool screenCell
(
    const shape& A, const bodyPose& pA,
    const shape& B, const bodyPose& pB,
    const vec3& c, double r,
    double& dA, double& dB, long& queries
)
{
    ++queries;
    dA = A.signedDistance(pA, c);
    if (dA > r) return false;
    ++queries;
    dB = B.signedDistance(pB, c);
    if (dB > r) return false;
    return true;
}


// * * * * * * * * * * * * * * * * Regions  * * * * * * * * * * * * * * * * //

disjointSets::disjointSets(int n)
:
    parent(n)
{
    std::iota(parent.begin(), parent.end(), 0);
}


int disjointSets::find(int i)
{
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
}


void disjointSets::join(int i, int j)
{
    parent[find(i)] = find(j);
}


void cellRegions::build(const std::vector<cellIndex>& cells, cellJoin join)
{
    for (const cellIndex& c : cells)
    {
        const int next = int(id_.size());
        id_[c] = next;
    }
    sets_ = disjointSets(int(id_.size()));
    for (const auto& e : id_)
    {
        if (join == cellJoin::faces)
        {
            for (int d = 0; d < 3; ++d)
            {
                cellIndex nb = e.first;
                ++nb[d];
                const auto it = id_.find(nb);
                if (it != id_.end()) sets_.join(e.second, it->second);
            }
        }
        else
        {
            for (int a = -1; a <= 1; ++a)
            {
                for (int b = -1; b <= 1; ++b)
                {
                    for (int c = -1; c <= 1; ++c)
                    {
                        const cellIndex nb{e.first[0] + a, e.first[1] + b, e.first[2] + c};
                        const auto it = id_.find(nb);
                        if (it != id_.end()) sets_.join(e.second, it->second);
                    }
                }
            }
        }
    }
}


int cellRegions::label(const cellIndex& c)
{
    const auto it = id_.find(c);
    return it == id_.end() ? -1 : sets_.find(it->second);
}


int cellRegions::labelNear(const cellIndex& c)
{
    for (int a = -1; a <= 1; ++a)
    {
        for (int b = -1; b <= 1; ++b)
        {
            for (int d = -1; d <= 1; ++d)
            {
                const auto it = id_.find(cellIndex{c[0] + a, c[1] + b, c[2] + d});
                if (it != id_.end()) return sets_.find(it->second);
            }
        }
    }
    return -1;
}


// * * * * * * * * * * * * * * * *  Normals  * * * * * * * * * * * * * * * //

vec3 firstDirection(std::initializer_list<vec3> candidates)
{
    for (const vec3& v : candidates)
    {
        if (v.norm() > 0) return v.normalized();
    }
    return vec3::UnitX();
}


bool fitPlaneNormal
(
    const std::vector<vec3>& points,
    const vec3& ref,
    const planeFitCriteria& criteria,
    vec3& normal
)
{
    if (points.size() < 3)
    {
        return false;
    }
    vec3 mean = vec3::Zero();
    for (const vec3& p : points) mean += p;
    mean /= double(points.size());
    mat3 C = mat3::Zero();
    for (const vec3& p : points) C += (p - mean)*(p - mean).transpose();
    Eigen::SelfAdjointEigenSolver<mat3> eig(C);
    const vec3 l = eig.eigenvalues();
    if (!(l(2) > 0 && l(1) > criteria.minSpread*l(2)))
    {
        return false;
    }
    if (std::isfinite(criteria.maxFlatness) && !(l(0) < criteria.maxFlatness*l(1)))
    {
        return false;
    }
    const vec3 nrm = eig.eigenvectors().col(0).normalized();
    if (criteria.requireFinite && !nrm.allFinite())
    {
        return false;
    }
    normal = nrm.dot(ref) < 0 ? vec3(-nrm) : nrm;
    return true;
}


// * * * * * * * * * * * * * * * * *  Area * * * * * * * * * * * * * * * * //

projectedPixels::projectedPixels(const vec3& normal, double pixel)
:
    pixel_(pixel),
    t1_(normal.unitOrthogonal()),
    t2_(normal.cross(t1_))
{}


void projectedPixels::mark(const vec3& x)
{
    const long long i = std::llround(x.dot(t1_)/pixel_);
    const long long j = std::llround(x.dot(t2_)/pixel_);
    pixels_.insert((i << 32) ^ (j & 0xffffffffLL));
}


void projectedPixels::markCube(const vec3& lo, int nSub)
{
    for (int l = 0; l < nSub; ++l)
    {
        for (int j = 0; j < nSub; ++j)
        {
            const bool rim = (l == 0 || l == nSub - 1 || j == 0 || j == nSub - 1);
            for (int i = 0; i < nSub; i += (rim ? 1 : std::max(1, nSub - 1)))
            {
                mark(lo + pixel_*vec3(i + 0.5, j + 0.5, l + 0.5));
            }
        }
    }
}


double projectedPixels::area() const
{
    return double(pixels_.size())*pixel_*pixel_;
}


// * * * * * * * * * * * * * * * * Regions  * * * * * * * * * * * * * * * * //

void sortLargestFirst(std::vector<contactRegion>& regions, bool stable)
{
    const auto larger = [](const contactRegion& x, const contactRegion& y)
    {
        return x.volume > y.volume;
    };
    if (stable)
    {
        std::stable_sort(regions.begin(), regions.end(), larger);
    }
    else
    {
        std::sort(regions.begin(), regions.end(), larger);
    }
}

} // End namespace overlapTools
} // End namespace immersedDEM
