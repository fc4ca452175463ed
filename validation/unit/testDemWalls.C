// Walls of the DEM: a plane and an open triangle surface carry a resting
// sphere at the same height; a prescribed (moving) plane pushes a sphere.

#include "demSolver.H"
#include "sphereShape.H"
#include "halfSpaceShape.H"
#include "wallMeshShape.H"
#include "coreError.H"

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
    EXPECT_LT(dem.bodies()[i].velocity.norm(), 1e-3);
    return dem.bodies()[i].pose.position().z();
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
