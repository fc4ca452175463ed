#include "uniformOverlap.H"
#include "overlapTools.H"

#include <cmath>
#include <map>

namespace immersedDEM
{

namespace
{

using overlapTools::cellIndex;

// A sub-volume's state: checked, in A, in B, reached by a fill, and
// whether it has a face neighbour only in A, only in B
enum : unsigned char
{
    checked = 1, inA = 2, inB = 4, expanded = 8, nbOnlyA = 16, nbOnlyB = 32
};

inline bool isCommon(unsigned char st) { return (st & (inA | inB)) == (inA | inB); }
inline bool isOnlyA(unsigned char st) { return (st & (inA | inB)) == inA; }
inline bool isOnlyB(unsigned char st) { return (st & (inA | inB)) == inB; }


// What one base cell (or, summed, one region) contributes
struct cellSum
{
    double volume = 0;
    vec3 first = vec3::Zero();
    std::vector<vec3> edgePoints;
    vec3 faceSum = vec3::Zero();    // vector area, common -> only B minus -> only A
    double faceArea = 0;            // the area of those faces
    vec3 onlyASum = vec3::Zero();
    vec3 onlyBSum = vec3::Zero();
    long nOnlyA = 0;
    long nOnlyB = 0;
    std::vector<vec3> commons;      // centres of common sub-volumes
    std::vector<vec3> fullCells;    // lower corners of cells inside both

    void add(const cellSum& s)
    {
        volume += s.volume;
        first += s.first;
        edgePoints.insert(edgePoints.end(), s.edgePoints.begin(), s.edgePoints.end());
        faceSum += s.faceSum;
        faceArea += s.faceArea;
        addSides(s);
        commons.insert(commons.end(), s.commons.begin(), s.commons.end());
        fullCells.insert(fullCells.end(), s.fullCells.begin(), s.fullCells.end());
    }

    void addSides(const cellSum& s)
    {
        onlyASum += s.onlyASum;
        onlyBSum += s.onlyBSum;
        nOnlyA += s.nOnlyA;
        nOnlyB += s.nOnlyB;
    }
};


// The states of a split cell's six boundary layers, kept to look up the
// neighbours across its faces: layer 2a (2a+1) holds the sub-volumes with
// index 0 (n - 1) along axis a, at u + n v, u and v the indices along the
// axes a + 1 and a + 2 (mod 3)
struct boundaryLayers
{
    std::array<std::vector<unsigned char>, 6> layer;
};


// Algorithm 1 on one contact cell
class contactCellFill
{
    const shape& A_;
    const bodyPose& pA_;
    const shape& B_;
    const bodyPose& pB_;
    const int n_;

    std::vector<unsigned char> state_;
    std::vector<int> queue_;

    bool common(int k) const { return isCommon(state_[k]); }

    vec3 centre(const vec3& lo, double s, int k) const
    {
        const int i = k % n_, j = (k/n_) % n_, l = k/(n_*n_);
        return lo + s*vec3(i + 0.5, j + 0.5, l + 0.5);
    }

    // Lines 12-19: check one sub-volume
    void check(const vec3& lo, double s, int k, cellSum& sum)
    {
        unsigned char& st = state_[k];
        st |= checked;
        ++leaves;
        const vec3 x = centre(lo, s, k);
        queries += 2;
        if (A_.inside(pA_, x)) st |= inA;
        if (B_.inside(pB_, x)) st |= inB;
        if (common(k))
        {
            const double v = s*s*s;
            sum.volume += v;
            sum.first += v*x;
            sum.commons.push_back(x);
        }
    }

    // Lines 8-21: a flood fill from a common seed, growing only from
    // common sub-volumes, over face neighbours inside the cell
    void fill(const vec3& lo, double s, int seed, cellSum& sum)
    {
        queue_.clear();
        queue_.push_back(seed);
        const int stride[3] = {1, n_, n_*n_};
        for (size_t q = 0; q < queue_.size(); ++q)
        {
            const int k = queue_[q];
            if (!(state_[k] & checked)) check(lo, s, k, sum);
            if (!common(k) || (state_[k] & expanded)) continue;
            state_[k] |= expanded;
            const int idx[3] = {k % n_, (k/n_) % n_, k/(n_*n_)};
            auto push = [&](int m)
            {
                // Not again where nothing can come of it
                if (state_[m] & expanded) return;
                if ((state_[m] & checked) && !common(m)) return;
                queue_.push_back(m);
            };
            for (int d = 0; d < 3; ++d)
            {
                if (idx[d] > 0) push(k - stride[d]);
                if (idx[d] < n_ - 1) push(k + stride[d]);
            }
        }
    }

public:

    long queries = 0;
    long leaves = 0;

    contactCellFill
    (
        const shape& A, const bodyPose& pA, const shape& B, const bodyPose& pB, int n
    )
    :
        A_(A), pA_(pA), B_(B), pB_(pB), n_(n),
        state_(size_t(n)*n*n)
    {}

    void evaluate(const vec3& lo, double h, cellSum& sum, boundaryLayers& layers)
    {
        const int n = n_;
        const double s = h/n;
        const int nn = n*n*n;
        const int stride[3] = {1, n, n*n};
        std::fill(state_.begin(), state_.end(), 0);

        // The seed search: every unchecked sub-volume is checked, and each
        // common one no fill has reached seeds a fill (nothing is missed)
        for (int r = 0; r < nn; ++r)
        {
            if (!(state_[r] & checked)) check(lo, s, r, sum);
            if (common(r) && !(state_[r] & expanded)) fill(lo, s, r, sum);
        }

        // The sides, and the neighbours only in A or only in B inside the
        // cell with the vector area of the faces to them
        for (int k = 0; k < nn; ++k)
        {
            const unsigned char sk = state_[k];
            if (isOnlyA(sk) || isOnlyB(sk))
            {
                const vec3 x = centre(lo, s, k);
                if (isOnlyA(sk)) { sum.onlyASum += x; ++sum.nOnlyA; }
                else { sum.onlyBSum += x; ++sum.nOnlyB; }
            }
            const int idx[3] = {k % n, (k/n) % n, k/(n*n)};
            for (int a = 0; a < 3; ++a)
            {
                if (idx[a] == n - 1) continue;
                const int m = k + stride[a];
                const unsigned char sm = state_[m];
                const vec3 e = s*s*vec3::Unit(a);     // from k to m
                if (isCommon(sk) && (isOnlyA(sm) || isOnlyB(sm)))
                {
                    state_[k] |= isOnlyA(sm) ? nbOnlyA : nbOnlyB;
                    sum.faceSum += isOnlyA(sm) ? vec3(-e) : e;
                    sum.faceArea += s*s;
                }
                if (isCommon(sm) && (isOnlyA(sk) || isOnlyB(sk)))
                {
                    state_[m] |= isOnlyA(sk) ? nbOnlyA : nbOnlyB;
                    sum.faceSum += isOnlyA(sk) ? e : vec3(-e);
                    sum.faceArea += s*s;
                }
            }
        }

        // Lines 22-33: edge sub-volumes away from the cell's faces now; on
        // them once the neighbours across the faces are known
        for (int k = 0; k < nn; ++k)
        {
            const int idx[3] = {k % n, (k/n) % n, k/(n*n)};
            const bool inner =
                idx[0] > 0 && idx[0] < n - 1 && idx[1] > 0 && idx[1] < n - 1
             && idx[2] > 0 && idx[2] < n - 1;
            const unsigned char sk = state_[k];
            if (inner && isCommon(sk) && (sk & nbOnlyA) && (sk & nbOnlyB))
            {
                sum.edgePoints.push_back(centre(lo, s, k));
            }
        }

        for (int a = 0; a < 3; ++a)
        {
            const int b = (a + 1) % 3, c = (a + 2) % 3;
            for (int side = 0; side < 2; ++side)
            {
                std::vector<unsigned char>& layer = layers.layer[2*a + side];
                layer.assign(size_t(n)*n, 0);
                for (int v = 0; v < n; ++v)
                {
                    for (int u = 0; u < n; ++u)
                    {
                        int idx[3];
                        idx[a] = side ? n - 1 : 0;
                        idx[b] = u;
                        idx[c] = v;
                        layer[u + n*v] = state_[idx[0] + n*idx[1] + n*n*idx[2]];
                    }
                }
            }
        }
    }
};


vec3 regionNormal(const cellSum& r, const vec3& centreLine)
{
    // Zero for a closed surface (a body inside the other), up to round-off
    const vec3 faces = r.faceSum.norm() > 1e-9*r.faceArea ? r.faceSum : vec3(vec3::Zero());
    const vec3 sides = r.nOnlyA > 0 && r.nOnlyB > 0
        ? vec3(r.onlyBSum/double(r.nOnlyB) - r.onlyASum/double(r.nOnlyA))
        : vec3(vec3::Zero());
    const vec3 ref = overlapTools::firstDirection({faces, sides, centreLine});

    // Determined: not collinear
    overlapTools::planeFitCriteria plane;
    plane.minSpread = 1e-6;
    vec3 n = ref;
    overlapTools::fitPlaneNormal(r.edgePoints, ref, plane, n);
    return n;
}


double projectedArea(const cellSum& r, const vec3& n, double h, int nSub)
{
    overlapTools::projectedPixels pixels(n, h/nSub);
    for (const vec3& x : r.commons) pixels.mark(x);
    for (const vec3& lo : r.fullCells)
    {
        // A cube's shadow is its boundary's: the outer layer of sub-volumes
        pixels.markCube(lo, nSub);
    }
    return pixels.area();
}

} // End anonymous namespace


contactGeometry uniformOverlap::evaluate
(
    const shape& A, const bodyPose& pA,
    const shape& B, const bodyPose& pB,
    const overlapSettings& settings
) const
{
    const double h = settings.h;
    const int L = settings.level;
    overlapTools::checkCellSize(type(), h);
    overlapTools::checkLevel(type(), L, maxLevel);
    const int n = 1 << L;
    const double s = h/n;

    contactGeometry g;
    const axisAlignedBox box = overlapTools::commonBox(A, pA, B, pB);
    if (box.empty())
    {
        return g;
    }

    contactCellFill cellFill(A, pA, B, pB, n);
    std::map<cellIndex, cellSum> sums;              // cells with overlap
    std::map<cellIndex, cellSum> sides;             // contact cells without
    std::map<cellIndex, boundaryLayers> layers;     // all contact cells
    long queries = 0, leaves = 0;
    overlapTools::forEachScreenedCell
    (
        A, pA, B, pB, box, h, queries, leaves,
        [&](const cellIndex& ci, const vec3& corner, double dA, double dB, double r)
        {
            cellSum cs;
            if (dA < -r && dB < -r)
            {
                const double v = h*h*h;
                cs.volume = v;
                cs.first = v*(corner + vec3::Constant(0.5*h));
                cs.fullCells.push_back(corner);
            }
            else
            {
                cellFill.evaluate(corner, h, cs, layers[ci]);
            }
            if (cs.volume > 0)
            {
                sums.emplace(ci, std::move(cs));
            }
            else if (cs.nOnlyA + cs.nOnlyB > 0)
            {
                sides.emplace(ci, std::move(cs));
            }
        }
    );
    g.queries = queries + cellFill.queries;
    g.leaves = leaves + cellFill.leaves;
    if (sums.empty())
    {
        return g;
    }

    // Neighbours across the faces between two split cells; a full cell is
    // common throughout (nothing to add); in a cell neither split nor full
    // (outside a body, or beyond the box) the neighbours of the common
    // sub-volumes are checked now (the paper has no such neighbours: a
    // contact plane on a cell face would have no edge sub-volumes)
    long extraQueries = 0;
    for (auto& e : layers)
    {
        const auto own = sums.find(e.first);
        if (own == sums.end()) continue;
        const vec3 corner = h*vec3(e.first[0], e.first[1], e.first[2]);
        for (int a = 0; a < 3; ++a)
        {
            const int b = (a + 1) % 3, c = (a + 2) % 3;
            for (int side = 0; side < 2; ++side)
            {
                cellIndex nb = e.first;
                nb[a] += side ? 1 : -1;
                if (layers.count(nb) || sums.count(nb)) continue;
                std::vector<unsigned char>& P = e.second.layer[2*a + side];
                const vec3 dir = (side ? 1.0 : -1.0)*vec3::Unit(a);
                for (size_t t = 0; t < P.size(); ++t)
                {
                    if (!isCommon(P[t])) continue;
                    vec3 idx;
                    idx[a] = side ? n - 1 : 0;
                    idx[b] = double(t % n);
                    idx[c] = double(t/n);
                    const vec3 x = corner + s*(idx + vec3::Constant(0.5)) + s*dir;
                    extraQueries += 2;
                    const bool a1 = A.inside(pA, x), b1 = B.inside(pB, x);
                    if (a1 != b1)
                    {
                        P[t] |= a1 ? nbOnlyA : nbOnlyB;
                        own->second.faceSum += (a1 ? -s*s : s*s)*dir;
                        own->second.faceArea += s*s;
                    }
                }
            }
        }
    }
    g.queries += extraQueries;
    g.leaves += extraQueries/2;

    for (auto& e : layers)
    {
        for (int a = 0; a < 3; ++a)
        {
            cellIndex nb = e.first;
            ++nb[a];
            const auto it = layers.find(nb);
            if (it == layers.end()) continue;
            std::vector<unsigned char>& P = e.second.layer[2*a + 1];
            std::vector<unsigned char>& Q = it->second.layer[2*a];
            const vec3 ea = s*s*vec3::Unit(a);      // from P to Q
            for (size_t t = 0; t < P.size(); ++t)
            {
                const unsigned char sp = P[t], sq = Q[t];
                if (isCommon(sp) && (isOnlyA(sq) || isOnlyB(sq)))
                {
                    cellSum& f = sums.at(e.first);
                    P[t] |= isOnlyA(sq) ? nbOnlyA : nbOnlyB;
                    f.faceSum += isOnlyA(sq) ? vec3(-ea) : ea;
                    f.faceArea += s*s;
                }
                if (isCommon(sq) && (isOnlyA(sp) || isOnlyB(sp)))
                {
                    cellSum& f = sums.at(nb);
                    Q[t] |= isOnlyA(sp) ? nbOnlyA : nbOnlyB;
                    f.faceSum += isOnlyA(sp) ? ea : vec3(-ea);
                    f.faceArea += s*s;
                }
            }
        }
    }

    // Edge sub-volumes on the split cells' faces
    for (const auto& e : layers)
    {
        const auto it = sums.find(e.first);
        if (it == sums.end()) continue;
        const auto& lay = e.second.layer;
        const vec3 corner = h*vec3(e.first[0], e.first[1], e.first[2]);
        for (int l = 0; l < n; ++l)
        {
            for (int j = 0; j < n; ++j)
            {
                for (int i = 0; i < n; ++i)
                {
                    unsigned char st = 0;
                    if (i == 0) st |= lay[0][j + n*l];
                    if (i == n - 1) st |= lay[1][j + n*l];
                    if (j == 0) st |= lay[2][l + n*i];
                    if (j == n - 1) st |= lay[3][l + n*i];
                    if (l == 0) st |= lay[4][i + n*j];
                    if (l == n - 1) st |= lay[5][i + n*j];
                    if (isCommon(st) && (st & nbOnlyA) && (st & nbOnlyB))
                    {
                        it->second.edgePoints.push_back
                        (
                            corner + s*vec3(i + 0.5, j + 0.5, l + 0.5)
                        );
                    }
                    // Only the boundary layer
                    if (j > 0 && j < n - 1 && l > 0 && l < n - 1 && i == 0 && n > 2)
                    {
                        i = n - 2;
                    }
                }
            }
        }
    }

    // Regions: base cells joined across faces, edges and corners (at a
    // low level the sampled overlap of a thin contact is often connected
    // only diagonally)
    overlapTools::cellRegions sets(sums, overlapTools::cellJoin::facesEdgesCorners);

    std::map<int, cellSum> regions;
    for (const auto& e : sums)
    {
        regions[sets.label(e.first)].add(e.second);
    }

    // A contact cell with no overlap next to a region still tells on which
    // side A and B are
    for (const auto& e : sides)
    {
        const int near = sets.labelNear(e.first);
        if (near >= 0) regions[near].addSides(e.second);
    }

    const vec3 centreLine = pB.position() - pA.position();
    for (const auto& e : regions)
    {
        const cellSum& rs = e.second;
        contactRegion cr;
        cr.volume = rs.volume;
        cr.point = rs.first/rs.volume;
        cr.normal = regionNormal(rs, centreLine);
        cr.area = projectedArea(rs, cr.normal, h, n);
        g.regions.push_back(cr);
    }
    overlapTools::sortLargestFirst(g.regions, true);
    return g;
}

} // End namespace immersedDEM
