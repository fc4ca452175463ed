#include "convexCells.H"
#include "triangleMeshShape.H"
#include "coreError.H"

#include <algorithm>
#include <cmath>
#include <limits>

namespace immersedDEM
{

namespace
{

//- The convex polyhedra of a shape the plane path serves: the shape's own,
//  or its pieces' with their frames in the body's; empty when it is none
std::vector<std::pair<const convexPolyhedron*, bodyPose>> polyhedraOf
(
    const shape& s, const bool piecesToo = true
)
{
    std::vector<std::pair<const convexPolyhedron*, bodyPose>> out;
    const triangleMeshShape* m = shapeAs<triangleMeshShape>(s);
    if (!m) return out;
    if (m->convex())
    {
        if (m->convex()->faces().size() <= convexCells::maxFaces)
        {
            out.emplace_back(m->convex(), bodyPose());
        }
        return out;
    }
    if (!piecesToo) return out;
    for (const auto& p : m->pieces())
    {
        const convexPolyhedron* P = p->convex();
        if (!P || P->faces().size() > convexCells::maxFaces)
        {
            out.clear();
            return out;
        }
        out.emplace_back(P, p->bodyInFile());
    }
    return out;
}


//- A polyhedron being clipped: its faces as polygons, the points of all
//  in one array (face f: points [first[f], first[f + 1]))
struct polygons
{
    std::vector<vec3> points;
    std::vector<int> first{0};

    void clear() { points.clear(); first.assign(1, 0); }
    int nFaces() const { return int(first.size()) - 1; }
    void close() { first.push_back(int(points.size())); }
};


//- Clip every face of X by n.y <= t into Y and close Y with the face on
//  the plane (the points there, in angular order about n). onPlane: the
//  tolerance of a point on the plane
void clip
(
    const polygons& X, const vec3& n, double t, double onPlane,
    polygons& Y, std::vector<vec3>& cap,
    std::vector<std::pair<double, int>>& order
)
{
    Y.clear();
    cap.clear();
    for (int f = 0; f < X.nFaces(); ++f)
    {
        const int b = X.first[f], e = X.first[f + 1];
        const size_t start = Y.points.size();
        for (int i = b; i < e; ++i)
        {
            const vec3& p = X.points[i];
            const vec3& q = X.points[i + 1 < e ? i + 1 : b];
            const double dp = n.dot(p) - t, dq = n.dot(q) - t;
            if (dp <= onPlane)
            {
                Y.points.push_back(p);
                if (dp >= -onPlane) cap.push_back(p);
            }
            if ((dp < -onPlane && dq > onPlane) || (dp > onPlane && dq < -onPlane))
            {
                // The crossing, from the inner end (the same point whichever
                // face of the edge computes it)
                const bool pIn = dp < 0;
                const vec3& a = pIn ? p : q;
                const vec3& c = pIn ? q : p;
                const double da = pIn ? dp : dq, dc = pIn ? dq : dp;
                const vec3 x = a + (c - a)*(da/(da - dc));
                Y.points.push_back(x);
                cap.push_back(x);
            }
        }
        if (Y.points.size() - start >= 3)
        {
            Y.close();
        }
        else
        {
            Y.points.resize(start);
        }
    }
    if (cap.size() < 3) return;
    vec3 m = vec3::Zero();
    for (const vec3& p : cap) m += p;
    m /= double(cap.size());
    const vec3 u = (std::abs(n.x()) < 0.9 ? vec3::UnitX() : vec3::UnitY()).cross(n).normalized();
    const vec3 w = n.cross(u);
    order.resize(cap.size());
    for (size_t i = 0; i < cap.size(); ++i)
    {
        const vec3 r = cap[i] - m;
        // A pseudo-angle: monotone in the angle, no atan2
        const double a = u.dot(r), b = w.dot(r);
        const double l = std::abs(a) + std::abs(b);
        double angle = l > 0 ? b/l : 0;
        if (a < 0) angle = 2 - angle;
        else if (b < 0) angle = 4 + angle;
        order[i] = {angle, int(i)};
    }
    std::sort(order.begin(), order.end());
    for (const auto& o : order) Y.points.push_back(cap[o.second]);
    Y.close();
}


//- The volume of X clipped by n.y <= t (the last clip): each face's
//  clipped outline integrated as it is produced (divergence theorem
//  about the origin), closed by the face on the plane: its area vector
//  closes theirs, and its every point has n.y = t
double clippedVolumeOf(const polygons& X, const vec3& n, double t, double onPlane)
{
    double V = 0;
    vec3 sum = vec3::Zero();
    for (int f = 0; f < X.nFaces(); ++f)
    {
        const int b = X.first[f], e = X.first[f + 1];
        vec3 q0 = vec3::Zero(), qp = vec3::Zero(), A = vec3::Zero();
        int count = 0;
        auto emit = [&](const vec3& q)
        {
            if (count == 0) q0 = q;
            else if (count >= 2) A += (qp - q0).cross(q - q0);
            qp = q;
            ++count;
        };
        double dp = n.dot(X.points[b]) - t;
        for (int i = b; i < e; ++i)
        {
            const vec3& p = X.points[i];
            const vec3& q = X.points[i + 1 < e ? i + 1 : b];
            const double dq = n.dot(q) - t;
            if (dp <= onPlane) emit(p);
            if ((dp < -onPlane && dq > onPlane) || (dp > onPlane && dq < -onPlane))
            {
                const bool pIn = dp < 0;
                const vec3& a = pIn ? p : q;
                const vec3& c = pIn ? q : p;
                const double da = pIn ? dp : dq, dc = pIn ? dq : dp;
                emit(a + (c - a)*(da/(da - dc)));
            }
            dp = dq;
        }
        if (count >= 3)
        {
            V += q0.dot(A);
            sum += A;
        }
    }
    return (V - t*n.dot(sum))/6;
}

//- The volume of the box [-e, e] behind two or three planes n_k.y <= t_k
//  whose normals are well apart, without building their faces: the box's
//  faces are clipped by every plane and integrated (divergence theorem
//  about the origin); each plane's face has every point at n_k.y = t_k
//  and an unknown area b_k/2, and the faces' area vectors close, so
//  sum b_k n_k = -(the clipped box faces' sum): two or three independent
//  normals give the b_k. False when the normals are too near dependent
//  (the caller clips face by face then)
bool boxVolumeBehindFew
(
    const vec3& e, const std::vector<std::pair<vec3, double>>& cuts,
    double onPlane, double& volume
)
{
    const size_t k = cuts.size();
    mat3 N = mat3::Zero();
    for (size_t i = 0; i < k; ++i) N.col(i) = cuts[i].first;
    if (k == 2)
    {
        if (N.col(0).cross(N.col(1)).squaredNorm() < 1e-4) return false;
    }
    else if (k != 3 || std::abs(N.determinant()) < 1e-2)
    {
        return false;
    }

    static constexpr int faces[6][4] =
    {
        {0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
        {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}
    };
    vec3 corner[8];
    for (int c = 0; c < 8; ++c)
    {
        for (int i = 0; i < 3; ++i) corner[c][i] = (c >> i) & 1 ? e[i] : -e[i];
    }
    double V = 0;
    vec3 S = vec3::Zero();
    for (const auto& f : faces)
    {
        vec3 a[16], b[16];
        int na = 4;
        for (int i = 0; i < 4; ++i) a[i] = corner[f[i]];
        for (size_t c = 0; c < k && na >= 3; ++c)
        {
            const vec3& n = cuts[c].first;
            const double t = cuts[c].second;
            int nb = 0;
            double dp = n.dot(a[0]) - t;
            for (int i = 0; i < na; ++i)
            {
                const vec3& p = a[i];
                const vec3& q = a[i + 1 < na ? i + 1 : 0];
                const double dq = n.dot(q) - t;
                if (dp <= onPlane) b[nb++] = p;
                if ((dp < -onPlane && dq > onPlane) || (dp > onPlane && dq < -onPlane))
                {
                    const bool pIn = dp < 0;
                    const vec3& x = pIn ? p : q;
                    const vec3& y = pIn ? q : p;
                    const double dx = pIn ? dp : dq, dy = pIn ? dq : dp;
                    b[nb++] = x + (y - x)*(dx/(dx - dy));
                }
                dp = dq;
            }
            na = nb;
            for (int i = 0; i < na; ++i) a[i] = b[i];
        }
        if (na < 3) continue;
        vec3 A = vec3::Zero();
        for (int i = 1; i + 1 < na; ++i) A += (a[i] - a[0]).cross(a[i + 1] - a[0]);
        V += a[0].dot(A);
        S += A;
    }
    // sum b_i n_i = -S (least squares for two planes: consistent)
    vec3 bk = vec3::Zero();
    if (k == 2)
    {
        const double c = N.col(0).dot(N.col(1));
        const double r0 = -S.dot(N.col(0)), r1 = -S.dot(N.col(1));
        const double det = 1 - c*c;
        bk[0] = (r0 - c*r1)/det;
        bk[1] = (r1 - c*r0)/det;
    }
    else
    {
        bk = N.partialPivLu().solve(-S);
    }
    for (size_t i = 0; i < k; ++i) V += cuts[i].second*bk[i];
    volume = V/6;
    return true;
}

} // End anonymous namespace


bool convexCells::handles(const shape& s, const bool piecesToo)
{
    return !polyhedraOf(s, piecesToo).empty();
}


convexCells::convexCells(const shape& s, const bodyPose& pose)
:
    pose_(pose)
{
    const auto polyhedra = polyhedraOf(s);
    if (polyhedra.empty())
    {
        throw coreError
        (
            "convexCells: the shape is neither a convex mesh nor a union of"
            " convex pieces of at most " + std::to_string(maxFaces) + " faces each"
        );
    }
    if (polyhedra.size() > 1) whole_ = &s;
    pieces_.resize(polyhedra.size());
    for (size_t k = 0; k < polyhedra.size(); ++k)
    {
        const convexPolyhedron& P = *polyhedra[k].first;
        const bodyPose p = pose*polyhedra[k].second;
        piece& Q = pieces_[k];
        for (const auto& f : P.faces())
        {
            const vec3 n = p.vectorToWorld(f.normal);
            Q.normal.push_back(n);
            Q.offset.push_back(f.offset + n.dot(p.position()));
            Q.faces.push_back(f.corners);
        }
        for (const vec3& x : P.vertices())
        {
            Q.corner.push_back(p.toWorld(x));
        }
        for (const auto& f : Q.faces)
        {
            axisAlignedBox b;
            b.min = b.max = Q.corner[f[0]];
            for (const int i : f)
            {
                b.min = b.min.cwiseMin(Q.corner[i]);
                b.max = b.max.cwiseMax(Q.corner[i]);
            }
            Q.faceBox.push_back(b);
        }
        Q.centre = vec3::Zero();
        for (const vec3& x : Q.corner) Q.centre += x;
        Q.centre /= double(Q.corner.size());
        for (const vec3& x : Q.corner)
        {
            Q.radius = std::max(Q.radius, (x - Q.centre).norm());
        }
        Q.radius *= 1 + 1e-12;
    }
}


double convexCells::planeDistance(const size_t k, const vec3& x) const
{
    const piece& P = pieces_[k];
    double s = -std::numeric_limits<double>::max();
    for (size_t i = 0; i < P.normal.size(); ++i)
    {
        s = std::max(s, P.normal[i].dot(x) - P.offset[i]);
    }
    return s;
}


surfacePoint convexCells::outsideClosest
(
    const piece& P, const vec3& x, const double s, const int kMax
) const
{
    // The foot on a face's plane, if within its outline
    auto footInFace = [&](const int f, const double sf, vec3& y)
    {
        const vec3& n = P.normal[f];
        y = x - sf*n;
        const std::vector<int>& c = P.faces[f];
        for (size_t i = 0; i < c.size(); ++i)
        {
            const vec3& a = P.corner[c[i]];
            const vec3& b = P.corner[c[(i + 1) % c.size()]];
            if ((b - a).cross(y - a).dot(n) < 0) return false;
        }
        return true;
    };

    surfacePoint sp;
    vec3 y;
    if (footInFace(kMax, s, y))
    {
        // No point of the body is nearer than the plane farthest in front
        sp.point = y;
        sp.normal = P.normal[kMax];
        sp.distance = s;
        return sp;
    }
    // The nearest point of the faces x is in front of (the nearest point
    // of a convex body lies on such a face)
    double best = std::numeric_limits<double>::max();
    for (size_t f = 0; f < P.normal.size(); ++f)
    {
        const double sf = P.normal[f].dot(x) - P.offset[f];
        if (sf <= 0 || sf*sf >= best) continue;
        if (footInFace(int(f), sf, y))
        {
            best = sf*sf;
            sp.point = y;
            continue;
        }
        const std::vector<int>& c = P.faces[f];
        for (size_t i = 0; i < c.size(); ++i)
        {
            const vec3& a = P.corner[c[i]];
            const vec3& b = P.corner[c[(i + 1) % c.size()]];
            const vec3 ab = b - a;
            const double t = std::clamp((x - a).dot(ab)/ab.squaredNorm(), 0.0, 1.0);
            const vec3 q = a + t*ab;
            const double d2 = (x - q).squaredNorm();
            if (d2 < best)
            {
                best = d2;
                sp.point = q;
            }
        }
    }
    sp.distance = std::sqrt(best);
    sp.normal = (x - sp.point)/sp.distance;
    return sp;
}


narrowBand::value convexCells::classify(const vec3& x, const double reach) const
{
    narrowBand::value v;
    if (pieces_.size() == 1)
    {
        const piece& P = pieces_[0];
        double s = -std::numeric_limits<double>::max();
        int k = 0;
        for (size_t i = 0; i < P.normal.size(); ++i)
        {
            const double si = P.normal[i].dot(x) - P.offset[i];
            if (si > s) { s = si; k = int(i); }
        }
        v.phi = s;
        if (s > reach || s < -reach)
        {
            return v;
        }
        v.exact = true;
        if (s <= 0)
        {
            // Inside: the nearest face's plane, its foot on the face
            v.sp.point = x - s*P.normal[k];
            v.sp.normal = P.normal[k];
            v.sp.distance = s;
            return v;
        }
        v.sp = outsideClosest(P, x, s, k);
        v.phi = v.sp.distance;
        return v;
    }

    // A union of pieces: a lower bound of each piece's signed distance
    // (its sphere's where that is beyond the reach, else its planes')
    thread_local std::vector<double> lower;
    lower.resize(pieces_.size());
    double sMin = std::numeric_limits<double>::max();
    for (size_t k = 0; k < pieces_.size(); ++k)
    {
        const double sphere = (x - pieces_[k].centre).norm() - pieces_[k].radius;
        lower[k] = sphere > reach ? sphere : planeDistance(k, x);
        sMin = std::min(sMin, lower[k]);
    }
    v.phi = sMin;
    if (sMin > reach || sMin < -reach)
    {
        // Outside every piece by more than the reach, or deeper than it
        // in one (the union's depth is no less)
        return v;
    }
    v.exact = true;
    if (sMin <= 0)
    {
        // Inside, near a piece's face: the union's own depth (beyond the
        // reach, near the pieces' shared faces only: settled)
        v.sp = whole_->closest(pose_, x);
        v.phi = v.sp.distance;
        v.exact = std::abs(v.phi) <= reach;
        return v;
    }
    double best = std::numeric_limits<double>::max();
    for (size_t k = 0; k < pieces_.size(); ++k)
    {
        if (lower[k] >= best) continue;
        const piece& P = pieces_[k];
        double s = -std::numeric_limits<double>::max();
        int kMax = 0;
        for (size_t i = 0; i < P.normal.size(); ++i)
        {
            const double si = P.normal[i].dot(x) - P.offset[i];
            if (si > s) { s = si; kMax = int(i); }
        }
        if (s >= best) continue;
        const surfacePoint sp = outsideClosest(P, x, s, kMax);
        if (sp.distance < best)
        {
            best = sp.distance;
            v.sp = sp;
        }
    }
    v.phi = best;
    return v;
}


double convexCells::clippedVolume(const piece& P, const vec3& lo, const vec3& hi) const
{
    // About the box centre (round-off), the planes that cut the box
    const vec3 c = 0.5*(lo + hi);
    const vec3 e = 0.5*(hi - lo);
    // The scratch of this thread (no allocation per cell)
    thread_local std::vector<std::pair<vec3, double>> cuts;
    thread_local std::vector<int> cutFace;
    thread_local polygons X, Y;
    thread_local std::vector<vec3> cap;
    thread_local std::vector<std::pair<double, int>> order;
    cuts.clear();
    cutFace.clear();
    double s = -std::numeric_limits<double>::max();
    int kMax = 0;
    for (size_t i = 0; i < P.normal.size(); ++i)
    {
        const vec3& n = P.normal[i];
        const double t = P.offset[i] - n.dot(c);
        const double r = n.cwiseAbs().dot(e);
        if (t <= -r) return 0;          // the box is wholly in front
        if (t < r)
        {
            cuts.emplace_back(n, t);
            cutFace.push_back(int(i));
        }
        if (-t > s) { s = -t; kMax = int(i); }
    }
    const double V = 8*e.prod();
    if (cuts.empty()) return V;
    if (cuts.size() > 1)
    {
        // A point of the body in the box (the centre, or the body's
        // nearest point to it): only faces meeting the box bound their
        // intersection there; their boxes, grown by round-off, meet it
        const double slack = 1e-9*e.norm();
        bool held = s <= 0;
        if (!held)
        {
            const vec3 q = outsideClosest(P, c, s, kMax).point - c;
            held = (q.cwiseAbs().array() <= e.array() + slack).all();
        }
        if (held)
        {
            size_t kept = 0;
            for (size_t k = 0; k < cuts.size(); ++k)
            {
                const axisAlignedBox& b = P.faceBox[cutFace[k]];
                if
                (
                    (b.min.array() <= hi.array() + slack).all()
                 && (b.max.array() >= lo.array() - slack).all()
                )
                {
                    cuts[kept++] = cuts[k];
                }
            }
            // (none: round-off; all of them clip, which is exact too)
            if (kept > 0) cuts.resize(kept);
        }
    }

    double few = 0;
    if
    (
        (cuts.size() == 2 || cuts.size() == 3)
     && boxVolumeBehindFew(e, cuts, 1e-12*e.norm(), few)
    )
    {
        return std::clamp(few, 0.0, V);
    }
    X.clear();
    for (int a = 0; a < 3; ++a)
    {
        const int u = (a + 1) % 3, w = (a + 2) % 3;
        for (const double side : {-1.0, 1.0})
        {
            // Corners counter-clockwise about the outward normal side e_a
            const double su[4] = {-1, 1, 1, -1}, sw[4] = {-1, -1, 1, 1};
            for (int k = 0; k < 4; ++k)
            {
                const int j = side > 0 ? k : 3 - k;
                vec3 p;
                p[a] = side*e[a];
                p[u] = su[j]*e[u];
                p[w] = sw[j]*e[w];
                X.points.push_back(p);
            }
            X.close();
        }
    }
    const double onPlane = 1e-12*e.norm();
    for (size_t k = 0; k + 1 < cuts.size(); ++k)
    {
        clip(X, cuts[k].first, cuts[k].second, onPlane, Y, cap, order);
        std::swap(X, Y);
        if (X.nFaces() < 4) return 0;
    }
    return std::clamp(clippedVolumeOf(X, cuts.back().first, cuts.back().second, onPlane), 0.0, V);
}


double convexCells::fraction(const vec3& lo, const vec3& hi) const
{
    const double V = (hi - lo).prod();
    double inside = 0;
    for (const piece& P : pieces_)
    {
        // A piece whose sphere misses the box has none of it
        const vec3 gap = (lo - P.centre).cwiseMax(P.centre - hi).cwiseMax(0.0);
        if (gap.squaredNorm() > P.radius*P.radius) continue;
        inside += clippedVolume(P, lo, hi);
    }
    return std::clamp(inside/V, 0.0, 1.0);
}

} // End namespace immersedDEM
