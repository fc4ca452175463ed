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
