// Walls of the DEM: a plane and an open triangle surface carry a resting
// sphere at the same height; a prescribed (moving) plane pushes a sphere.

#include "demSolver.H"
#include "sphereShape.H"
#include "halfSpaceShape.H"
#include "wallMeshShape.H"
#include "coreError.H"
#include "primitiveMeshes.H"
#include "overlapEngine.H"
#include "sphereOverlap.H"

#include <gtest/gtest.h>

using namespace immersedDEM;

namespace
{

const double R = 0.005, rho = 1000;

demSolver makeDem(const std::string& method)
{
    contactMaterial soft{"soft", 1e6, 0.3, 0.3, 0.5};
    demSettings s;
    s.overlapMethod = method;
    s.overlap = {2*R/10, 2};
    s.gravity = vec3(0, 0, -9.81);
    return demSolver({soft}, s);
}

// Settle a sphere dropped from z0 on whatever wall the DEM holds
double restingHeight(demSolver& dem, double z0)
{
    rigidBody b("ball", std::make_shared<sphereShape>(R), rho);
    b.pose = bodyPose(vec3(0.001, 0.002, z0), quat::Identity());
    const int i = dem.addBody(b);
    dem.advance(0.3);
    EXPECT_LT(dem.bodies()[i].velocity.norm(), 1e-3);   // at rest after 0.3 s (falling 1 mm reaches 0.14 m/s)
    return dem.bodies()[i].pose.position().z();
}

// A ball at pb 0.1 mm into the floor z = -0.05 of wall w: w is flat
// there, and the virtual mesh gives the exact cap (to round-off, 1e-12
// of it) with the floor's normal
void expectFloorCap(const wallMeshShape& w, const bodyPose& pb)
{
    vec3 x, n;
    ASSERT_TRUE(w.flatNear(pb.position(), R, x, n));
    EXPECT_NEAR(n.z(), 1, 1e-12);
    const sphereShape ball(R);
    const auto engine = overlapEngine::New("virtualMesh");
    const contactGeometry g = engine->evaluate(w, bodyPose(), ball, pb, {2*R/20, 4});
    const contactGeometry exact = sphereOverlap::cap(vec3(0, 0, -0.05), vec3::UnitZ(), pb.position(), R);
    ASSERT_EQ(g.regions.size(), 1u);
    EXPECT_NEAR(g.regions[0].volume, exact.regions[0].volume, 1e-12*exact.regions[0].volume);
    EXPECT_NEAR(g.regions[0].normal.z(), 1, 1e-12);
}

} // End anonymous namespace


TEST(demWalls, planeAndOpenMeshCarryTheSameSphere)
{
    // Static overlap: m g = Y* V / l_c with V = pi R delta^2 (cap), l_c = R
    demSolver plane = makeDem("virtualMesh");
    rigidBody floor("floor", std::make_shared<halfSpaceShape>(), 1);
    floor.pose = halfSpaceShape::poseOf(vec3::Zero(), vec3::UnitZ());
    floor.motion = motionType::fixed;
    plane.addBody(floor, true);
    const double zPlane = restingHeight(plane, R + 0.001);

    // The same floor as an open surface of two triangles, normals up
    triangleSoup square;
    square.points = {{-0.05, -0.05, 0}, {0.05, -0.05, 0}, {0.05, 0.05, 0}, {-0.05, 0.05, 0}};
    square.faces = {{0, 1, 2}, {0, 2, 3}};
    demSolver mesh = makeDem("virtualMesh");
    rigidBody meshFloor("meshFloor", std::make_shared<wallMeshShape>(square, "square", 2*R), 1);
    meshFloor.motion = motionType::fixed;
    mesh.addBody(meshFloor, true);
    const double zMesh = restingHeight(mesh, R + 0.001);

    const double m = rho*4.0/3.0*M_PI*R*R*R;
    const double Ystar = 1/(2*(1 - 0.09)/1e6);     // both sides "soft"
    const double delta = std::sqrt(m*9.81*R/(Ystar*M_PI*R));
    // 5%: the volume law's static overlap is this estimate to leading
    // order in delta/R (the lens's volume pi R delta^2 its first term)
    EXPECT_NEAR((R - zPlane)/delta, 1, 0.05) << "plane overlap " << R - zPlane;
    EXPECT_NEAR((R - zMesh)/delta, 1, 0.05) << "mesh overlap " << R - zMesh;
}


TEST(demWalls, prescribedPlaneLiftsASphere)
{
    demSolver dem = makeDem("sphere");
    rigidBody lift("lift", std::make_shared<halfSpaceShape>(), 1);
    lift.pose = halfSpaceShape::poseOf(vec3::Zero(), vec3::UnitZ());
    lift.motion = motionType::prescribed;
    lift.velocity = vec3(0, 0, 0.05);
    dem.addBody(lift, true);
    rigidBody b("ball", std::make_shared<sphereShape>(R), rho);
    b.pose = bodyPose(vec3(0, 0, R), quat::Identity());
    const int i = dem.addBody(b);
    dem.advance(0.4);
    // The floor rose 20 mm; the sphere rides on it, moving with it
    EXPECT_NEAR(dem.bodies()[0].pose.position().z(), 0.02, 1e-12);
    EXPECT_NEAR(dem.bodies()[i].pose.position().z(), 0.02 + R, 0.05*R);
    EXPECT_NEAR(dem.bodies()[i].velocity.z(), 0.05, 0.005);
}


TEST(demWalls, wallsMustNotMoveByForces)
{
    demSolver dem = makeDem("sphere");
    rigidBody w("w", std::make_shared<halfSpaceShape>(), 1);
    EXPECT_THROW(dem.addBody(w, true), coreError);     // free wall
}


// A sphere against a flat part of a mesh wall (the floor of a closed box
// surface, normals inward) gets the exact cap, the same as against a plane;
// near the box's edge (two faces not coplanar) and on an open surface's rim
// the wall is not flat: the octree measures it
TEST(demWalls, flatPartOfAMeshWallGivesTheExactCap)
{
    triangleSoup box = primitiveMeshes::box(vec3(0.05, 0.05, 0.05));
    for (triFace& f : box.faces) std::swap(f[1], f[2]);     // normals inward
    const wallMeshShape wall(box, "box", 0.02);
    const sphereShape ball(R);
    // The box spans -0.05..0.05; a ball sinking 0.1 mm into its floor
    const bodyPose pw;
    const bodyPose pb(vec3(0.003, -0.002, -0.05 + R - 1e-4), quat::Identity());
    expectFloorCap(wall, pb);
    const auto engine = overlapEngine::New("virtualMesh");
    vec3 x, n;
    // Swapped: the normal turns
    const contactGeometry s = engine->evaluate(ball, pb, wall, pw, {2*R/20, 4});
    EXPECT_NEAR(s.regions[0].normal.z(), -1, 1e-12);

    // Near the floor's edge the side wall is within reach: not flat
    EXPECT_FALSE(wall.flatNear(vec3(0.05 - 0.5*R, 0, -0.05 + R - 1e-4), R, x, n));
    // An open two-triangle plate: its rim is within reach of any ball on it
    triangleSoup plate;
    plate.points = {vec3(-0.1, -0.1, 0), vec3(0.1, -0.1, 0), vec3(0.1, 0.1, 0), vec3(-0.1, 0.1, 0)};
    plate.faces = {{0, 1, 2}, {0, 2, 3}};
    const wallMeshShape open(plate, "plate", 0.02);
    EXPECT_FALSE(open.flatNear(vec3(0, 0, R - 1e-4), R, x, n));
}


// A channel's walls end at its outlet: there the wall's rim lies on the
// domain's boundary, which turns to the fluid's side (the outlet is at a
// right angle to the walls). Told so (the reader's 'continued' edges),
// the walls are extended across it: a ball crossing the outlet on the floor
// gets the exact cap, and at the floor's corner with a side wall the
// planes of both. Not told, the rim is the rim (the octree measures it)
TEST(demWalls, wallContinuedAcrossAnOutletGivesTheExactCap)
{
    // A box tank, normals inward, without its x = +0.05 side (the outlet)
    const triangleSoup box = primitiveMeshes::box(vec3(0.05, 0.05, 0.05));
    triangleSoup channel;
    channel.points = box.points;
    for (triFace f : box.faces)
    {
        bool outlet = true;
        for (const int v : f) outlet = outlet && box.points[v].x() > 0.05 - 1e-12;
        std::swap(f[1], f[2]);
        if (!outlet) channel.faces.push_back(f);
    }
    ASSERT_EQ(channel.faces.size(), 10u);
    std::vector<wallMeshShape::edge> rim;
    for (const triFace& f : channel.faces)
    {
        for (int k = 0; k < 3; ++k)
        {
            const int a = f[k], b = f[(k + 1)%3];
            if (box.points[a].x() > 0.05 - 1e-12 && box.points[b].x() > 0.05 - 1e-12)
            {
                rim.push_back({a, b});
            }
        }
    }
    ASSERT_EQ(rim.size(), 4u);      // the outlet's four edges
    const wallMeshShape open(channel, "channel", 0.02);
    const wallMeshShape continued(channel, "channel", 0.02, rim);
    EXPECT_EQ(open.openFaces() != nullptr, true);
    EXPECT_EQ(continued.openFaces(), nullptr);

    // A ball on the floor, its centre 0.3 R inside the outlet, 0.1 mm deep
    const bodyPose pb(vec3(0.05 - 0.3*R, 0.002, -0.05 + R - 1e-4), quat::Identity());
    vec3 x, n;
    EXPECT_FALSE(open.flatNear(pb.position(), R, x, n));
    expectFloorCap(continued, pb);

    // In the floor's corner with the side wall y = -0.05, at the outlet:
    // two planes, the tank's convex inside
    std::vector<wallMeshShape::plane> planes;
    const vec3 corner(0.05 - 0.3*R, -0.05 + 0.8*R, -0.05 + 0.8*R);
    EXPECT_FALSE(open.convexFluidNear(corner, R, planes));
    ASSERT_TRUE(continued.convexFluidNear(corner, R, planes));
    EXPECT_EQ(planes.size(), 2u);

    // Away from the outlet both are the same closed tank
    const vec3 far(-0.02, 0.003, -0.05 + R - 1e-4);
    EXPECT_TRUE(open.flatNear(far, R, x, n));
    EXPECT_TRUE(continued.flatNear(far, R, x, n));

    // An edge that is not on the rim cannot be continued
    EXPECT_THROW
    (
        wallMeshShape(channel, "channel", 0.02, {{channel.faces[0][0], channel.faces[0][1]}}),
        coreError
    );
}
