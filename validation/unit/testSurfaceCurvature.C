/*---------------------------------------------------------------------------*\
Description
    Tests of the surface curvature the closest-point queries return (the
    shape operator: exact for a sphere, fitted per triangle for a mesh,
    zero across sharp edges) and of what it is for: the virtual mesh's
    leaves bend their tangent planes with it, which removes the tangent
    planes' excess volume between two convex surfaces.
\*---------------------------------------------------------------------------*/

#include "virtualMeshOverlap.H"
#include "exactOverlap.H"
#include "sphereOverlap.H"
#include "sphereShape.H"
#include "triangleMeshShape.H"
#include "primitiveMeshes.H"
#include "testHelpers.H"

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

using namespace immersedDEM;
using immersedDEM::test::relErr;

namespace
{

// Eigenvalues of the shape operator in the plane normal to n, ascending
std::pair<double, double> principalCurvatures(const surfacePoint& sp)
{
    const Eigen::SelfAdjointEigenSolver<mat3> es(sp.curvature);
    // The eigenvector closest to n carries the normal eigenvalue (0)
    int normalIdx = 0;
    double best = -1;
    for (int k = 0; k < 3; ++k)
    {
        const double c = std::abs(es.eigenvectors().col(k).dot(sp.normal));
        if (c > best) { best = c; normalIdx = k; }
    }
    std::vector<double> t;
    for (int k = 0; k < 3; ++k) if (k != normalIdx) t.push_back(es.eigenvalues()(k));
    return {std::min(t[0], t[1]), std::max(t[0], t[1])};
}

// The same shape seen through flat tangent planes: curvature dropped
class flatShape
:
    public shape
{
    const shape& s_;

public:

    explicit flatShape(const shape& s) : s_(s) {}
    std::string type() const override { return s_.type(); }
    double volume() const override { return s_.volume(); }
    vec3 principalMoments() const override { return s_.principalMoments(); }
    axisAlignedBox localBox() const override { return s_.localBox(); }
    double boundingRadius() const override { return s_.boundingRadius(); }
    using shape::inside;
    using shape::signedDistance;
    using shape::closest;
    bool inside(const vec3& p) const override { return s_.inside(p); }
    double signedDistance(const vec3& p) const override { return s_.signedDistance(p); }
    surfacePoint closest(const vec3& p) const override
    {
        surfacePoint sp = s_.closest(p);
        sp.curvature.setZero();
        return sp;
    }
    triangleSoup surface() const override { return s_.surface(); }
};

} // End anonymous namespace


TEST(surfaceCurvature, sphereIsExactAndFollowsThePose)
{
    const double R = 0.004;
    const sphereShape s(R);
    const bodyPose pose(vec3(0.01, -0.02, 0.003), quat(Eigen::AngleAxisd(0.7, vec3(1, 2, 3).normalized())));
    const vec3 x = pose.position() + vec3(0.003, 0.001, -0.004);
    const surfacePoint sp = s.closest(pose, x);
    const mat3 expected = (mat3::Identity() - sp.normal*sp.normal.transpose())/R;
    EXPECT_LT((sp.curvature - expected).norm(), 1e-9/R);
    EXPECT_LT((sp.curvature*sp.normal).norm(), 1e-9/R);
}


TEST(surfaceCurvature, icosphereTrianglesBendLikeTheSphere)
{
    // Level 4: 5120 triangles, edges about R/10
    const double R = 0.005;
    const triangleMeshShape mesh(primitiveMeshes::icosphere(R, 4), "icosphere");
    double worst = 0, worstNormal = 0;
    for (int i = 0; i < 200; ++i)
    {
        const vec3 dir = vec3(std::sin(0.37*i + 0.2), std::cos(1.13*i), std::sin(0.71*i + 1)).normalized();
        // Outside, on and inside the surface
        const surfacePoint sp = mesh.closest(dir*R*(0.8 + 0.002*i));
        const auto k = principalCurvatures(sp);
        worst = std::max({worst, std::abs(k.first*R - 1), std::abs(k.second*R - 1)});
        worstNormal = std::max(worstNormal, (sp.curvature*sp.normal).norm()*R);
    }
    EXPECT_LT(worst, 0.1) << "principal curvatures off 1/R by up to " << 100*worst << "%";
    // The operator acts in the face's plane, the closest normal is within
    // a facet's angle of it
    EXPECT_LT(worstNormal, 0.15);
}


TEST(surfaceCurvature, boxFacesStayFlatAtTheirSharpEdges)
{
    const triangleMeshShape box(primitiveMeshes::box(vec3(0.002, 0.003, 0.004)), "box");
    for (const vec3& x : {vec3(0.0019, 0.0029, 0), vec3(0.001, 0.0031, 0.0039),
                          vec3(0.0025, 0, 0), vec3(0, 0, 0.0041)})
    {
        EXPECT_LT(box.closest(x).curvature.norm(), 1e-9) << x.transpose();
    }
}


TEST(surfaceCurvature, virtualMeshLeavesLoseTheTangentPlaneExcess)
{
    // Two spheres 0.2% of d into each other: the lens is 10 um thick,
    // a tenth of the level-2 leaf (h/4 = 125 um). Flat tangent planes put
    // a sagitta of about kappa s^2/12 per unit area of each cap into the
    // lens, several per cent here; bent by the curvature the leaves give
    // the lens within 0.5%, for the sphere and for a level-5 icosphere.
    const double R = 0.005, h = 0.0005, frac = 0.002;
    const vec3 c2(0.0013, 0.0021, 0.0007);
    const vec3 c1 = c2 - (2*R - frac*2*R)*vec3(1, 2, 3).normalized();
    const bodyPose p1(c1, quat::Identity()), p2(c2, quat::Identity());
    const overlapSettings coarse{h, 2};

    const sphereShape s(R);
    const flatShape sFlat(s);
    const double lens = sphereOverlap::lens(c1, R, c2, R).volume();
    const double v = virtualMeshOverlap().evaluate(s, p1, s, p2, test::octree(h, 2)).volume();
    const double vFlat = virtualMeshOverlap().evaluate(sFlat, p1, sFlat, p2, coarse).volume();
    std::cout << "sphere lens at level 2: flat " << 100*(vFlat/lens - 1)
              << "%, curved " << 100*(v/lens - 1) << "%" << std::endl;
    EXPECT_GT(vFlat/lens - 1, 0.02);
    EXPECT_LT(relErr(v, lens), 0.005);

    const triangleMeshShape ico(primitiveMeshes::icosphere(R, 5), "icosphere");
    const flatShape icoFlat(ico);
    const double exact = exactOverlap().evaluate(ico, p1, ico, p2, {}).volume();
    const double vm = virtualMeshOverlap().evaluate(ico, p1, ico, p2, coarse).volume();
    const double vmFlat = virtualMeshOverlap().evaluate(icoFlat, p1, icoFlat, p2, coarse).volume();
    std::cout << "icosphere lens at level 2: flat " << 100*(vmFlat/exact - 1)
              << "%, curved " << 100*(vm/exact - 1) << "%" << std::endl;
    EXPECT_GT(vmFlat/exact - 1, 0.02);
    EXPECT_LT(relErr(vm, exact), 0.005);
}


TEST(surfaceCurvature, smoothCurvatureIsContinuousAcrossFacesWherePerFaceJumps)
{
    // A Raschig ring (4 mm, bore 2 mm, 6 mm high, 24 sides): across each
    // edge between two faces of one side of a crease (the cylinders'
    // facets), the curvature just inside one face and just inside the
    // other, 1e-10 m from the edge's middle and 1e-10 m off the surface
    // (at a concave edge the closest point is then at most 1.3e-10 m into
    // the other face). smoothCurvature: the same on both sides within 1e-6
    // of the largest (the corners' interpolation changes by at most the
    // faces' jump, 0.37 of the largest, over a facet of 1 mm: 5e-8 here). The faces' own curvatures (what the
    // films used, and what a point on the edge gets from whichever face
    // the tree returns) must jump across some edge by more than 1%: the
    // defect this replaces (serial and parallel films of rings 3% apart)
    const triangleMeshShape ring(primitiveMeshes::hollowCylinder(0.004, 0.002, 0.006, 24), "ring");
    const surfaceDistance& d = ring.distanceField();
    const std::vector<vec3>& P = ring.points();
    const double cosCrease = std::cos(surfaceDistance::creaseAngleDegrees*M_PI/180);
    double scale = 0;
    for (int f = 0; f < int(ring.surface().faces.size()); ++f) scale = std::max(scale, d.faceCurvature(f).norm());
    ASSERT_GT(scale, 0);
    double worstSmooth = 0, worstFace = 0;
    int edges = 0;
    const int nF = int(ring.surface().faces.size());
    for (int f = 0; f < nF; ++f)
    {
        for (int g = f + 1; g < nF; ++g)
        {
            const triFace& a = d.face(f);
            const triFace& b = d.face(g);
            std::vector<int> shared;
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j)
                    if (a[i] == b[j]) shared.push_back(a[i]);
            if (shared.size() != 2 || d.faceNormal(f).dot(d.faceNormal(g)) < cosCrease) continue;
            const vec3 m = 0.5*(P[shared[0]] + P[shared[1]]);
            auto inside = [&](int face)
            {
                const triFace& t = d.face(face);
                const vec3 c = (P[t[0]] + P[t[1]] + P[t[2]])/3;
                return vec3(m + 1e-10*(c - m).normalized() + 1e-10*d.faceNormal(face));
            };
            const vec3 pf = inside(f), pg = inside(g);
            worstSmooth = std::max(worstSmooth, (d.smoothCurvature(pf) - d.smoothCurvature(pg)).norm());
            worstFace = std::max(worstFace, (d.closest(pf).curvature - d.closest(pg).curvature).norm());
            ++edges;
        }
    }
    std::cout << edges << " smooth edges: smoothCurvature jumps by " << worstSmooth/scale
        << " of the largest, the faces' own by " << worstFace/scale << std::endl;
    ASSERT_GT(edges, 100);
    EXPECT_LT(worstSmooth, 1e-6*scale);
    EXPECT_GT(worstFace, 1e-2*scale);
}
