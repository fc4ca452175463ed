// triangleMeshShape's body frame: principal axes at the centroid, and
// bodyInFile() mapping body coordinates back to the input coordinates.

#include "triangleMeshShape.H"
#include "primitiveMeshes.H"
#include "massProperties.H"
#include "surfaceFileIO.H"
#include "testHelpers.H"

#include <fstream>

using namespace immersedDEM;
using namespace immersedDEM::test;

namespace
{

const std::vector<Eigen::Vector2d> Lpolygon =
{
    {0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 3}, {0, 3}
};

// Input soups placed away from the origin and rotated
triangleSoup placedBox(const vec3& h)
{
    triangleSoup s = primitiveMeshes::box(h);
    primitiveMeshes::transform
    (
        s, bodyPose::axisAngle(vec3(0.3, -1, 0.5), 1.1).toRotationMatrix(), vec3(5, -3, 2)
    );
    return s;
}

triangleSoup placedL()
{
    triangleSoup s = primitiveMeshes::extrudedPolygon(Lpolygon, 0.7);
    primitiveMeshes::transform
    (
        s, bodyPose::axisAngle(vec3(1, 1, 0), 0.4).toRotationMatrix(), vec3(-1, 2, 0.5)
    );
    return s;
}

void checkFrame(const triangleSoup& input, const triangleMeshShape& shape)
{
    const triangleSoup body = shape.surface();
    ASSERT_EQ(body.points.size(), input.points.size());
    ASSERT_EQ(body.faces.size(), input.faces.size());
    EXPECT_EQ(shape.nTriangles(), input.faces.size());

    // Every body vertex maps back onto its input vertex
    double scale = 0;
    for (const vec3& p : input.points) scale = std::max(scale, p.norm());
    for (size_t i = 0; i < input.points.size(); ++i)
    {
        const vec3 x = shape.bodyInFile().toWorld(body.points[i]);
        EXPECT_NEAR((x - input.points[i]).norm(), 0.0, 1e-12*scale) << "vertex " << i;
        const vec3 b = shape.bodyInFile().toBody(input.points[i]);
        EXPECT_NEAR((b - body.points[i]).norm(), 0.0, 1e-12*scale) << "vertex " << i;
    }

    // Body frame: centroid at the origin, inertia diagonal and ascending
    const massProperties mp = massProperties::of(body);
    const double I = shape.principalMoments()[2];
    EXPECT_LT(relErr(mp.volume, shape.volume()), 1e-12);
    EXPECT_NEAR(mp.centroid.norm(), 0.0, 1e-12*scale);
    for (int i = 0; i < 3; ++i)
    {
        EXPECT_NEAR(mp.inertia(i, i), shape.principalMoments()[i], 1e-12*I);
        for (int j = 0; j < 3; ++j)
        {
            if (i != j) EXPECT_NEAR(mp.inertia(i, j), 0.0, 1e-12*I);
        }
    }
    EXPECT_LE(shape.principalMoments()[0], shape.principalMoments()[1]);
    EXPECT_LE(shape.principalMoments()[1], shape.principalMoments()[2]);

    // bodyInFile's position is the file centroid
    EXPECT_NEAR
    (
        (shape.bodyInFile().position() - shape.fileMassProperties().centroid).norm(),
        0.0, 1e-14*scale
    );

    // Bounding radius: the farthest vertex from the centroid
    double rMax = 0;
    for (const vec3& p : body.points) rMax = std::max(rMax, p.norm());
    EXPECT_DOUBLE_EQ(shape.boundingRadius(), rMax);
    for (const vec3& p : body.points)
    {
        EXPECT_TRUE(shape.localBox().contains(p));
    }
}

} // End anonymous namespace


TEST(triangleMeshShapeFrame, box)
{
    const vec3 h(0.25, 1.0, 0.5);
    const triangleSoup input = placedBox(h);
    const triangleMeshShape shape(input, "box");
    checkFrame(input, shape);

    EXPECT_EQ(shape.type(), "triangleMesh");
    EXPECT_EQ(shape.name(), "box");

    // Centred local box; body x along the longest side (smallest moment)
    EXPECT_NEAR(shape.localBox().centre().norm(), 0.0, 1e-12);
    EXPECT_NEAR(shape.localBox().span().x(), 2.0, 1e-12);
    EXPECT_NEAR(shape.localBox().span().y(), 1.0, 1e-12);
    EXPECT_NEAR(shape.localBox().span().z(), 0.5, 1e-12);
    EXPECT_NEAR(shape.boundingRadius(), h.norm(), 1e-12);

    // The body x axis is the file box's long (y) axis, up to sign
    const mat3 Rbox = bodyPose::axisAngle(vec3(0.3, -1, 0.5), 1.1).toRotationMatrix();
    const mat3 Rbody = shape.bodyInFile().rotation();
    EXPECT_NEAR(std::abs(Rbody.col(0).dot(Rbox.col(1))), 1.0, 1e-12);
    EXPECT_NEAR(std::abs(Rbody.col(1).dot(Rbox.col(2))), 1.0, 1e-12);
    EXPECT_NEAR(std::abs(Rbody.col(2).dot(Rbox.col(0))), 1.0, 1e-12);
    EXPECT_NEAR(Rbody.determinant(), 1.0, 1e-12);
}


TEST(triangleMeshShapeFrame, extrudedL)
{
    const triangleSoup input = placedL();
    const triangleMeshShape shape(input, "L");
    checkFrame(input, shape);

    // A file point inside the L (in the foot, at (0.5, 0.5, 0.35) before
    // placement) is inside in the body frame
    const vec3 xIn =
        bodyPose::axisAngle(vec3(1, 1, 0), 0.4).toRotationMatrix()*vec3(0.5, 0.5, 0.35)
      + vec3(-1, 2, 0.5);
    EXPECT_TRUE(shape.inside(shape.bodyInFile().toBody(xIn)));
    // The notch of the L, (1.5, 2, 0.35) before placement, is outside
    const vec3 xOut =
        bodyPose::axisAngle(vec3(1, 1, 0), 0.4).toRotationMatrix()*vec3(1.5, 2, 0.35)
      + vec3(-1, 2, 0.5);
    EXPECT_FALSE(shape.inside(shape.bodyInFile().toBody(xOut)));
    EXPECT_NEAR(shape.signedDistance(shape.bodyInFile().toBody(xOut)), 0.5, 1e-12);
}


TEST(triangleMeshShapeFrame, icosphereCentredAlready)
{
    // Centroid at the origin in the file: bodyInFile is a pure rotation
    const triangleSoup input = primitiveMeshes::icosphere(1.5, 3);
    const triangleMeshShape shape(input, "ball");
    checkFrame(input, shape);
    EXPECT_NEAR(shape.bodyInFile().position().norm(), 0.0, 1e-12);
    EXPECT_NEAR(shape.boundingRadius(), 1.5, 1e-12);
}


TEST(triangleMeshShapeFrame, fromFileScaled)
{
    const std::string file = testing::TempDir() + "frameScaled.obj";
    const vec3 h(1, 2, 3);
    surfaceFileIO::write(file, primitiveMeshes::box(h));
    const auto shape = triangleMeshShape::fromFile(file, 0.01);
    EXPECT_EQ(shape->name(), file);
    EXPECT_LT(relErr(shape->volume(), 8*h.prod()*1e-6), 1e-12);
    EXPECT_NEAR(shape->boundingRadius(), 0.01*h.norm(), 1e-14);
    // Moment about the longest (z) side: m/3 (hx^2 + hy^2) at scale 0.01
    EXPECT_LT
    (
        relErr(shape->principalMoments()[0], 8*h.prod()*1e-6/3.0*(1 + 4)*1e-4), 1e-12
    );

    EXPECT_TRUE(throwsCoreError
    (
        [&]{ triangleMeshShape::fromFile(file, 0); }, {file, "scale must be positive"}
    ));
    EXPECT_TRUE(throwsCoreError
    (
        [&]{ triangleMeshShape::fromFile(file, -1); }, {"scale must be positive"}
    ));
    EXPECT_TRUE(throwsCoreError
    (
        [&]{ triangleMeshShape::fromFile(file, std::nan("")); }, {"scale must be positive"}
    ));
    std::remove(file.c_str());
}
