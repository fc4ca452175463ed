#include "lubrication.H"
#include "convexDistance.H"
#include "convexPolyhedron.H"
#include "triangleMeshShape.H"
#include "sphereShape.H"
#include "halfSpaceShape.H"
#include "wallMeshShape.H"
#include "surfaceTriangles.H"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <vector>
#include <cmath>

namespace immersedDEM
{

namespace
{

//- A sphere (centre c, radius r) as A against any shape B
closestApproach sphereAgainst
(
    const vec3& c, double r, const shape& B, const bodyPose& pB, double cap
)
{
    closestApproach a;
    const surfacePoint sp = B.closest(pB, c);
    a.gap = sp.distance - r;
    if (!(a.gap < cap))
    {
        return a;
    }
    a.found = true;
    // B's outward normal at its closest point points to the centre
    a.normal = -sp.normal;
    a.pointB = sp.point;
    a.pointA = c + r*a.normal;
    return a;
}


//- The footprint of a mesh's face turned towards the other body (d in
//  the mesh's frame, low its least corner along d) into a, if smaller
//  than the one a holds; its mean height added to a's. The band takes
//  the whole face (a tenth of the body's bounding radius: a face tilted
//  by the angle limit, 0.05 rad, across the body) and at least the gap:
//  a face tilted against the other is a wedge (lubrication::wedge)
bool setFootprint
(
    closestApproach& a, const triangleBVH& T, const bodyPose& p,
    const vec3& d, double low, double band, double radius
)
{
    const triangleBVH::footprint f =
        T.footprintBelow(d, low, std::max({band, a.gap, 0.1*radius}));
    if (!(f.area > 0))
    {
        return false;
    }
    a.footprintHeight += f.height;
    if (a.footprintArea > 0 && a.footprintArea <= f.area)
    {
        return true;
    }
    const mat3& R = p.rotation();
    a.footprintArea = f.area;
    a.footprintSpread = R*f.spread*R.transpose();
    a.footprintCentre = p.toWorld(f.centroid);
    return true;
}


//- A plane (A) and a mesh (B): the lowest corners of B over the plane
closestApproach planeAgainstMesh
(
    const bodyPose& pP, const triangleBVH& tB, const bodyPose& pB, double cap,
    double band, double radius
)
{
    closestApproach a;
    const vec3 n = pP.vectorToWorld(vec3::UnitZ());
    const vec3 nB = pB.vectorToBody(n);
    const double h0 = n.dot(pB.position() - pP.position());
    const double low = tB.minAlong(nB);
    a.gap = h0 + low;
    if (!(a.gap < cap))
    {
        return a;
    }
    a.found = true;
    a.normal = n;
    // The corners within a band above the lowest, weighted to fade out
    // at its top: a face parallel to the plane gives its centre, an edge
    // its middle, and the point moves continuously as the body turns (a
    // point jumping between corners made the run depend on round-off)
    vec3 mean;
    if (!tB.meanCornerBelow(nB, low, band, mean))
    {
        return closestApproach();
    }
    a.pointB = pB.toWorld(mean);
    a.pointA = a.pointB - n.dot(a.pointB - pP.position())*n;
    setFootprint(a, tB, pB, nB, low, band, radius);
    return a;
}

} // End anonymous namespace


double lubrication::coefficient
(
    double mu, double R, double h, double hAct, double hRough
)
{
    if (!(h < hAct) || !(hAct > 0))
    {
        return 0;
    }
    const double g = std::max(h, std::min(hRough, hAct));
    return 6*M_PI*mu*R*R*(1/g - 1/hAct);
}


lubrication::flatFilm lubrication::flatCoefficients
(
    double mu, double area, double s1, double s2, double h, double hAct,
    double hRough
)
{
    flatFilm f;
    if (!(h < hAct) || !(hAct > 0) || !(area > 0) || !(s1 > 0) || !(s2 > 0))
    {
        return f;
    }
    const double g = std::max(h, std::min(hRough, hAct));
    const double film = M_PI*mu*(1/(g*g*g) - 1/(hAct*hAct*hAct));
    const double r = std::sqrt(std::sqrt(s1/s2));
    const double a1 = std::sqrt(area/M_PI)*r, a2 = std::sqrt(area/M_PI)/r;
    const double a1s = a1*a1, a2s = a2*a2;
    f.normal = 3*film*a1s*a1*a2s*a2/(a1s + a2s);
    f.tilt1 = film*a1*a2s*a2/(2/a1s + 6/a2s);
    f.tilt2 = film*a2*a1s*a1/(2/a2s + 6/a1s);
    return f;
}


closestApproach lubrication::approach
(
    const shape& A, const bodyPose& pA,
    const shape& B, const bodyPose& pB,
    double cap
)
{
    const auto* sA = shapeAs<sphereShape>(A);
    const auto* sB = shapeAs<sphereShape>(B);
    if (sA)
    {
        return sphereAgainst(pA.position(), sA->radius(), B, pB, cap);
    }
    if (sB)
    {
        closestApproach a = sphereAgainst(pB.position(), sB->radius(), A, pA, cap);
        std::swap(a.pointA, a.pointB);
        a.normal = -a.normal;
        return a;
    }
    const triangleBVH* tA = trianglesOf(A);
    const triangleBVH* tB = trianglesOf(B);
    if (shapeAs<halfSpaceShape>(A) && tB)
    {
        return planeAgainstMesh
        (
            pA, *tB, pB, cap, std::min(0.1*cap, 1e-2*B.boundingRadius()),
            B.boundingRadius()
        );
    }
    if (shapeAs<halfSpaceShape>(B) && tA)
    {
        closestApproach a = planeAgainstMesh
        (
            pB, *tA, pA, cap, std::min(0.1*cap, 1e-2*A.boundingRadius()),
            A.boundingRadius()
        );
        std::swap(a.pointA, a.pointB);
        a.normal = -a.normal;
        return a;
    }
    closestApproach a;
    if (!tA || !tB || tA->empty() || tB->empty())
    {
        return a;
    }
    // B's triangles in A's frame
    const mat3 R = pA.rotation().transpose()*pB.rotation();
    const vec3 t = pA.rotation().transpose()*(pB.position() - pA.position());
    const auto* mA = shapeAs<triangleMeshShape>(A);
    const auto* mB = shapeAs<triangleMeshShape>(B);
    // A convex body in a locally convex part of a wall mesh: the least
    // height of its corners over the wall's planes there
    bool wallFirst = false;
    const convexWallGap cw = convexWallDistance(A, pA, B, pB, cap, wallFirst);
    if (cw.known)
    {
        if (cw.beyondReach || !(cw.gap < cap))
        {
            return a;
        }
        a.found = true;
        if (!(cw.gap > 0))
        {
            a.gap = 0;
            return a;
        }
        a.gap = cw.gap;
        a.pointA = wallFirst ? cw.pointWall : cw.pointBody;
        a.pointB = wallFirst ? cw.pointBody : cw.pointWall;
    }
    else if (mA && mB && madeOfConvexParts(*mA) && madeOfConvexParts(*mB))
    {
        // Two convex meshes: their corners' distance (GJK); bodies of
        // convex pieces: their hulls' or their pieces' closest points
        // (GJK), exact
        const convexClosest c = mA->convex() && mB->convex()
            ? convexDistance(mA->convex()->vertices(), mB->convex()->vertices(), R, t)
            : closestParts(*mA, pA, *mB, pB, cap, -1, false);
        if (c.intersecting)
        {
            a.found = true;
            a.gap = 0;
            return a;
        }
        if (!(c.distance < cap))
        {
            return a;
        }
        a.found = true;
        a.gap = c.distance;
        a.pointA = pA.toWorld(c.pointA);
        a.pointB = pA.toWorld(c.pointB);
    }
    else
    {
        const triangleBVH::pairHit hit = triangleBVH::closestPair(*tA, *tB, R, t, cap);
        if (hit.faceA < 0)
        {
            return a;
        }
        a.found = true;
        a.gap = hit.distance;
        a.pointA = pA.toWorld(hit.pointA);
        a.pointB = pA.toWorld(hit.pointB);
    }
    if (a.gap > 0)
    {
        a.normal = (a.pointB - a.pointA)/(a.pointB - a.pointA).norm();

        // Faces nearly parallel: the closest pair of triangles is any
        // point of them; the film's centre is the weighted middle of the
        // body's corners nearest the other (meanCornerBelow: a face's
        // centre, continuous as the body turns), of both bodies' for two
        // bodies
        const double band =
            std::min(0.1*cap, 1e-2*std::min(A.boundingRadius(), B.boundingRadius()));
        vec3 sum = vec3::Zero();
        int parts = 0, flat = 0;
        const bool wallA = shapeAs<wallMeshShape>(A) != nullptr;
        const bool wallB = shapeAs<wallMeshShape>(B) != nullptr;
        auto face = [&](const triangleBVH& T, const bodyPose& p, const vec3& dir, const vec3& shift, double radius)
        {
            const vec3 d = p.vectorToBody(dir);
            const double low = T.minAlong(d);
            vec3 mean;
            if (T.meanCornerBelow(d, low, band, mean))
            {
                sum += p.toWorld(mean) + shift;
                ++parts;
            }
            flat += setFootprint(a, T, p, d, low, band, radius);
        };
        if (!wallB) face(*tB, pB, a.normal, -0.5*a.gap*a.normal, B.boundingRadius());
        if (!wallA) face(*tA, pA, -a.normal, 0.5*a.gap*a.normal, A.boundingRadius());
        if (flat < (wallA || wallB ? 1 : 2))
        {
            // A face against an edge or a corner: no parallel film
            a.footprintArea = 0;
            a.footprintSpread = mat3::Zero();
            a.footprintHeight = 0;
        }
        if (parts == (wallA || wallB ? 1 : 2))
        {
            const vec3 middle = sum/double(parts);
            a.pointA = middle - 0.5*a.gap*a.normal;
            a.pointB = middle + 0.5*a.gap*a.normal;
        }
    }
    // Inside the other (no triangles crossing, but a body through a wall
    // or inside another): the caller takes the contact's geometry
    if (a.gap > 0 && A.signedDistance(pA, a.pointB) < 0)
    {
        a.gap = 0;
    }
    return a;
}


mat3 lubrication::curvatureNear(const shape& S, const bodyPose& p, const vec3& x)
{
    if (shapeAs<halfSpaceShape>(S))
    {
        return mat3::Zero();
    }
    // A triangle surface's, continuous in x: its faces' own curvatures
    // jump from face to face, and which face a point on an edge goes to
    // is decided by round-off (serial and parallel runs of rings took
    // different ones, and their films differed by 3%)
    const surfaceDistance* d = nullptr;
    if (const auto* m = shapeAs<triangleMeshShape>(S)) d = &m->distanceField();
    else if (const auto* w = shapeAs<wallMeshShape>(S)) d = &w->distanceField();
    if (d)
    {
        const mat3& R = p.rotation();
        return R*d->smoothCurvature(p.toBody(x))*R.transpose();
    }
    return S.closest(p, x).curvature;
}


lubrication::wedgeFactors lubrication::wedgeIntegrated(const double ratio)
{
    wedgeFactors w;
    if (!(ratio > 1))
    {
        return w;
    }
    // h = 1 + (ratio - 1) s on s in [0, 1]; the moments I_k = int s^k/h^3
    // ds, integrated in t = ln h (smooth: the integrand is s^k e^(-2t)
    // dt/(ratio - 1)) by 4-point Gauss-Legendre on 64 intervals
    const double T = std::log(ratio);
    double I[5] = {0, 0, 0, 0, 0};
    const double xg[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
    const double wg[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};
    const int n = 64;
    for (int i = 0; i < n; ++i)
    {
        for (int g = 0; g < 4; ++g)
        {
            const double t = T*(i + 0.5*(1 + xg[g]))/n;
            const double s = std::expm1(t)/(ratio - 1);
            const double f = wg[g]*0.5*T/n*std::exp(-2*t)/(ratio - 1);
            double sk = 1;
            for (double& Ik : I)
            {
                Ik += f*sk;
                sk *= s;
            }
        }
    }
    // The film for dh/dt = -(a + b (s - 1/2)): h^3 p' = C1 - J, J = c1 s
    // + c2 s^2 (c1 = 12 (a - b/2), c2 = 6 b), p(0) = p(1) = 0; force int
    // p ds and moment int (s - 1/2) p ds, by parts in the moments
    auto film = [&I](double a, double b, double& F, double& M)
    {
        const double c1 = 12*(a - 0.5*b), c2 = 6*b;
        const double C1 = (c1*I[1] + c2*I[2])/I[0];
        F = C1*(I[0] - I[1]) - c1*(I[1] - I[2]) - c2*(I[2] - I[3]);
        M = -0.5*(C1*(I[2] - I[1]) - c1*(I[3] - I[2]) - c2*(I[4] - I[3]));
    };
    double Fa, Ma, Fb, Mb;
    film(1, 0, Fa, Ma);
    film(0, 1, Fb, Mb);
    // Parallel plates at the mean gap hm: F = 1/hm^3, M = 1/(60 hm^3)
    const double hm = 0.5*(1 + ratio), hm3 = hm*hm*hm;
    w.normal = Fa*hm3;
    w.tilt = 60*Mb*hm3;
    w.offset = -Ma/Fa;
    return w;
}


lubrication::wedgeFactors lubrication::wedge(const double ratio)
{
    // Nodes at ln(ratio) = k ln(1e4)/nodes
    static constexpr int nodes = 96;
    static const double top = std::log(1e4);
    static const std::vector<wedgeFactors> table = []
    {
        std::vector<wedgeFactors> t(nodes + 1);
        for (int k = 0; k <= nodes; ++k)
        {
            t[k] = wedgeIntegrated(std::exp(k*top/nodes));
        }
        return t;
    }();
    if (!(ratio > 1))
    {
        return table[0];
    }
    const double x = std::min(std::log(ratio), top)/top*nodes;
    const int k = std::min(int(x), nodes - 1);
    const double f = x - k;
    const wedgeFactors& p = table[k];
    const wedgeFactors& q = table[k + 1];
    wedgeFactors w;
    w.normal = p.normal + f*(q.normal - p.normal);
    w.tilt = p.tilt + f*(q.tilt - p.tilt);
    w.offset = p.offset + f*(q.offset - p.offset);
    return w;
}


lubrication::tangentAxes lubrication::principalInPlane(const mat3& M, const vec3& n)
{
    // A basis of the plane
    const vec3 a = std::abs(n.x()) < 0.9 ? vec3::UnitX() : vec3::UnitY();
    const vec3 t1 = n.cross(a).normalized();
    const vec3 t2 = n.cross(t1);
    const double m12 = 0.5*(t1.dot(M*t2) + t2.dot(M*t1));
    Eigen::Matrix2d m;
    m << t1.dot(M*t1), m12, m12, t2.dot(M*t2);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(m);
    tangentAxes axes;
    for (int i = 0; i < 2; ++i)
    {
        axes.e[i] = eig.eigenvectors()(0, i)*t1 + eig.eigenvectors()(1, i)*t2;
        axes.s[i] = eig.eigenvalues()(i);
    }
    return axes;
}


double lubrication::gapRadius
(
    const mat3& KA, const mat3& KB, const vec3& n, double Rcap
)
{
    const tangentAxes k = principalInPlane(KA + KB, n);
    const double kMin = 1/Rcap;
    const double k1 = std::max(k.s[0], kMin);
    const double k2 = std::max(k.s[1], kMin);
    return 1/std::sqrt(k1*k2);
}

} // End namespace immersedDEM
