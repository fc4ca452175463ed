// Overlaps present at the start: found with their volumes and equivalent
// depths, none for exactly touching bodies, and removed by separation
// without changing velocities; a body squeezed between two walls is
// reported, not looped on for ever.

#include "initialOverlaps.H"
#include "sphereShape.H"
#include "halfSpaceShape.H"
#include "triangleMeshShape.H"
#include "primitiveMeshes.H"

#include <gtest/gtest.h>

using namespace immersedDEM;

namespace
{

const double R = 0.005, rho = 2500;

demSolver makeDem()
{
    contactMaterial glass{"glass", 6e10, 0.23, 0.9, 0.3};
    demSettings s;
    s.gravity = vec3(0, 0, -9.81);
    return demSolver({glass}, s);
}

rigidBody sphereAt(const std::string& name, const vec3& x, double radius = R)
{
    rigidBody b(name, std::make_shared<sphereShape>(radius), rho);
    b.pose = bodyPose(x, quat::Identity());
    return b;
}

rigidBody cubeAt(const std::string& name, const vec3& x, double half)
{
    auto cube = std::make_shared<triangleMeshShape>
    (
        primitiveMeshes::box(vec3::Constant(half)), name
    );
    rigidBody b(name, cube, rho);
    b.pose = cube->poseFromFilePlacement(quat::Identity(), x);
    return b;
}

rigidBody planeWall(const std::string& name, const vec3& point, const vec3& normal)
{
    rigidBody w(name, std::make_shared<halfSpaceShape>(), 1);
    w.pose = halfSpaceShape::poseOf(point, normal);
    w.motion = motionType::fixed;
    return w;
}

// Lens of two equal spheres of radius r whose centres are s apart
double lensVolume(double r, double s)
{
    const double h = r - 0.5*s;
    return 2*M_PI*h*h*(3*r - h)/3;
}

} // End anonymous namespace


TEST(initialOverlaps, foundWithVolumesAndDepthsThenSeparated)
{
    demSolver dem = makeDem();
    dem.addBody(planeWall("floor", vec3::Zero(), vec3::UnitZ()), true);
    // Half into each other (the 8.4 m/s case), well above the floor
    const int a = dem.addBody(sphereAt("a", vec3(0, 0, 0.05)));
    const int b = dem.addBody(sphereAt("b", vec3(R, 0, 0.05)));
    // 1 mm into the floor, moving sideways
    rigidBody c = sphereAt("c", vec3(0.05, 0, R - 0.001));
    c.velocity = vec3(0.2, 0, 0);
    const int ic = dem.addBody(c);

    const std::vector<initialOverlap> found = initialOverlaps::find(dem);
    ASSERT_EQ(found.size(), 2u);
    for (const initialOverlap& o : found)
    {
        if (o.a == a || o.b == a)
        {
            // 1%: the overlap engine's volume accuracy
            EXPECT_NEAR(o.volume, lensVolume(R, R), 0.01*lensVolume(R, R));
            EXPECT_NEAR(o.diameter, 2*R, 1e-12);
        }
        else
        {
            EXPECT_EQ(o.b, ic);
            const double h = 0.001;
            const double cap = M_PI*h*h*(3*R - h)/3;
            EXPECT_NEAR(o.volume, cap, 0.01*cap);     // as the lens's
            // volume over the cap's base (pi a^2, a^2 = 2 R h - h^2)
            EXPECT_NEAR(o.depth, cap/(M_PI*(2*R*h - h*h)), 0.02*h);
        }
    }
    const std::string text = initialOverlaps::text(dem, found);
    EXPECT_NE(text.find("a and b"), std::string::npos) << text;
    EXPECT_NE(text.find("floor and c"), std::string::npos) << text;

    const vec3 centreBefore = 0.5*(dem.bodies()[a].pose.position() + dem.bodies()[b].pose.position());
    const overlapSeparation s = initialOverlaps::separate(dem);
    EXPECT_TRUE(s.remaining.empty());
    EXPECT_EQ(s.bodiesMoved, 3);
    EXPECT_LT(s.iterations, 100);   // converges, far below a loop
    EXPECT_TRUE(dem.histories().empty());
    for (const initialOverlap& o : initialOverlaps::find(dem))
    {
        EXPECT_LT(o.depth, initialOverlaps::depthTolerance*2*R);
    }

    // Equal masses: moved apart symmetrically along the line of centres
    const vec3 xa = dem.bodies()[a].pose.position(), xb = dem.bodies()[b].pose.position();
    EXPECT_NEAR((0.5*(xa + xb) - centreBefore).norm(), 0, 1e-9);
    EXPECT_NEAR((xb - xa).norm(), 2*R, 1e-3*R);
    EXPECT_NEAR(xa.y(), 0, 1e-12);
    // The floor does not move; c is lifted to rest on it, velocity kept
    EXPECT_NEAR(dem.bodies()[ic].pose.position().z(), R, 1e-3*R);
    EXPECT_NEAR(dem.bodies()[ic].pose.position().x(), 0.05, 1e-12);
    EXPECT_EQ(dem.bodies()[ic].velocity, vec3(0.2, 0, 0));

    // Nothing is released: the first steps do not fling the spheres
    dem.advance(1e-3);
    EXPECT_LT(dem.bodies()[a].velocity.norm(), 0.05);
    EXPECT_LT(dem.bodies()[b].velocity.norm(), 0.05);
}


TEST(initialOverlaps, touchingBodiesHaveNone)
{
    // Spheres exactly touching, and two cubes face to face with no gap
    demSolver dem = makeDem();
    dem.addBody(sphereAt("a", vec3(0, 0, 0.05)));
    dem.addBody(sphereAt("b", vec3(2*R, 0, 0.05)));
    dem.addBody(cubeAt("c1", vec3(0.1, 0, 0.05), R));
    dem.addBody(cubeAt("c2", vec3(0.1 + 2*R, 0, 0.05), R));
    const std::vector<initialOverlap> found = initialOverlaps::find(dem);
    EXPECT_TRUE(found.empty()) << initialOverlaps::text(dem, found);
}


TEST(initialOverlaps, facesOverlapByTheirDepth)
{
    // Two cubes 1 mm into each other face to face: the equivalent depth
    // (volume over area) is the depth
    demSolver dem = makeDem();
    const int c1 = dem.addBody(cubeAt("c1", vec3(0, 0, 0.05), R));
    const int c2 = dem.addBody(cubeAt("c2", vec3(2*R - 0.001, 0, 0.05), R));
    const std::vector<initialOverlap> found = initialOverlaps::find(dem);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_NEAR(found[0].volume, 0.001*4*R*R, 0.005*0.001*4*R*R);
    EXPECT_NEAR(found[0].depth, 0.001, 2e-5);

    const overlapSeparation s = initialOverlaps::separate(dem);
    EXPECT_TRUE(s.remaining.empty());
    const double gap =
        dem.bodies()[c2].pose.position().x() - dem.bodies()[c1].pose.position().x() - 2*R;
    // apart to the separation's depth tolerance (1e-9 of the diameter;
    // 1e-6 leaves room for the engine's round-off), and not pushed far
    // (0.1 mm: a tenth of the 1 mm overlap it removed)
    EXPECT_GE(gap, -1e-6*2*R);
    EXPECT_LT(gap, 1e-4);
}


TEST(initialOverlaps, squeezedBetweenWallsIsReportedNotLoopedOn)
{
    // A sphere of diameter 10 mm between two fixed planes 8 mm apart
    demSolver dem = makeDem();
    dem.addBody(planeWall("left", vec3(-0.004, 0, 0), vec3::UnitX()), true);
    dem.addBody(planeWall("right", vec3(0.004, 0, 0), -vec3::UnitX()), true);
    dem.addBody(sphereAt("ball", vec3(0, 0, 0.05)));
    const overlapSeparation s = initialOverlaps::separate(dem, 50);
    EXPECT_EQ(s.iterations, 50);
    EXPECT_FALSE(s.remaining.empty());
    for (const vec3& x : {dem.bodies()[2].pose.position()})
    {
        EXPECT_TRUE(std::isfinite(x.norm()));
        EXPECT_LT(std::abs(x.x()), 0.004);     // still between the walls
    }
}
