// Mass properties of closed triangle surfaces against closed forms:
// boxes (exact), icosphere and torus (convergence), non-convex extruded L
// (exact, by decomposition into two boxes).

#include "massProperties.H"
#include "primitiveMeshes.H"
#include "triangleMeshShape.H"
#include "testHelpers.H"

#include <Eigen/Eigenvalues>

using namespace immersedDEM;
using namespace immersedDEM::test;

namespace
{

// Inertia tensor about its centroid of a solid box (unit density) with full
// side lengths L, axes along the coordinate axes
mat3 boxInertia(const vec3& L)
{
    const double m = L.prod();
    return (m/12.0*vec3
    (
        L.y()*L.y() + L.z()*L.z(),
        L.x()*L.x() + L.z()*L.z(),
        L.x()*L.x() + L.y()*L.y()
    )).asDiagonal();
}

// Inertia of a point mass m at offset d (parallel-axis term)
mat3 parallelAxis(double m, const vec3& d)
{
    return m*(d.squaredNorm()*mat3::Identity() - d*d.transpose());
}

// (tol: the caller's, round-off of exact formulas)
void expectMatNear(const mat3& A, const mat3& B, double tol)
{
    for (int i = 0; i < 3; ++i)
    {
        for (int j = 0; j < 3; ++j)
        {
            EXPECT_NEAR(A(i, j), B(i, j), tol) << "entry (" << i << ',' << j << ")";
        }
    }
}

const std::vector<Eigen::Vector2d> Lpolygon =
{
    {0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 3}, {0, 3}
};

} // End anonymous namespace


TEST(massProperties, unitCube)
{
    const massProperties mp = massProperties::of(primitiveMeshes::box(vec3::Constant(0.5)));
    EXPECT_NEAR(mp.volume, 1.0, 1e-12);
    EXPECT_NEAR(mp.centroid.norm(), 0.0, 1e-12);
    for (int i = 0; i < 3; ++i)
    {
        EXPECT_NEAR(mp.principalMoments[i], 1.0/6.0, 1e-12/6.0);
    }
    expectMatNear(mp.inertia, mat3::Identity()/6.0, 1e-13);
}


TEST(massProperties, boxExact)
{
    const vec3 h(1.0, 0.5, 0.25);
    const vec3 L = 2*h;
    const massProperties mp = massProperties::of(primitiveMeshes::box(h));

    const double V = L.prod();
    EXPECT_LT(relErr(mp.volume, V), 1e-12);
    EXPECT_NEAR(mp.centroid.norm(), 0.0, 1e-12);

    // Ascending: about x (longest) smallest, about z largest
    const vec3 I = boxInertia(L).diagonal();
    EXPECT_LT(relErr(mp.principalMoments[0], I.x()), 1e-12);
    EXPECT_LT(relErr(mp.principalMoments[1], I.y()), 1e-12);
    EXPECT_LT(relErr(mp.principalMoments[2], I.z()), 1e-12);
    EXPECT_LT(mp.principalMoments[0], mp.principalMoments[1]);
    EXPECT_LT(mp.principalMoments[1], mp.principalMoments[2]);
    expectMatNear(mp.inertia, boxInertia(L), 1e-12*I.z());

    // m/12 (b^2 + c^2) written out for the largest one
    EXPECT_LT(relErr(mp.principalMoments[2], V/12.0*(2.0*2.0 + 1.0*1.0)), 1e-12);

    EXPECT_NEAR(massProperties::signedVolume(primitiveMeshes::box(h)), V, 1e-12*V);
    EXPECT_NEAR(std::abs(mp.principalAxes.determinant()), 1.0, 1e-12);
    EXPECT_GT(mp.principalAxes.determinant(), 0.0);
}


TEST(massProperties, boxOffOriginAndRotated)
{
    const vec3 h(1.0, 0.5, 0.25);
    const massProperties ref = massProperties::of(primitiveMeshes::box(h));

    std::mt19937 gen(12345);
    for (int trial = 0; trial < 10; ++trial)
    {
        const mat3 R = randomQuat(gen).toRotationMatrix();
        const vec3 t = randomVec(gen, -10, 10);
        triangleSoup s = primitiveMeshes::box(h);
        primitiveMeshes::transform(s, R, t);
        const massProperties mp = massProperties::of(s);

        EXPECT_LT(relErr(mp.volume, ref.volume), 1e-12);
        EXPECT_NEAR((mp.centroid - t).norm(), 0.0, 1e-12*t.norm());
        for (int i = 0; i < 3; ++i)
        {
            EXPECT_LT(relErr(mp.principalMoments[i], ref.principalMoments[i]), 1e-12);
            // Moments are distinct and in the order x, y, z of the box:
            // principal axis i is the rotated box axis i, up to sign
            EXPECT_NEAR(std::abs(mp.principalAxes.col(i).dot(R.col(i))), 1.0, 1e-12)
                << "axis " << i;
        }
        // Inertia tensor rotates as R I R^T
        expectMatNear(mp.inertia, R*ref.inertia*R.transpose(), 1e-12*ref.principalMoments[2]);
        EXPECT_GT(mp.principalAxes.determinant(), 0.0);
        expectMatNear(mp.principalAxes.transpose()*mp.principalAxes, mat3::Identity(), 1e-12);
    }
}


TEST(massProperties, farFromOriginStaysAccurate)
{
    // The reference point near the body keeps the sums well conditioned
    const vec3 h(1.0, 0.5, 0.25);
    const massProperties ref = massProperties::of(primitiveMeshes::box(h));
    triangleSoup s = primitiveMeshes::box(h);
    const vec3 t(1e6, -2e6, 3e6);
    primitiveMeshes::transform(s, mat3::Identity(), t);
    const massProperties mp = massProperties::of(s);
    EXPECT_LT(relErr(mp.volume, ref.volume), 1e-9);
    EXPECT_NEAR((mp.centroid - t).norm(), 0.0, 1e-8);
    for (int i = 0; i < 3; ++i)
    {
        // 1e-8: round-off of the far translation (moments about a centroid
        // far from the origin lose digits by cancellation)
        EXPECT_LT(relErr(mp.principalMoments[i], ref.principalMoments[i]), 1e-8);
    }
}


TEST(massProperties, viaTriangleMeshShape)
{
    const vec3 h(1.0, 0.5, 0.25);
    const mat3 R = bodyPose::axisAngle(vec3(1, 2, 3), 0.7).toRotationMatrix();
    const vec3 t(0.3, -4, 2);
    triangleSoup s = primitiveMeshes::box(h);
    primitiveMeshes::transform(s, R, t);
    const triangleMeshShape shape(s, "box");

    const double V = 8*h.prod();
    const vec3 I = boxInertia(2*h).diagonal();
    EXPECT_LT(relErr(shape.volume(), V), 1e-12);
    for (int i = 0; i < 3; ++i)
    {
        EXPECT_LT(relErr(shape.principalMoments()[i], I[i]), 1e-12);
    }
    EXPECT_NEAR((shape.fileMassProperties().centroid - t).norm(), 0.0, 1e-12);
    EXPECT_TRUE(shape.warnings().empty());
}


TEST(massProperties, icosphereConvergesToSphere)
{
    const double R = 0.7;
    const double V = 4.0/3.0*M_PI*R*R*R;
    const double I = 0.4*V*R*R;

    double prevErrV = 0, prevErrI = 0;
    for (int level = 1; level <= 5; ++level)
    {
        const triangleSoup s = primitiveMeshes::icosphere(R, level);
        ASSERT_EQ(s.faces.size(), size_t(20) << (2*level));
        const massProperties mp = massProperties::of(s);

        // Inscribed: always smaller than the sphere
        EXPECT_LT(mp.volume, V);
        EXPECT_NEAR(mp.centroid.norm(), 0.0, 1e-12);

        const double errV = relErr(mp.volume, V);
        double errI = 0;
        for (int i = 0; i < 3; ++i)
        {
            errI = std::max(errI, relErr(mp.principalMoments[i], I));
        }
        // Nearly isotropic (1e-3: the icosahedral faceting's anisotropy,
        // far below the volume's error)
        EXPECT_LT
        (
            (mp.principalMoments[2] - mp.principalMoments[0])/I, 1e-3
        ) << "level " << level;

        // The faceting's error is second order in the edge: a level
        // halves the edges and quarters it (3: a quarter with room for the
        // higher-order terms); at level 5 (edges about R/27) a few 1e-4
        if (level > 1)
        {
            EXPECT_GT(prevErrV/errV, 3.0) << "level " << level;
            EXPECT_GT(prevErrI/errI, 3.0) << "level " << level;
        }
        if (level == 5)
        {
            EXPECT_LT(errV, 2e-3);
            EXPECT_LT(errI, 2e-3);
        }
        prevErrV = errV;
        prevErrI = errI;
    }
}


TEST(massProperties, icosphereViaTriangleMeshShape)
{
    const double R = 2.0;
    const triangleSoup s = primitiveMeshes::icosphere(R, 4);
    const massProperties mp = massProperties::of(s);
    const triangleMeshShape shape(s, "icosphere");
    EXPECT_LT(relErr(shape.volume(), mp.volume), 1e-12);
    for (int i = 0; i < 3; ++i)
    {
        EXPECT_LT(relErr(shape.principalMoments()[i], mp.principalMoments[i]), 1e-12);
    }
    EXPECT_LT(relErr(shape.volume(), 4.0/3.0*M_PI*R*R*R), 1e-2);  // the faceting's deficit
    EXPECT_NEAR(shape.boundingRadius(), R, 1e-12);
}


namespace
{

struct torusErrors
{
    double V, Ixy, Izz;
};

torusErrors torusError(double R, double r, int nMajor, int nMinor)
{
    const massProperties mp = massProperties::of(primitiveMeshes::torus(R, r, nMajor, nMinor));
    const double V = 2*M_PI*M_PI*R*r*r;
    const double Izz = V*(R*R + 0.75*r*r);
    const double Ixx = V*(0.5*R*R + 0.625*r*r);

    // Axis z: the largest moment, about the z axis
    EXPECT_NEAR(std::abs(mp.principalAxes.col(2).z()), 1.0, 1e-9);
    EXPECT_NEAR(mp.centroid.norm(), 0.0, 1e-12);

    return
    {
        relErr(mp.volume, V),
        std::max(relErr(mp.principalMoments[0], Ixx), relErr(mp.principalMoments[1], Ixx)),
        relErr(mp.principalMoments[2], Izz)
    };
}

} // End anonymous namespace


TEST(massProperties, torusConverges)
{
    const double R = 1.0, r = 0.3;
    const torusErrors coarse = torusError(R, r, 128, 64);
    const torusErrors fine = torusError(R, r, 256, 128);

    // second order in the faceting, as the sphere's: 256 x 128 leaves
    // well under 1e-3, and doubling both counts quarters it (3: with room)
    EXPECT_LT(fine.V, 1e-3);
    EXPECT_LT(fine.Ixy, 1e-3);
    EXPECT_LT(fine.Izz, 1e-3);

    EXPECT_GT(coarse.V/fine.V, 3.0);
    EXPECT_GT(coarse.Ixy/fine.Ixy, 3.0);
    EXPECT_GT(coarse.Izz/fine.Izz, 3.0);
}


TEST(massProperties, torusViaTriangleMeshShape)
{
    const double R = 1.0, r = 0.3;
    const triangleMeshShape shape(primitiveMeshes::torus(R, r, 64, 32), "torus");
    const double V = 2*M_PI*M_PI*R*r*r;
    EXPECT_LT(relErr(shape.volume(), V), 1e-2);    // 64 x 32 facets' deficit
    EXPECT_LT(shape.volume(), V);
    // The hole: the centroid (body origin) is outside the body
    EXPECT_FALSE(shape.inside(vec3::Zero()));
    EXPECT_NEAR(shape.signedDistance(vec3::Zero()), R - r, 1e-2);
}


TEST(massProperties, extrudedLExact)
{
    const double H = 0.7;
    const massProperties mp =
        massProperties::of(primitiveMeshes::extrudedPolygon(Lpolygon, H));

    // The L as two boxes: A = [0,2]x[0,1]x[0,H], B = [0,1]x[1,3]x[0,H]
    const vec3 LA(2, 1, H), LB(1, 2, H);
    const vec3 cA(1, 0.5, H/2), cB(0.5, 2, H/2);
    const double mA = LA.prod(), mB = LB.prod();
    const double V = mA + mB;
    const vec3 c = (mA*cA + mB*cB)/V;
    const mat3 I =
        boxInertia(LA) + parallelAxis(mA, cA - c)
      + boxInertia(LB) + parallelAxis(mB, cB - c);

    EXPECT_LT(relErr(mp.volume, V), 1e-10);
    EXPECT_NEAR((mp.centroid - c).norm(), 0.0, 1e-10*c.norm());
    expectMatNear(mp.inertia, I, 1e-10*I.norm());
    // The product of inertia is not zero for an L
    EXPECT_GT(std::abs(mp.inertia(0, 1)), 0.1*I.norm());

    Eigen::SelfAdjointEigenSolver<mat3> eig(I);
    for (int i = 0; i < 3; ++i)
    {
        EXPECT_LT(relErr(mp.principalMoments[i], eig.eigenvalues()[i]), 1e-10);
        EXPECT_NEAR
        (
            std::abs(mp.principalAxes.col(i).dot(eig.eigenvectors().col(i))), 1.0, 1e-10
        );
    }

    // And through the shape
    const triangleMeshShape shape(primitiveMeshes::extrudedPolygon(Lpolygon, H), "L");
    EXPECT_LT(relErr(shape.volume(), V), 1e-10);
    for (int i = 0; i < 3; ++i)
    {
        EXPECT_LT(relErr(shape.principalMoments()[i], eig.eigenvalues()[i]), 1e-10);
    }
}


TEST(massProperties, extrudedPolygonRejectsClockwise)
{
    std::vector<Eigen::Vector2d> cw(Lpolygon.rbegin(), Lpolygon.rend());
    EXPECT_TRUE(throwsCoreError
    (
        [&]{ primitiveMeshes::extrudedPolygon(cw, 1.0); },
        {"extrudedPolygon", "counter-clockwise"}
    ));
}


TEST(massProperties, inwardSoupHasNegativeSignedVolume)
{
    triangleSoup s = primitiveMeshes::box(vec3(1, 2, 3));
    for (triFace& f : s.faces) std::swap(f[1], f[2]);
    EXPECT_NEAR(massProperties::signedVolume(s), -48.0, 1e-12);
    EXPECT_NEAR(massProperties::of(s).volume, -48.0, 1e-12);
}


TEST(massProperties, emptySoup)
{
    const massProperties mp = massProperties::of(triangleSoup());
    EXPECT_EQ(mp.volume, 0.0);
    EXPECT_EQ(mp.centroid, vec3::Zero());
}
