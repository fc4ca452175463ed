// bodyPose: transforms, axis-angle, composition, world boxes; and the
// axisAlignedBox it uses.

#include "bodyPose.H"
#include "testHelpers.H"

using namespace immersedDEM;
using namespace immersedDEM::test;

TEST(bodyPose, defaultIsIdentity)
{
    const bodyPose p;
    const vec3 x(1, -2, 3);
    EXPECT_EQ(p.toWorld(x), x);
    EXPECT_EQ(p.toBody(x), x);
    EXPECT_EQ(p.rotation(), mat3::Identity());
    EXPECT_EQ(p.position(), vec3::Zero());
}


TEST(bodyPose, roundTrip)
{
    std::mt19937 gen(21);
    for (int i = 0; i < 200; ++i)
    {
        const bodyPose p(randomVec(gen, -100, 100), randomQuat(gen));
        const vec3 x = randomVec(gen, -10, 10);
        EXPECT_NEAR((p.toBody(p.toWorld(x)) - x).norm(), 0.0, 1e-12);
        EXPECT_NEAR((p.toWorld(p.toBody(x)) - x).norm(), 0.0, 1e-12);
        EXPECT_NEAR((p.vectorToBody(p.vectorToWorld(x)) - x).norm(), 0.0, 1e-13);
        // Rigid: distances kept; vectors are not translated
        const vec3 y = randomVec(gen, -10, 10);
        EXPECT_NEAR((p.toWorld(x) - p.toWorld(y)).norm(), (x - y).norm(), 1e-12);
        EXPECT_NEAR((p.vectorToWorld(x) - (p.toWorld(x) - p.position())).norm(), 0.0, 1e-12);
        EXPECT_NEAR(p.rotation().determinant(), 1.0, 1e-14);
        EXPECT_NEAR((p.rotation() - p.orientation().toRotationMatrix()).norm(), 0.0, 1e-15);
    }
}


TEST(bodyPose, normalisesQuaternion)
{
    const quat q(2, 0, 0, 2);    // 90 degrees about z, not unit
    const bodyPose p(vec3(1, 0, 0), q);
    EXPECT_NEAR(p.orientation().norm(), 1.0, 1e-15);
    EXPECT_NEAR((p.toWorld(vec3(1, 0, 0)) - vec3(1, 1, 0)).norm(), 0.0, 1e-15);

    bodyPose r;
    r.setOrientation(quat(0, 0, 3, 0));     // 180 degrees about y
    EXPECT_NEAR(r.orientation().norm(), 1.0, 1e-15);
    EXPECT_NEAR((r.toWorld(vec3(1, 2, 3)) - vec3(-1, 2, -3)).norm(), 0.0, 1e-15);
    r.setPosition(vec3(0, 0, 1));
    EXPECT_NEAR((r.toWorld(vec3(1, 2, 3)) - vec3(-1, 2, -2)).norm(), 0.0, 1e-15);
}


TEST(bodyPose, axisAngle)
{
    const quat qz = bodyPose::axisAngle(vec3(0, 0, 5), M_PI/2);
    EXPECT_NEAR((qz*vec3(1, 0, 0) - vec3(0, 1, 0)).norm(), 0.0, 1e-15);
    EXPECT_NEAR((qz*vec3(0, 0, 1) - vec3(0, 0, 1)).norm(), 0.0, 1e-15);

    const quat qx = bodyPose::axisAngle(vec3(-2, 0, 0), M_PI/2);   // about -x
    EXPECT_NEAR((qx*vec3(0, 1, 0) - vec3(0, 0, -1)).norm(), 0.0, 1e-15);

    // Zero axis or angle: identity
    EXPECT_NEAR(bodyPose::axisAngle(vec3::Zero(), 1.0).angularDistance(quat::Identity()), 0, 1e-15);
    EXPECT_NEAR(bodyPose::axisAngle(vec3(1, 2, 3), 0).angularDistance(quat::Identity()), 0, 1e-15);

    // Angle recovered, axis kept, for a general rotation
    const vec3 axis = vec3(1, -2, 0.5).normalized();
    const quat q = bodyPose::axisAngle(3*axis, 2.0);
    const Eigen::AngleAxisd aa(q);
    EXPECT_NEAR(aa.angle(), 2.0, 1e-14);
    EXPECT_NEAR((aa.axis() - axis).norm(), 0.0, 1e-14);
    EXPECT_NEAR((q*axis - axis).norm(), 0.0, 1e-14);
    EXPECT_NEAR(q.norm(), 1.0, 1e-15);
}


TEST(bodyPose, composition)
{
    std::mt19937 gen(22);
    for (int i = 0; i < 100; ++i)
    {
        const bodyPose a(randomVec(gen, -5, 5), randomQuat(gen));
        const bodyPose b(randomVec(gen, -5, 5), randomQuat(gen));
        const bodyPose c(randomVec(gen, -5, 5), randomQuat(gen));
        const vec3 x = randomVec(gen, -3, 3);
        EXPECT_NEAR(((a*b).toWorld(x) - a.toWorld(b.toWorld(x))).norm(), 0.0, 1e-12);
        EXPECT_NEAR(((a*b).toBody(x) - b.toBody(a.toBody(x))).norm(), 0.0, 1e-12);
        // Associative
        EXPECT_NEAR((((a*b)*c).toWorld(x) - (a*(b*c)).toWorld(x)).norm(), 0.0, 1e-12);
        // Identity is neutral
        EXPECT_NEAR(((a*bodyPose()).toWorld(x) - a.toWorld(x)).norm(), 0.0, 1e-13);
        EXPECT_NEAR(((bodyPose()*a).toWorld(x) - a.toWorld(x)).norm(), 0.0, 1e-13);
        // Inverse
        const bodyPose inv(-(a.orientation().conjugate()*a.position()), a.orientation().conjugate());
        EXPECT_NEAR(((inv*a).toWorld(x) - x).norm(), 0.0, 1e-12);
    }
    // Not commutative: a rotation then a translation, and the other way
    const bodyPose rot(vec3::Zero(), bodyPose::axisAngle(vec3::UnitZ(), M_PI/2));
    const bodyPose shift(vec3(1, 0, 0), quat::Identity());
    EXPECT_NEAR(((rot*shift).toWorld(vec3::Zero()) - vec3(0, 1, 0)).norm(), 0.0, 1e-15);
    EXPECT_NEAR(((shift*rot).toWorld(vec3::Zero()) - vec3(1, 0, 0)).norm(), 0.0, 1e-15);
}


TEST(bodyPose, worldBoxOfBox)
{
    std::mt19937 gen(23);
    const axisAlignedBox b(vec3(-1, 0, 2), vec3(3, 0.5, 2.25));
    for (int i = 0; i < 100; ++i)
    {
        const bodyPose p(randomVec(gen, -5, 5), randomQuat(gen));
        axisAlignedBox corners;
        for (int c = 0; c < 8; ++c)
        {
            corners.add(p.toWorld(vec3
            (
                c & 1 ? b.max.x() : b.min.x(),
                c & 2 ? b.max.y() : b.min.y(),
                c & 4 ? b.max.z() : b.min.z()
            )));
        }
        const axisAlignedBox w = p.toWorld(b);
        EXPECT_NEAR((w.min - corners.min).norm(), 0.0, 1e-12);
        EXPECT_NEAR((w.max - corners.max).norm(), 0.0, 1e-12);
    }
}


TEST(axisAlignedBox, basics)
{
    axisAlignedBox e;
    EXPECT_TRUE(e.empty());
    EXPECT_FALSE(e.contains(vec3::Zero()));
    EXPECT_FALSE(e.overlaps(axisAlignedBox(vec3::Constant(-1), vec3::Constant(1))));

    e.add(vec3(1, 2, 3));
    EXPECT_FALSE(e.empty());
    EXPECT_TRUE(e.contains(vec3(1, 2, 3)));     // a single point
    e.add(vec3(-1, 4, 0));
    EXPECT_EQ(e.min, vec3(-1, 2, 0));
    EXPECT_EQ(e.max, vec3(1, 4, 3));
    EXPECT_EQ(e.centre(), vec3(0, 3, 1.5));
    EXPECT_EQ(e.span(), vec3(2, 2, 3));
    EXPECT_TRUE(e.contains(vec3(1, 4, 0)));     // closed
    EXPECT_FALSE(e.contains(vec3(1 + 1e-12, 3, 1)));

    const axisAlignedBox f = e.inflated(0.5);
    EXPECT_EQ(f.min, vec3(-1.5, 1.5, -0.5));
    EXPECT_EQ(f.max, vec3(1.5, 4.5, 3.5));

    const axisAlignedBox g(vec3(1, 4, 3), vec3(2, 5, 4));   // touches at a corner
    EXPECT_TRUE(e.overlaps(g));
    EXPECT_TRUE(g.overlaps(e));
    EXPECT_FALSE(e.intersection(g).empty());
    const axisAlignedBox h(vec3(1.5, 3, 1), vec3(2, 5, 4));
    EXPECT_FALSE(e.overlaps(h));
    EXPECT_TRUE(e.intersection(h).empty());
    const axisAlignedBox i = e.intersection(axisAlignedBox(vec3(0, 0, 0), vec3(5, 3, 1)));
    EXPECT_EQ(i.min, vec3(0, 2, 0));
    EXPECT_EQ(i.max, vec3(1, 3, 1));

    axisAlignedBox u;
    u.add(e);
    u.add(g);
    EXPECT_EQ(u.min, vec3(-1, 2, 0));
    EXPECT_EQ(u.max, vec3(2, 5, 4));
}
