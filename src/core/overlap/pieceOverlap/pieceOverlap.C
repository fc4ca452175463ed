#include "pieceOverlap.H"
#include "convexDistance.H"
#include "halfSpaceShape.H"
#include "overlapTools.H"
#include "triangleMeshShape.H"
#include "wallMeshShape.H"

#include <algorithm>
#include <numeric>

namespace immersedDEM
{

namespace
{

// One side of the pair: its pieces (or the shape itself), posed, with
// its world box (empty for a plane or a wall: not boxed) and its oriented
// box (its box in its own frame: centre, axes, half-extents)
struct part
{
    const shape* s;
    bodyPose pose;
    int index;
    axisAlignedBox box;
    vec3 centre = vec3::Zero();
    mat3 axes = mat3::Identity();
    vec3 half = vec3::Zero();
};


// Whether two oriented boxes are apart: a separating axis among their 15
// candidates (the faces' normals and the edges' cross products)
bool orientedApart(const part& x, const part& y)
{
    const mat3 R = x.axes.transpose()*y.axes;
    const vec3 t = x.axes.transpose()*(y.centre - x.centre);
    mat3 absR = R.cwiseAbs();
    absR.array() += 1e-12;
    const vec3& a = x.half;
    const vec3& b = y.half;
    for (int i = 0; i < 3; ++i)
    {
        if (std::abs(t[i]) > a[i] + b.dot(absR.row(i))) return true;
        if (std::abs(t.dot(R.col(i))) > b[i] + a.dot(absR.col(i))) return true;
    }
    for (int i = 0; i < 3; ++i)
    {
        const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
        for (int j = 0; j < 3; ++j)
        {
            const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
            const double ra = a[i1]*absR(i2, j) + a[i2]*absR(i1, j);
            const double rb = b[j1]*absR(i, j2) + b[j2]*absR(i, j1);
            if (std::abs(t[i2]*R(i1, j) - t[i1]*R(i2, j)) > ra + rb) return true;
        }
    }
    return false;
}


bool unbounded(const shape& S)
{
    return S.shapeKind() == shape::kind::halfSpace || S.shapeKind() == shape::kind::wallMesh;
}


// The shape S at pose p as a part, boxed unless a plane or a wall
part partOf(const shape& S, const bodyPose& p, int index)
{
    part q{&S, p, index, axisAlignedBox()};
    if (!unbounded(S))
    {
        q.box = S.worldBox(p);
        const axisAlignedBox b = S.localBox();
        q.centre = p.toWorld(b.centre());
        q.axes = p.rotation();
        // (grown by 1e-9 of the size: touching boxes meet)
        q.half = 0.5*b.span() + vec3::Constant(1e-9*S.boundingRadius());
    }
    return q;
}


std::vector<part> partsOf(const shape& S, const bodyPose& p)
{
    std::vector<part> out;
    const auto* m = shapeAs<triangleMeshShape>(S);
    if (m && !m->pieces().empty())
    {
        const auto& P = m->pieces();
        for (size_t i = 0; i < P.size(); ++i)
        {
            out.push_back(partOf(*P[i], p*P[i]->bodyInFile(), int(i)));
        }
    }
    else
    {
        out.push_back(partOf(S, p, 0));
    }
    return out;
}


// Whether a ball (centre c, radius r) can reach the shape S at pose p
bool reaches(const vec3& c, double r, const shape& S, const bodyPose& p)
{
    if (S.shapeKind() == shape::kind::halfSpace)
    {
        return p.vectorToWorld(vec3::UnitZ()).dot(c - p.position()) <= r;
    }
    if (const auto* w = shapeAs<wallMeshShape>(S))
    {
        return !w->clearOf(p.toBody(c), r);
    }
    return (c - p.position()).norm() <= r + S.boundingRadius();
}


bool neighbours(const shape& S, int i, int j)
{
    if (i == j) return true;
    const auto* m = shapeAs<triangleMeshShape>(S);
    if (!m || m->pieces().empty()) return false;
    const std::vector<int>& n = m->pieceNeighbours(i);
    return std::find(n.begin(), n.end(), j) != n.end();
}


bool apart(const shape& X, const bodyPose& pX, const shape& Y, const bodyPose& pY)
{
    const auto* mx = shapeAs<triangleMeshShape>(X);
    const auto* my = shapeAs<triangleMeshShape>(Y);
    if (!mx || !my || !mx->convex() || !my->convex())
    {
        return false;
    }
    const mat3 RxT = pX.rotation().transpose();
    return !convexDistance
    (
        mx->convex()->vertices(), my->convex()->vertices(),
        RxT*pY.rotation(), RxT*(pY.position() - pX.position())
    ).intersecting;
}


int root(std::vector<int>& up, int i)
{
    while (up[i] != i) i = up[i] = up[up[i]];
    return i;
}

} // End anonymous namespace


bool pieceOverlap::handles(const shape& A, const shape& B)
{
    auto pieced = [](const shape& S)
    {
        const auto* m = shapeAs<triangleMeshShape>(S);
        return m && !m->pieces().empty();
    };
    auto partner = [&](const shape& S)
    {
        const auto* m = shapeAs<triangleMeshShape>(S);
        return (m && (m->convex() || !m->pieces().empty()))
            || S.shapeKind() == shape::kind::halfSpace
            || S.shapeKind() == shape::kind::wallMesh;
    };
    return (pieced(A) && partner(B)) || (pieced(B) && partner(A));
}


contactGeometry pieceOverlap::evaluate
(
    const overlapEngine& perPiece,
    const shape& A, const bodyPose& pA,
    const shape& B, const bodyPose& pB,
    const overlapSettings& settings
)
{
    // The pieces of each side that can reach the other body: their balls,
    // and their boxes against its box
    auto near = [](std::vector<part> P, const shape& other, const bodyPose& pOther)
    {
        const part whole = partOf(other, pOther, 0);
        std::vector<part> kept;
        for (const part& q : P)
        {
            if
            (
                unbounded(*q.s)
             || (
                    reaches(q.pose.position(), q.s->boundingRadius(), other, pOther)
                 && (
                        whole.box.empty()
                     || (q.box.overlaps(whole.box) && !orientedApart(q, whole))
                    )
                )
            )
            {
                kept.push_back(q);
            }
        }
        return kept;
    };
    const std::vector<part> a = near(partsOf(A, pA), B, pB);
    const std::vector<part> b = near(partsOf(B, pB), A, pA);

    // Each pair of parts whose balls meet (a plane or a wall: the pieces
    // kept reach it)
    struct piecewise
    {
        contactRegion r;
        int ia, ib;
    };
    std::vector<piecewise> found;
    contactGeometry g;
    for (const part& x : a)
    {
        for (const part& y : b)
        {
            if
            (
                !unbounded(*x.s) && !unbounded(*y.s)
             && (
                    !x.box.overlaps(y.box)
                 || (x.pose.position() - y.pose.position()).norm()
                  > x.s->boundingRadius() + y.s->boundingRadius()
                 || orientedApart(x, y)
                )
            )
            {
                continue;
            }
            // Two convex parts apart (GJK on their corners, a fraction of
            // a clip's cost): no overlap
            if (apart(*x.s, x.pose, *y.s, y.pose))
            {
                continue;
            }
            const contactGeometry one = perPiece.evaluate(*x.s, x.pose, *y.s, y.pose, settings);
            g.queries += one.queries;
            g.leaves += one.leaves;
            for (const contactRegion& r : one.regions)
            {
                found.push_back({r, x.index, y.index});
            }
        }
    }

    // Regions of the same or neighbouring pieces on both sides whose
    // boxes meet are one
    const double eps =
        1e-9*(shapeAs<triangleMeshShape>(A) ? A.boundingRadius() : B.boundingRadius());
    const int n = int(found.size());
    std::vector<int> up(n);
    std::iota(up.begin(), up.end(), 0);
    for (int i = 0; i < n; ++i)
    {
        for (int j = i + 1; j < n; ++j)
        {
            const bool samePair = found[i].ia == found[j].ia && found[i].ib == found[j].ib;
            const axisAlignedBox& bi = found[i].r.box;
            const axisAlignedBox& bj = found[j].r.box;
            if
            (
                !samePair
             && neighbours(A, found[i].ia, found[j].ia)
             && neighbours(B, found[i].ib, found[j].ib)
             && (bi.empty() || bj.empty() || bi.inflated(eps).overlaps(bj))
            )
            {
                up[root(up, i)] = root(up, j);
            }
        }
    }
    std::vector<std::vector<int>> groups(n);
    for (int i = 0; i < n; ++i) groups[root(up, i)].push_back(i);

    for (const std::vector<int>& G : groups)
    {
        if (G.empty()) continue;
        if (G.size() == 1)
        {
            g.regions.push_back(found[G[0]].r);
            continue;
        }
        contactRegion m;
        m.volume = 0;
        m.point = vec3::Zero();
        int largest = G[0];
        for (const int i : G)
        {
            const contactRegion& r = found[i].r;
            m.volume += r.volume;
            m.point += r.volume*r.point;
            m.areaVector += r.areaVector;
            if (r.volume > found[largest].r.volume) largest = i;
        }
        m.point /= m.volume;
        m.areaMoment = vec3::Zero();
        for (const int i : G)
        {
            const contactRegion& r = found[i].r;
            m.areaMoment += r.areaMoment + (r.point - m.point).cross(r.areaVector);
        }
        bool boxed = true;
        for (const int i : G)
        {
            boxed = boxed && !found[i].r.box.empty();
            m.box.add(found[i].r.box);
        }
        if (!boxed) m.box = axisAlignedBox();
        // S of parts that cancel (a body wholly inside the other): zero
        double parts = 0;
        for (const int i : G) parts += found[i].r.area;
        if (!(m.areaVector.norm() > 1e-9*parts))
        {
            m.areaVector = vec3::Zero();
        }
        m.area = m.areaVector.norm();
        m.normal = m.area > 0 ? vec3(m.areaVector/m.area) : found[largest].r.normal;
        g.regions.push_back(m);
    }
    // Largest first, as the other engines (stable: the pieces' order)
    overlapTools::sortLargestFirst(g.regions, true);
    return g;
}

} // End namespace immersedDEM
