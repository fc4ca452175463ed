// World-frame queries of posed shapes equal the body-frame queries; world
// boxes contain the posed bodies; placement of the file's coordinates.

#include "triangleMeshShape.H"
#include "sphereShape.H"
#include "primitiveMeshes.H"
#include "testHelpers.H"

using namespace immersedDEM;
using namespace immersedDEM::test;

namespace
{

const std::vector<Eigen::Vector2d> Lpolygon =
{
    {0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 3}, {0, 3}
};

triangleSoup LSoup()
{
    return primitiveMeshes::extrudedPolygon(Lpolygon, 0.7);
}

} // End anonymous namespace


TEST(poseInvariance, queriesOfMeshAndSphere)
{
    const triangleMeshShape L(LSoup(), "L");
    const sphereShape ball(0.8);
    std::mt19937 gen(11);

    for (const shape* s : {static_cast<const shape*>(&L), static_cast<const shape*>(&ball)})
    {
        const double r = s->boundingRadius();
        int nIn = 0, nOut = 0;
        for (int trial = 0; trial < 20; ++trial)
        {
            const bodyPose pose(randomVec(gen, -50, 50), randomQuat(gen));
            for (int i = 0; i < 100; ++i)
            {
                const vec3 b = randomVec(gen, -1.2*r, 1.2*r);
                const vec3 w = pose.toWorld(b);
                const double d = s->signedDistance(b);
                EXPECT_NEAR(s->signedDistance(pose, w), d, 1e-12) << s->type();
                // Away from round-off of the surface the sides agree
                if (std::abs(d) > 1e-9)
                {
                    EXPECT_EQ(s->inside(pose, w), s->inside(b)) << s->type();
                    EXPECT_EQ(s->inside(pose, w), d < 0) << s->type();
                    (d < 0 ? nIn : nOut)++;
                }
                const surfacePoint sb = s->closest(b);
                const surfacePoint sw = s->closest(pose, w);
                EXPECT_NEAR((sw.point - pose.toWorld(sb.point)).norm(), 0.0, 1e-11);
                EXPECT_NEAR((sw.normal - pose.vectorToWorld(sb.normal)).norm(), 0.0, 1e-9);
                EXPECT_NEAR(sw.distance, sb.distance, 1e-12);
            }
        }
        EXPECT_GT(nIn, 20) << s->type();
        EXPECT_GT(nOut, 100) << s->type();
    }
}


TEST(poseInvariance, worldBoxContainsPosedBody)
{
    const triangleMeshShape L(LSoup(), "L");
    const triangleMeshShape box(primitiveMeshes::box(vec3(1, 0.5, 0.25)), "box");
    const sphereShape ball(0.8);
    std::mt19937 gen(12);

    for (int trial = 0; trial < 50; ++trial)
    {
        const bodyPose pose(randomVec(gen, -5, 5), randomQuat(gen));

        for (const triangleMeshShape* s : {&L, &box})
        {
            const axisAlignedBox wb = s->worldBox(pose);
            axisAlignedBox vb;
            for (const vec3& v : s->surface().points)
            {
                const vec3 w = pose.toWorld(v);
                EXPECT_TRUE(wb.inflated(1e-12).contains(w)) << s->name();
                vb.add(w);
            }
            EXPECT_TRUE(wb.inflated(1e-12).contains(vb.min));
            EXPECT_TRUE(wb.inflated(1e-12).contains(vb.max));
            if (s == &box)
            {
                // The box of a rotated box is exact
                EXPECT_NEAR((wb.min - vb.min).norm(), 0.0, 1e-12);
                EXPECT_NEAR((wb.max - vb.max).norm(), 0.0, 1e-12);
            }
        }

        // Sphere: exact, the centre plus or minus R
        const axisAlignedBox sb = ball.worldBox(pose);
        EXPECT_NEAR((sb.min - (pose.position() - vec3::Constant(0.8))).norm(), 0.0, 1e-14);
        EXPECT_NEAR((sb.max - (pose.position() + vec3::Constant(0.8))).norm(), 0.0, 1e-14);
        for (const vec3& v : ball.surface().points)
        {
            EXPECT_TRUE(sb.inflated(1e-12).contains(pose.toWorld(v)));
        }
    }
}


TEST(poseInvariance, poseFromFilePlacement)
{
    // A file whose body frame is far from the file's: off-origin and turned
    triangleSoup file = LSoup();
    primitiveMeshes::transform
    (
        file, bodyPose::axisAngle(vec3(0, 1, 1), 0.9).toRotationMatrix(), vec3(3, 4, -2)
    );
    const triangleMeshShape s(file, "L");
    const triangleSoup body = s.surface();
    ASSERT_EQ(body.points.size(), file.points.size());

    std::mt19937 gen(13);
    for (int trial = 0; trial < 20; ++trial)
    {
        const quat R = randomQuat(gen);
        const vec3 t = randomVec(gen, -10, 10);
        const bodyPose pose = s.poseFromFilePlacement(R, t);
        for (size_t i = 0; i < file.points.size(); ++i)
        {
            const vec3 expected = R.toRotationMatrix()*file.points[i] + t;
            EXPECT_NEAR((pose.toWorld(body.points[i]) - expected).norm(), 0.0, 1e-12)
                << "vertex " << i;
        }
        // The centroid goes where the placement takes the file's centroid
        EXPECT_NEAR
        (
            (pose.position() - (R*s.fileMassProperties().centroid + t)).norm(), 0.0, 1e-12
        );
        // A point of the foot of the L, placed, is inside; one of the notch is not
        const mat3 Rf = bodyPose::axisAngle(vec3(0, 1, 1), 0.9).toRotationMatrix();
        const vec3 xIn = Rf*vec3(1.5, 0.5, 0.35) + vec3(3, 4, -2);
        const vec3 xOut = Rf*vec3(1.5, 2.0, 0.35) + vec3(3, 4, -2);
        EXPECT_TRUE(s.inside(pose, R*xIn + t));
        EXPECT_FALSE(s.inside(pose, R*xOut + t));
        EXPECT_NEAR(s.signedDistance(pose, R*xOut + t), 0.5, 1e-12);
        EXPECT_NEAR(s.signedDistance(pose, R*xIn + t), -0.35, 1e-12);
    }

    // Identity placement: the pose is bodyInFile itself
    const bodyPose id = s.poseFromFilePlacement(quat::Identity(), vec3::Zero());
    EXPECT_NEAR((id.position() - s.bodyInFile().position()).norm(), 0.0, 1e-15);
    EXPECT_NEAR(id.orientation().angularDistance(s.bodyInFile().orientation()), 0.0, 1e-12);
}
