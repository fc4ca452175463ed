#include "cellsOverlap.H"
#include "coreError.H"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <unordered_set>

namespace immersedDEM
{

namespace
{

using cellIndex = std::array<long, 3>;

struct sharedCell
{
    vec3 corner;
    double lambdaA;
    double lambdaB;
};


// Union-find over the shared cells
struct disjointSets
{
    std::vector<int> parent;
    explicit disjointSets(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
    int find(int i) { while (parent[i] != i) i = parent[i] = parent[parent[i]]; return i; }
    void join(int i, int j) { parent[find(i)] = find(j); }
};


// The fraction of the cell's sample points inside the body
double sampledFraction
(
    const shape& s, const bodyPose& p, const vec3& corner, double h, long& queries
)
{
    const int m = cellsOverlap::nSample;
    const double ds = h/m;
    int in = 0;
    for (int l = 0; l < m; ++l)
    {
        for (int j = 0; j < m; ++j)
        {
            for (int i = 0; i < m; ++i)
            {
                in += s.inside(p, corner + ds*vec3(i + 0.5, j + 0.5, l + 0.5));
            }
        }
    }
    queries += m*m*m;
    return double(in)/(m*m*m);
}

} // End anonymous namespace


contactGeometry cellsOverlap::evaluate
(
    const shape& A, const bodyPose& pA,
    const shape& B, const bodyPose& pB,
    const overlapSettings& settings
) const
{
    const double h = settings.h;
    if (!(std::isfinite(h) && h > 0))
    {
        throw coreError("cells: the base cell size h must be positive, not " + std::to_string(h));
    }

    contactGeometry g;
    const axisAlignedBox box = A.worldBox(pA).intersection(B.worldBox(pB));
    if (box.empty())
    {
        return g;
    }

    cellIndex lo, hi;
    for (int d = 0; d < 3; ++d)
    {
        lo[d] = long(std::floor(box.min[d]/h));
        hi[d] = long(std::floor(box.max[d]/h));
    }

    // The shared cells: lambda_A > 0 and lambda_B > 0
    const double r = 0.5*std::sqrt(3.0)*h;
    std::map<cellIndex, sharedCell> shared;
    long queries = 0, leaves = 0;
    for (long i = lo[0]; i <= hi[0]; ++i)
    {
        for (long j = lo[1]; j <= hi[1]; ++j)
        {
            for (long k = lo[2]; k <= hi[2]; ++k)
            {
                ++leaves;
                const vec3 corner(i*h, j*h, k*h);
                const vec3 c = corner + vec3::Constant(0.5*h);
                ++queries;
                const double dA = A.signedDistance(pA, c);
                if (dA > r) continue;
                ++queries;
                const double dB = B.signedDistance(pB, c);
                if (dB > r) continue;
                const double lA = dA < -r ? 1.0 : sampledFraction(A, pA, corner, h, queries);
                if (lA <= 0) continue;
                const double lB = dB < -r ? 1.0 : sampledFraction(B, pB, corner, h, queries);
                if (lB <= 0) continue;
                shared.emplace(cellIndex{i, j, k}, sharedCell{corner, lA, lB});
            }
        }
    }
    g.queries = queries;
    g.leaves = leaves;
    if (shared.empty())
    {
        return g;
    }

    // Regions: shared cells joined across faces
    std::map<cellIndex, int> id;
    std::vector<const sharedCell*> cells;
    for (const auto& e : shared)
    {
        id[e.first] = int(cells.size());
        cells.push_back(&e.second);
    }
    disjointSets sets(int(cells.size()));
    for (const auto& e : id)
    {
        for (int d = 0; d < 3; ++d)
        {
            cellIndex nb = e.first;
            ++nb[d];
            const auto it = id.find(nb);
            if (it != id.end()) sets.join(e.second, it->second);
        }
    }
    std::map<int, std::vector<int>> members;
    for (int m = 0; m < int(cells.size()); ++m)
    {
        members[sets.find(m)].push_back(m);
    }

    const double V = h*h*h;
    const vec3 centreLine = pB.position() - pA.position();
    for (const auto& e : members)
    {
        double volume = 0;
        vec3 first = vec3::Zero(), mean = vec3::Zero();
        std::vector<vec3> edgeCentres;
        for (int m : e.second)
        {
            const sharedCell& sc = *cells[m];
            const vec3 c = sc.corner + vec3::Constant(0.5*h);
            const double v = std::max(0.0, sc.lambdaA + sc.lambdaB - 1)*V;
            volume += v;
            first += v*c;
            mean += c;
            if (sc.lambdaA < 1 && sc.lambdaB < 1) edgeCentres.push_back(c);
        }
        if (!(volume > 0))
        {
            continue;
        }
        mean /= double(e.second.size());

        // A to B: cells on B's side hold more of B
        vec3 side = vec3::Zero();
        double sideScale = 0;
        for (int m : e.second)
        {
            const sharedCell& sc = *cells[m];
            const vec3 x = sc.corner + vec3::Constant(0.5*h) - mean;
            side += (sc.lambdaB - sc.lambdaA)*x;
            sideScale += std::abs(sc.lambdaB - sc.lambdaA)*x.norm();
        }
        if (!(side.norm() > 1e-9*sideScale))
        {
            side = vec3::Zero();    // symmetric: round-off only
        }
        const vec3 fallback =
            centreLine.norm() > 0 ? vec3(centreLine.normalized())
          : side.norm() > 0 ? vec3(side.normalized()) : vec3(vec3::UnitX());
        const vec3 ref = side.norm() > 0 ? vec3(side.normalized()) : fallback;

        vec3 normal = fallback;
        if (edgeCentres.size() >= 3)
        {
            vec3 em = vec3::Zero();
            for (const vec3& p : edgeCentres) em += p;
            em /= double(edgeCentres.size());
            mat3 C = mat3::Zero();
            for (const vec3& p : edgeCentres) C += (p - em)*(p - em).transpose();
            Eigen::SelfAdjointEigenSolver<mat3> eig(C);
            const vec3 l = eig.eigenvalues();
            if (l(2) > 0 && l(1) > 1e-6*l(2))
            {
                const vec3 nrm = eig.eigenvectors().col(0).normalized();
                if (nrm.allFinite())
                {
                    normal = nrm.dot(ref) < 0 ? vec3(-nrm) : nrm;
                }
            }
        }

        // Area: the shadow of the cells that add volume
        const int ms = nSample;
        const double pixel = h/ms;
        const vec3 t1 = normal.unitOrthogonal();
        const vec3 t2 = normal.cross(t1);
        std::unordered_set<long long> pixels;
        for (int m : e.second)
        {
            const sharedCell& sc = *cells[m];
            if (sc.lambdaA + sc.lambdaB <= 1) continue;
            for (int l = 0; l < ms; ++l)
            {
                for (int j = 0; j < ms; ++j)
                {
                    const bool rim = (l == 0 || l == ms - 1 || j == 0 || j == ms - 1);
                    for (int i = 0; i < ms; i += (rim ? 1 : ms - 1))
                    {
                        const vec3 x = sc.corner + pixel*vec3(i + 0.5, j + 0.5, l + 0.5);
                        const long long u = std::llround(x.dot(t1)/pixel);
                        const long long w = std::llround(x.dot(t2)/pixel);
                        pixels.insert((u << 32) ^ (w & 0xffffffffLL));
                    }
                }
            }
        }

        contactRegion cr;
        cr.volume = volume;
        cr.point = first/volume;
        cr.normal = normal;
        cr.area = double(pixels.size())*pixel*pixel;
        g.regions.push_back(cr);
    }
    std::stable_sort
    (
        g.regions.begin(), g.regions.end(),
        [](const contactRegion& x, const contactRegion& y){ return x.volume > y.volume; }
    );
    return g;
}

} // End namespace immersedDEM
