// Lubrication below the resolved gap (lubrication.H): the formula, the
// closest approach and the gap's radius for spheres, planes and meshes,
// and the force inside the DEM (a sphere coasting towards a wall against
// the film follows the integral of the formula; a very viscous film is
// stable at a coarse step; no fluid, no force).

#include "lubrication.H"
#include "demSolver.H"
#include "sphereShape.H"
#include "halfSpaceShape.H"
#include "triangleMeshShape.H"
#include "wallMeshShape.H"
#include "primitiveMeshes.H"

#include <gtest/gtest.h>

#include <cmath>

using namespace immersedDEM;

namespace
{

bodyPose at(const vec3& x)
{
    return bodyPose(x, quat::Identity());
}

std::shared_ptr<triangleMeshShape> cube(double half)
{
    return std::make_shared<triangleMeshShape>
    (
        primitiveMeshes::box(vec3(half, half, half)), "cube"
    );
}

} // End anonymous namespace


TEST(lubrication, coefficientFollowsTheFormulaAndIsClamped)
{
    const double mu = 1e-3, R = 0.005, hAct = 1e-3, hR = 1e-5;
    const double h = 2e-4;
    EXPECT_NEAR
    (
        lubrication::coefficient(mu, R, h, hAct, hR),
        6*M_PI*mu*R*R*(1/h - 1/hAct), 1e-12
    );
    // Zero at and beyond the activation distance, continuous there
    EXPECT_EQ(lubrication::coefficient(mu, R, hAct, hAct, hR), 0);
    EXPECT_EQ(lubrication::coefficient(mu, R, 2*hAct, hAct, hR), 0);
    EXPECT_LT(lubrication::coefficient(mu, R, 0.999*hAct, hAct, hR), 1.01e-3*6*M_PI*mu*R*R/hAct);
    // Held at its roughness value below it, overlap included
    const double cR = 6*M_PI*mu*R*R*(1/hR - 1/hAct);
    EXPECT_NEAR(lubrication::coefficient(mu, R, 0.5*hR, hAct, hR), cR, 1e-12*cR);
    EXPECT_NEAR(lubrication::coefficient(mu, R, -1e-4, hAct, hR), cR, 1e-12*cR);
    // The force opposes the normal relative velocity
    const vec3 F = lubrication::force(mu, R, h, hAct, hR, vec3::UnitZ(), -0.01);
    EXPECT_GT(F.z(), 0);
    EXPECT_NEAR(F.z(), 6*M_PI*mu*R*R*0.01*(1/h - 1/hAct), 1e-15);
}


TEST(lubrication, closestApproachOfSpheresPlanesAndMeshes)
{
    const double R = 0.005, g = 3e-4, cap = 1e-3;
    auto ball = std::make_shared<sphereShape>(R);
    auto plane = std::make_shared<halfSpaceShape>();
    const bodyPose floor = halfSpaceShape::poseOf(vec3::Zero(), vec3::UnitZ());

    // Two spheres along x
    closestApproach a = lubrication::approach(*ball, at(vec3::Zero()), *ball, at(vec3(2*R + g, 0, 0)), cap);
    ASSERT_TRUE(a.found);
    EXPECT_NEAR(a.gap, g, 1e-12);
    EXPECT_NEAR((a.normal - vec3::UnitX()).norm(), 0, 1e-12);
    EXPECT_NEAR((a.pointA - vec3(R, 0, 0)).norm(), 0, 1e-12);
    EXPECT_NEAR((a.pointB - vec3(R + g, 0, 0)).norm(), 0, 1e-12);
    // Beyond the cap: not found
    EXPECT_FALSE(lubrication::approach(*ball, at(vec3::Zero()), *ball, at(vec3(2*R + 2*cap, 0, 0)), cap).found);

    // Plane (A) and sphere (B), and the other order
    a = lubrication::approach(*plane, floor, *ball, at(vec3(0.01, 0, R + g)), cap);
    ASSERT_TRUE(a.found);
    EXPECT_NEAR(a.gap, g, 1e-12);
    EXPECT_NEAR((a.normal - vec3::UnitZ()).norm(), 0, 1e-12);
    a = lubrication::approach(*ball, at(vec3(0.01, 0, R + g)), *plane, floor, cap);
    EXPECT_NEAR(a.gap, g, 1e-12);
    EXPECT_NEAR((a.normal + vec3::UnitZ()).norm(), 0, 1e-12);

    // A cube face parallel to the plane: the gap, and the face's centre
    const auto c = cube(R);
    a = lubrication::approach(*plane, floor, *c, at(vec3(0.002, -0.001, R + g)), cap);
    ASSERT_TRUE(a.found);
    EXPECT_NEAR(a.gap, g, 1e-12);
    EXPECT_NEAR((a.pointB - vec3(0.002, -0.001, g)).norm(), 0, 1e-12);
    EXPECT_NEAR((a.pointA - vec3(0.002, -0.001, 0)).norm(), 0, 1e-12);

    // Two cubes face to face along y (meshes: closest pair of triangles)
    a = lubrication::approach(*c, at(vec3::Zero()), *c, at(vec3(0.001, 2*R + g, 0)), cap);
    ASSERT_TRUE(a.found);
    EXPECT_NEAR(a.gap, g, 1e-12);
    EXPECT_NEAR((a.normal - vec3::UnitY()).norm(), 0, 1e-9);
    EXPECT_NEAR(a.pointA.y(), R, 1e-12);
    EXPECT_NEAR(a.pointB.y(), R + g, 1e-12);

    // A sphere over a cube's corner (closest point on a mesh)
    const vec3 corner(R, R, R);
    const vec3 dir = vec3(1, 1, 1).normalized();
    a = lubrication::approach(*ball, at(corner + (R + g)*dir), *c, at(vec3::Zero()), cap);
    ASSERT_TRUE(a.found);
    EXPECT_NEAR(a.gap, g, 1e-12);
    EXPECT_NEAR((a.normal + dir).norm(), 0, 1e-9);
    EXPECT_NEAR((a.pointB - corner).norm(), 0, 1e-12);

    // A tilted cube over the plane: its lowest corner
    const quat tilt(Eigen::AngleAxisd(0.3, vec3(1, 0, 0)));
    const bodyPose tilted(vec3(0, 0, 0.02), tilt);
    double zMin = 1;
    for (const vec3& p : primitiveMeshes::box(vec3(R, R, R)).points)
    {
        zMin = std::min(zMin, tilted.toWorld(p).z());
    }
    a = lubrication::approach(*plane, floor, *c, tilted, 1);
    ASSERT_TRUE(a.found);
    EXPECT_NEAR(a.gap, zMin, 1e-12);
    EXPECT_NEAR(a.pointB.z(), zMin, 1e-12);
}


TEST(lubrication, gapRadiusOfSpheresPlanesFacesAndMeshes)
{
    const double Ra = 0.004, Rb = 0.006, Rcap = Ra*Rb/(Ra + Rb);
    const vec3 n = vec3(1, 2, 3).normalized();
    const mat3 P = mat3::Identity() - n*n.transpose();
    // Two spheres: the harmonic radius, exactly
    EXPECT_NEAR(lubrication::gapRadius(P/Ra, P/Rb, n, Rcap), Rcap, 1e-15);
    // A sphere and a plane: the sphere's radius
    EXPECT_NEAR(lubrication::gapRadius(P/Rb, mat3::Zero(), n, Rb), Rb, 1e-15);
    // Two flat faces: the cap
    EXPECT_NEAR(lubrication::gapRadius(mat3::Zero(), mat3::Zero(), n, Rcap), Rcap, 1e-15);
    // A cylinder (one principal curvature) on a plane, cap above it:
    // R = 1/sqrt(k kMin)
    const vec3 t = n.cross(vec3::UnitX()).normalized();
    const double Rc = 0.002, cap = 0.01;
    EXPECT_NEAR
    (
        lubrication::gapRadius(t*t.transpose()/Rc, mat3::Zero(), n, cap),
        1/std::sqrt(1/Rc/cap), 1e-12
    );

    // The curvature a mesh sphere measures gives its radius within 5%
    const double R = 0.005;
    const triangleMeshShape ico(primitiveMeshes::icosphere(R, 4), "ico");
    const bodyPose p = at(vec3(0.001, 0, 0));
    const vec3 x = p.position() + 1.1*R*vec3(0.3, -0.5, 0.8).normalized();
    const surfacePoint sp = ico.closest(p, x);
    const double Rm = lubrication::gapRadius
    (
        lubrication::curvatureNear(ico, p, x), mat3::Zero(), sp.normal, 10*R
    );
    // 5%: the curvature read from the facets of a level-4 icosphere (edges
    // of R/10: their normals' turn estimates 1/R to a few percent)
    EXPECT_NEAR(Rm/R, 1, 0.05);
}


namespace
{

//- A free sphere coasting at v0 towards a plane from the activation
//  distance, no gravity, no contact reached: its speed at gap h is
//  v0 + (6 pi mu R^2/m) [ln(hAct/h) - (hAct - h)/hAct]
struct coasting
{
    double R = 0.005, rho = 2500, mu = 0.1, cell = 5e-4, v0 = -0.01;
    //- The floor's film factor (1 no-slip, 1/4 slip)
    double film = 1;
    demSolver dem;
    int ball = -1;

    explicit coasting
    (
        double deltaT = 0, double mu_ = 0.1, bool active = true,
        double film_ = 1
    )
    :
        mu(mu_),
        film(film_),
        dem(makeDem(deltaT, active))
    {
        rigidBody floor("floor", std::make_shared<halfSpaceShape>(), 1);
        floor.pose = halfSpaceShape::poseOf(vec3::Zero(), vec3::UnitZ());
        floor.motion = motionType::fixed;
        floor.filmFactor = film;
        dem.addBody(floor, true);
        rigidBody b("ball", std::make_shared<sphereShape>(R), rho);
        b.pose = at(vec3(0, 0, R + cell));
        b.velocity = vec3(0, 0, v0);
        b.fluidCellSize = cell;
        ball = dem.addBody(b);
        dem.setFluidViscosity(mu);
    }

    static demSolver makeDem(double deltaT, bool active)
    {
        contactMaterial soft{"soft", 1e6, 0.3, 0.3, 0.5};
        demSettings s;
        s.overlapMethod = "sphere";
        s.deltaT = deltaT;
        s.lubrication.active = active;
        s.lubrication.activation = 1;
        return demSolver({soft}, s);
    }

    double gap() const { return dem.bodies()[ball].pose.position().z() - R; }
    double speed() const { return dem.bodies()[ball].velocity.z(); }

    //- Coast until the ball stops (at most 4000 steps of 1e-4 s): the
    //  largest relative error of its speed against exactSpeed while it
    //  is above half its start (near its stop the speed is small), and
    //  the number of steps checked
    double coast(int& checked)
    {
        double worst = 0;
        checked = 0;
        for (int i = 0; i < 4000 && speed() < 0; ++i)
        {
            dem.advance(1e-4);
            if (speed() > 0.5*v0) continue;
            worst = std::max(worst, std::abs(speed()/exactSpeed(gap()) - 1));
            ++checked;
        }
        return worst;
    }

    //- The film slows the ball and its nominal added mass
    double exactSpeed(double h) const
    {
        const double m =
            rho*4.0/3.0*M_PI*R*R*R + dem.bodies()[ball].fluid.nominalAddedMass;
        return v0 + film*6*M_PI*mu*R*R/m*(std::log(cell/h) - (cell - h)/cell);
    }
};

} // End anonymous namespace


TEST(lubrication, sphereCoastingToAWallFollowsTheFilm)
{
    coasting c;
    int checked = 0;
    const double worst = c.coast(checked);
    EXPECT_GT(checked, 10);
    // 1%: the DEM's sub-steps integrate the film's 1/h against the exact
    // v(h); without the film (or with m + m_a) the speed is off by more
    EXPECT_LT(worst, 0.01) << "largest relative speed error";
    // It stops in the film (the exact stop: v(h) = 0), never touching
    EXPECT_GT(c.gap(), 0.3*c.cell);
    EXPECT_LT(c.gap(), 0.6*c.cell);
    EXPECT_GT(c.dem.bodies()[c.ball].lubricationForce.z(), -1e-12);
    EXPECT_TRUE(c.dem.contacts().empty());
}


TEST(lubrication, sphereCoastingToASlipWallFollowsAQuarterOfTheFilm)
{
    // A stress-free plane (a slip patch): by the mirror image, the sphere
    // and its image approach each other at 2 u across 2 h, with the pair's
    // radius R/2: 6 pi mu (R/2)^2 (2 u)/(2 h) = 6 pi mu R^2 u/h / 4
    coasting slip(0, 0.1, true, 0.25);
    coasting noSlip;
    int checked = 0, checkedNoSlip = 0;
    const double worst = slip.coast(checked);
    noSlip.coast(checkedNoSlip);
    EXPECT_GT(checked, 10);
    // 1%: as for the no-slip wall (the sub-steps' integration of 1/h)
    EXPECT_LT(worst, 0.01) << "largest relative speed error";
    // Each stops where its own exact speed is zero (h/cell 0.43 and
    // 0.14 here): 5% of the approach speed, as for the nominal added mass
    EXPECT_LT(std::abs(slip.exactSpeed(slip.gap())), 0.05*std::abs(slip.v0));
    EXPECT_LT(std::abs(noSlip.exactSpeed(noSlip.gap())), 0.05*std::abs(noSlip.v0));
    EXPECT_LT(slip.gap(), 0.5*noSlip.gap());
}


TEST(lubrication, wallFilmFollowsEachFacesFluidSide)
{
    // A tank (mesh wall) whose +x side slips and whose other sides stick:
    // a cube approaching the +x side feels a quarter of the film of the
    // same cube approaching the -x side (mirror poses), and none against a
    // wall the fluid passes through (film factor 0)
    const auto tankMesh = std::make_shared<wallMeshShape>
    (
        primitiveMeshes::openBox(vec3(-0.025, -0.025, 0), vec3(0.025, 0.025, 0.05), 8),
        "tank", 0.01
    );
    std::vector<double> perFace(tankMesh->surface().faces.size(), 1);
    const triangleSoup mesh = tankMesh->surface();
    int slipFaces = 0;
    for (size_t f = 0; f < mesh.faces.size(); ++f)
    {
        bool plusX = true;
        for (int k = 0; k < 3; ++k)
        {
            plusX = plusX && std::abs(mesh.points[mesh.faces[f][k]].x() - 0.025) < 1e-12;
        }
        if (plusX)
        {
            perFace[f] = 0.25;
            ++slipFaces;
        }
    }
    ASSERT_GT(slipFaces, 0);
    const auto force = [&](double side, double tankFactor, bool perFaces)
    {
        contactMaterial glass{"glass", 1e7, 0.24, 1, 0};
        demSettings s;
        s.overlap.level = 0;
        demSolver dem({glass}, s);
        rigidBody tank("tank", tankMesh, 1);
        tank.motion = motionType::fixed;
        tank.filmFactor = tankFactor;
        if (perFaces)
        {
            tank.faceFilm = std::make_shared<std::vector<double>>(perFace);
        }
        dem.addBody(tank, true);
        rigidBody b("cube", cube(0.005), 2500);
        b.pose = at(vec3(side*0.019, 0.001, 0.025));
        b.velocity = vec3(side*0.033, 0, 0);
        b.fluidCellSize = 3.125e-3;
        const int i = dem.addBody(b);
        dem.setFluidViscosity(1e-3);
        // (one short step: the film's force at the start velocity, not
        // averaged over sub-steps that it slows differently)
        dem.step(1e-8);
        return std::make_pair(dem.bodies()[i].lubricationForce, dem.work().lubricatedPairs);
    };
    // Near the slipping +x side a quarter of the film of the same pose
    // against a wall that sticks everywhere; near the -x side (no-slip
    // faces) the same film as there. (1e-6: the same pose and faces, one
    // factor apart; the reported force follows the velocity the film
    // changes within the step, 1.8e-9 relative at this step and 1.8e-6 at
    // 1e-5 s; a wrong face's factor would be off by 0.75)
    const auto plus = force(1, 1, true);
    const auto plusSticking = force(1, 1, false);
    ASSERT_LT(plusSticking.first.x(), 0) << "the film pushes the cube back";
    EXPECT_NEAR(plus.first.x()/plusSticking.first.x(), 0.25, 1e-6);
    const auto minus = force(-1, 1, true);
    const auto minusSticking = force(-1, 1, false);
    ASSERT_GT(minusSticking.first.x(), 0);
    EXPECT_NEAR(minus.first.x()/minusSticking.first.x(), 1, 1e-6);
    // One factor for the whole wall gives the same as the per-face one
    // where all faces agree
    const auto uniform = force(1, 0.25, false);
    EXPECT_NEAR(uniform.first.x()/plus.first.x(), 1, 1e-12);
    // No film against a wall the fluid passes through
    const auto none = force(1, 0, false);
    EXPECT_EQ(none.first.norm(), 0);
    EXPECT_EQ(none.second, 0);
    EXPECT_GT(plus.second, 0);
}


TEST(lubrication, filmSlowsTheBodyWithItsNominalAddedMass)
{
    // The coupling's added mass m_a (here 4 m, the forcing's, for
    // stability) is inertia in the DEM; the film below the mesh slows the
    // ball as if it carried only its nominal Ca rho V (here 0.5 m)
    coasting c;
    rigidBody& b = c.dem.bodies()[c.ball];
    b.fluid.addedMass = 4*b.mass();
    b.fluid.nominalAddedMass = 0.5*b.mass();
    int checked = 0;
    const double worst = c.coast(checked);
    EXPECT_GT(checked, 10);
    // 1%: the DEM's sub-steps integrate the film's 1/h against the exact
    // v(h); without the film (or with m + m_a) the speed is off by more
    EXPECT_LT(worst, 0.01) << "largest relative speed error";
    // It stops where the exact stop of m + 0.5 m is (v(h) = 0), not in the
    // thinner film m + m_a would reach
    EXPECT_LT(std::abs(c.exactSpeed(c.gap())), 0.05*std::abs(c.v0));
}


TEST(lubrication, stiffFilmIsStableAtACoarseStep)
{
    // mu 1e3: c dt/m ~ 1e3 unclamped; the velocity-limited damper takes
    // out at most the approach in one step: no reversal, no growth
    coasting c(1e-4, 1e3);
    double previous = c.speed();
    for (int i = 0; i < 200; ++i)
    {
        c.dem.step(1e-4);
        EXPECT_LE(c.speed(), 1e-15) << "reversed at step " << i;
        EXPECT_GE(c.speed(), previous - 1e-15) << "sped up at step " << i;
        previous = c.speed();
    }
    EXPECT_GT(c.gap(), 0);
}


TEST(lubrication, noFluidOrSwitchedOffNoForce)
{
    // No fluid (the DEM-only runner: viscosity 0)
    coasting none(0, 0.0);
    none.dem.advance(0.01);
    EXPECT_NEAR(none.speed(), none.v0, 1e-15);
    EXPECT_EQ(none.dem.bodies()[none.ball].lubricationForce.norm(), 0);

    // Switched off by the user, with a fluid
    coasting off(0, 0.1, false);
    off.dem.advance(0.01);
    EXPECT_NEAR(off.speed(), off.v0, 1e-15);
    EXPECT_EQ(off.dem.work().lubricatedPairs, 0);

    // On: it acts
    coasting on;
    on.dem.advance(0.01);
    EXPECT_GT(on.speed(), on.v0 + 1e-4);
    EXPECT_GT(on.dem.work().lubricatedPairs, 0);
}


TEST(lubrication, twoBodiesStartTheirFilmAtThePairActivation)
{
    // A ball 2 cells from a wall, and a ball 2 cells from a second ball,
    // each approaching: the wall's film starts at activation (1.7 cells,
    // the default) and stays off; the pair's at pairActivation (2.5, the
    // default: both surfaces immersed) and acts. With pairActivation 1.7
    // the pair stays off too
    const double R = 0.005, cell = 5e-4, v0 = -0.01;
    for (const double pairActivation : {2.5, 1.7})
    {
        contactMaterial soft{"soft", 1e6, 0.3, 0.3, 0.5};
        demSettings s;
        s.overlapMethod = "sphere";
        EXPECT_EQ(s.lubrication.activation, 1.7);
        EXPECT_EQ(s.lubrication.pairActivation, 2.5);
        s.lubrication.pairActivation = pairActivation;
        demSolver dem({soft}, s);
        rigidBody floor("floor", std::make_shared<halfSpaceShape>(), 1);
        floor.pose = halfSpaceShape::poseOf(vec3::Zero(), vec3::UnitZ());
        floor.motion = motionType::fixed;
        dem.addBody(floor, true);
        // Far apart sideways (10 R): the balls meet the wall or each other
        // only as placed
        rigidBody onWall("onWall", std::make_shared<sphereShape>(R), 2500);
        onWall.pose = at(vec3(0, 0, R + 2*cell));
        onWall.velocity = vec3(0, 0, v0);
        onWall.fluidCellSize = cell;
        const int w = dem.addBody(onWall);
        rigidBody lower("lower", std::make_shared<sphereShape>(R), 2500);
        lower.pose = at(vec3(10*R, 0, 10*R));
        lower.motion = motionType::fixed;
        lower.fluidCellSize = cell;
        dem.addBody(lower);
        rigidBody upper("upper", std::make_shared<sphereShape>(R), 2500);
        upper.pose = at(vec3(10*R, 0, 12*R + 2*cell));
        upper.velocity = vec3(0, 0, v0);
        upper.fluidCellSize = cell;
        const int u = dem.addBody(upper);
        dem.setFluidViscosity(0.1);
        dem.advance(1e-5);   // moves 1e-7 m: the gaps stay near 2 cells
        EXPECT_EQ(dem.bodies()[w].lubricationForce.norm(), 0) << pairActivation;
        if (pairActivation > 2)
        {
            EXPECT_GT(dem.bodies()[u].lubricationForce.z(), 0);
        }
        else
        {
            EXPECT_EQ(dem.bodies()[u].lubricationForce.norm(), 0);
        }
    }
}


TEST(lubrication, tangentialMotionFeelsNoNormalFilm)
{
    coasting c;
    c.dem.bodies()[c.ball].velocity = vec3(0.01, 0, 0);
    c.dem.bodies()[c.ball].pose = at(vec3(0, 0, c.R + 0.3*c.cell));
    c.dem.bodiesChanged();
    c.dem.advance(1e-3);
    EXPECT_NEAR(c.speed(), 0, 1e-15);
    EXPECT_NEAR(c.dem.bodies()[c.ball].velocity.x(), 0.01, 1e-15);
}


TEST(lubrication, cubeNearTheSideOfAWallSurface)
{
    // A tank's walls (normals into the tank) and a cube 1 mm from its +x
    // side: the gap, the normal from the wall to the cube, the cube's
    // face centre
    const wallMeshShape tank
    (
        primitiveMeshes::openBox(vec3(-0.025, -0.025, 0), vec3(0.025, 0.025, 0.05), 8),
        "tank", 0.01
    );
    const auto c = cube(0.005);
    const bodyPose pc = at(vec3(0.019, 0.001, 0.025));
    const closestApproach a = lubrication::approach(tank, bodyPose(), *c, pc, 0.005);
    ASSERT_TRUE(a.found);
    EXPECT_NEAR(a.gap, 0.001, 1e-12);
    EXPECT_NEAR((a.normal + vec3::UnitX()).norm(), 0, 1e-9);
    EXPECT_NEAR((a.pointB - vec3(0.024, 0.001, 0.025)).norm(), 0, 1e-9);
}


TEST(lubrication, cubeApproachingAWallSurfaceInTheDem)
{
    contactMaterial glass{"glass", 1e7, 0.24, 1, 0};
    demSettings s;
    s.overlap.level = 0;
    demSolver dem({glass}, s);
    rigidBody tank
    (
        "tank",
        std::make_shared<wallMeshShape>
        (
            primitiveMeshes::openBox(vec3(-0.025, -0.025, 0), vec3(0.025, 0.025, 0.05), 8),
            "tank", 0.01
        ),
        1
    );
    tank.motion = motionType::fixed;
    dem.addBody(tank, true);
    rigidBody b("cube", cube(0.005), 2500);
    b.pose = at(vec3(0.019, 0.001, 0.025));
    b.velocity = vec3(0.33, 0, 0);
    b.fluidCellSize = 3.125e-3;
    const int i = dem.addBody(b);
    dem.setFluidViscosity(1e-3);
    dem.step(1e-5);
    // The film pushes the cube back from the wall (+x): force along -x
    EXPECT_LT(dem.bodies()[i].lubricationForce.x(), 0);
    EXPECT_NEAR(dem.bodies()[i].lubricationForce.y(), 0, 1e-12);
    EXPECT_GT(dem.work().lubricatedPairs, 0);
}


TEST(lubrication, filmPointMovesContinuouslyAsAFaceTurns)
{
    // A cube face over a plane turned by small angles: the film's point
    // leaves the face's centre gradually (it used to jump to a corner as
    // soon as the face was not exactly parallel: a run then depended on
    // round-off, serial against parallel)
    const double R = 0.005, g = 3e-4, cap = 5e-3;
    const auto c = cube(R);
    auto plane = std::make_shared<halfSpaceShape>();
    const bodyPose floor = halfSpaceShape::poseOf(vec3::Zero(), vec3::UnitZ());
    double previous = 0;
    for (const double angle : {0.0, 1e-9, 1e-6, 1e-5, 1e-4})
    {
        const bodyPose p(vec3(0, 0, R + g), quat(Eigen::AngleAxisd(angle, vec3::UnitY())));
        const closestApproach a = lubrication::approach(*plane, floor, *c, p, cap);
        ASSERT_TRUE(a.found);
        const double shift = std::hypot(a.pointB.x(), a.pointB.y());
        // The lowest edge is 2R sin(angle) below the highest: the point
        // moves by at most R times that over the band (1e-2 R here)
        EXPECT_LE(shift, R*(2*R*std::sin(angle))/(1e-2*R) + 1e-12) << "angle " << angle;
        EXPECT_GE(shift + 1e-15, previous);
        previous = shift;
    }
    EXPECT_LT(previous, R);
}


TEST(lubrication, footprintOfAFlatFaceFadesAsItTurns)
{
    // A cube's face over a plane: its footprint is the face (area 4 R^2,
    // area moments R^2/3 along the face, none across, no height); turned,
    // still the whole face, each triangle (each has a corner on the far
    // edge) weighted by the least of its normal's weight (fading to 0.05
    // rad) and its far corner's in the band (a tenth of the bounding
    // radius), the mean height over it R sin(angle); turned beyond 0.05
    // rad, nothing. A facetted sphere's lowest facets are no flat face
    const double R = 0.005, g = 3e-4, cap = 5e-3;
    const auto c = cube(R);
    auto plane = std::make_shared<halfSpaceShape>();
    const bodyPose floor = halfSpaceShape::poseOf(vec3::Zero(), vec3::UnitZ());
    auto over = [&](const shape& s, double angle)
    {
        const bodyPose p(vec3(0, 0, R + g), quat(Eigen::AngleAxisd(angle, vec3::UnitY())));
        return lubrication::approach(*plane, floor, s, p, cap);
    };
    const closestApproach flat = over(*c, 0);
    ASSERT_TRUE(flat.found);
    EXPECT_NEAR(flat.footprintArea, 4*R*R, 1e-9*R*R);
    EXPECT_NEAR(flat.footprintSpread(0, 0), R*R/3, 1e-9*R*R);
    EXPECT_NEAR(flat.footprintSpread(1, 1), R*R/3, 1e-9*R*R);
    EXPECT_NEAR(flat.footprintSpread(2, 2), 0, 1e-12*R*R);
    EXPECT_NEAR(flat.footprintSpread(0, 1), 0, 1e-12*R*R);
    EXPECT_NEAR(flat.footprintHeight, 0, 1e-12*R);
    EXPECT_NEAR(flat.footprintCentre.x(), 0, 1e-12*R);
    EXPECT_NEAR(flat.footprintCentre.y(), 0, 1e-12*R);

    const double band = 0.1*c->boundingRadius();
    for (const double angle : {0.015, 0.04})
    {
        const closestApproach turned = over(*c, angle);
        const double weight = std::min
        (
            1 - 2*R*std::sin(angle)/band,
            1 - (1 - std::cos(angle))/(1 - std::cos(0.05))
        );
        EXPECT_GT(weight, 0.3);     // the case is meant to test a partial footprint
        EXPECT_NEAR(turned.footprintArea, weight*4*R*R, 1e-6*R*R) << angle;    // exact: round-off
        EXPECT_NEAR(turned.footprintHeight, R*std::sin(angle), 1e-6*R) << angle;
    }
    EXPECT_EQ(over(*c, 0.06).footprintArea, 0);

    const triangleMeshShape ball(primitiveMeshes::icosphere(R, 3), "ball");
    EXPECT_EQ(over(ball, 0.3).footprintArea, 0);
}


TEST(lubrication, wedgeFilmAgainstTheReynoldsEquation)
{
    // Plates tilted against each other, the gap from h to ratio h: the
    // one-dimensional Reynolds equation solved independently (trapezoidal
    // rule on 400,001 points, numpy; the factors against parallel plates
    // at the mean gap): ratio 2: 1.072, 1.394, 0.069; 3.6: 1.250, 2.471,
    // 0.124; 10: 1.825, 6.849, 0.210
    const double ratio[3] = {2, 3.6, 10};
    const double normal[3] = {1.072, 1.250, 1.825};
    const double tilt[3] = {1.394, 2.471, 6.849};
    const double offset[3] = {0.069, 0.124, 0.210};
    for (int i = 0; i < 3; ++i)
    {
        const auto w = lubrication::wedgeIntegrated(ratio[i]);
        // the last printed digit of the independent solution (above)
        EXPECT_NEAR(w.normal, normal[i], 1e-3) << ratio[i];
        EXPECT_NEAR(w.tilt, tilt[i], 2e-3) << ratio[i];
        EXPECT_NEAR(w.offset, offset[i], 1e-3) << ratio[i];
        // the table within 0.5% of it
        const auto t = lubrication::wedge(ratio[i]);
        EXPECT_NEAR(t.normal, w.normal, 5e-3*w.normal) << ratio[i];
        EXPECT_NEAR(t.tilt, w.tilt, 5e-3*w.tilt) << ratio[i];
        EXPECT_NEAR(t.offset, w.offset, 5e-3) << ratio[i];
    }
    // Parallel plates, and continuity from them
    const auto p = lubrication::wedge(1);
    EXPECT_EQ(p.normal, 1);
    EXPECT_EQ(p.tilt, 1);
    EXPECT_EQ(p.offset, 0);
    const auto q = lubrication::wedge(1.01);
    EXPECT_NEAR(q.normal, 1, 1e-3);
    EXPECT_NEAR(q.tilt, 1, 1e-3);
    EXPECT_NEAR(q.offset, 0, 1e-3);
    // Held beyond the table's end, finite
    const auto far = lubrication::wedge(1e6);
    EXPECT_TRUE(std::isfinite(far.normal) && far.normal > normal[2]);
}


TEST(lubrication, flatFilmOfADisc)
{
    // The Reynolds equation's squeeze film of a disc of radius a at gap
    // h: normal 3 pi mu a^4/(2 h^3), tilt pi mu a^6/(8 h^3); less their
    // values at hAct, held below the roughness, none beyond hAct
    const double mu = 1e-3, a = 0.004, h = 2e-4, hAct = 4e-3, hR = 1e-5;
    const double film = 1/(h*h*h) - 1/(hAct*hAct*hAct);
    const auto disc = lubrication::flatCoefficients(mu, M_PI*a*a, a*a/4, a*a/4, h, hAct, hR);
    EXPECT_NEAR(disc.normal, 1.5*M_PI*mu*std::pow(a, 4)*film, 1e-12*disc.normal);
    EXPECT_NEAR(disc.tilt1, M_PI*mu*std::pow(a, 6)/8*film, 1e-12*disc.tilt1);
    EXPECT_NEAR(disc.tilt2, disc.tilt1, 1e-12*disc.tilt1);
    const auto held = lubrication::flatCoefficients(mu, M_PI*a*a, a*a/4, a*a/4, 0.1*hR, hAct, hR);
    EXPECT_NEAR(held.normal/disc.normal, (1/std::pow(hR, 3) - 1/std::pow(hAct, 3))/film, 1e-9);
    EXPECT_EQ(lubrication::flatCoefficients(mu, M_PI*a*a, a*a/4, a*a/4, hAct, hAct, hR).normal, 0);
    // A long footprint resists tilting about its length far more than
    // about its width (the arm is across the axis)
    const auto strip = lubrication::flatCoefficients(mu, 4*a*a, a*a/3, a*a/48, h, hAct, hR);
    EXPECT_GT(strip.tilt2, 10*strip.tilt1);
}


namespace
{

//- Two 10 mm cubes face to face along x, 0.1 mm apart, in a fluid of
//  viscosity mu (no contact)
struct facingCubes
{
    demSolver dem;
    int a = -1, b = -1;
    static constexpr double R = 0.005, gap = 1e-4;

    explicit facingCubes(double mu)
    :
        dem({contactMaterial{"glass", 6.3e10, 0.24, 1, 0}}, demSettings())
    {
        for (const double side : {-1.0, 1.0})
        {
            rigidBody c(side < 0 ? "a" : "b", cube(R), 2500);
            c.pose = at(vec3(side*(R + 0.5*gap), 0, 0));
            c.fluidCellSize = 3.125e-3;
            (side < 0 ? a : b) = dem.addBody(c);
        }
        dem.setFluidViscosity(mu);
    }
    rigidBody& A() { return dem.bodies()[a]; }
    rigidBody& B() { return dem.bodies()[b]; }
};

} // End anonymous namespace


TEST(lubrication, facingCubesSqueezeAndTiltLikePlates)
{
    // Approaching: the normal film is the plates' (the footprint's), far
    // above the equivalent spheres' 6 pi mu R*^2/h
    {
        facingCubes f(1e-3);
        f.B().velocity = vec3(-1e-3, 0, 0);
        f.dem.step(1e-6);
        const double hAct = 1.7*3.125e-3;
        const auto plates = lubrication::flatCoefficients
        (
            1e-3, 4*f.R*f.R, f.R*f.R/3, f.R*f.R/3, f.gap, hAct, 0
        );
        const double Fx = f.B().lubricationForce.x();
        // 1%: the face-on cubes are parallel plates; what is left is the
        // step's change of the gap (1e-6 s at 1e-3 m/s)
        EXPECT_NEAR(Fx, plates.normal*1e-3, 0.01*plates.normal*1e-3);
        const double Rstar = 0.5*std::cbrt(3*8*std::pow(f.R, 3)/(4*M_PI));
        EXPECT_GT(Fx, 100*6*M_PI*1e-3*Rstar*Rstar/f.gap*1e-3);
    }
    // Counter-rotating about y (the pair tilting open at the bottom, as
    // two cubes falling side by side turn): the tilt film takes the
    // relative tilting out (at most all of it in a step); about the
    // normal (x) they twist freely
    {
        facingCubes f(1e-2);
        f.A().angularVelocity = vec3(0.1, 0.1, 0);
        f.B().angularVelocity = vec3(-0.1, -0.1, 0);
        const double dt = 1e-5, hAct = 1.7*3.125e-3;
        f.dem.step(dt);
        const auto plates = lubrication::flatCoefficients
        (
            1e-2, 4*f.R*f.R, f.R*f.R/3, f.R*f.R/3, f.gap, hAct, 0
        );
        const double inv = 2/f.A().inertia()(1);
        const double expected = 0.2*(1 - plates.tilt1*inv*dt);
        const double relative = f.A().angularVelocity.y() - f.B().angularVelocity.y();
        EXPECT_LT(expected, 0.99*0.2);      // the film takes a visible share
        // 2% of the share taken: the implicit step against its linear
        // estimate 1 - c dt/I
        EXPECT_NEAR(relative, expected, 0.02*(0.2 - expected));
        EXPECT_NEAR(f.A().angularVelocity.x(), 0.1, 1e-9);
        EXPECT_NEAR(f.B().angularVelocity.x(), -0.1, 1e-9);
        // In 0.01 s the tilting has gone
        f.dem.advance(0.01);
        EXPECT_LT(std::abs(f.A().angularVelocity.y() - f.B().angularVelocity.y()), 1e-3*0.2);
    }
    // Without fluid, nothing
    {
        facingCubes f(0);
        f.A().angularVelocity = vec3(0, 0.1, 0);
        f.dem.step(1e-5);
        EXPECT_NEAR(f.A().angularVelocity.y(), 0.1, 1e-12);
    }
}


TEST(lubrication, facingCubesTiltedAgainstEachOtherKeepTheirFilm)
{
    // Two cubes turned open at the bottom (as two cubes falling side by
    // side in water turn, 0.0075 rad each at 0.049 s): the gap 0.1 mm at
    // the top edges, 0.25 mm at the bottom. Approaching, their film is
    // the wedge's: of the size of parallel plates at the mean gap (0.175
    // mm), far above the point's, acting between the centre and the
    // closest edge. (The footprint of a band at the closest gap had lost
    // it all: 1e-5 N where the plates give 1e-3 N.)
    const double theta = 0.0075, mu = 1e-3, u = 1e-3;
    facingCubes f(mu);
    const double R = f.R, hTop = 1e-4;
    // A turned about y by +theta, B by -theta, about their centres (the
    // facing faces' top edges towards each other), the centres apart so
    // that the top edges are hTop apart
    const double half = 0.5*hTop + R*(std::cos(theta) + std::sin(theta));
    f.A().pose = bodyPose(vec3(-half, 0, 0), quat(Eigen::AngleAxisd(theta, vec3::UnitY())));
    f.B().pose = bodyPose(vec3(half, 0, 0), quat(Eigen::AngleAxisd(-theta, vec3::UnitY())));
    f.B().velocity = vec3(-u, 0, 0);
    f.dem.step(1e-6);
    const double hAct = 1.7*3.125e-3;
    const double hMean = hTop + 2*R*std::sin(2*theta)/2;
    const auto plates = lubrication::flatCoefficients
    (
        mu, 4*R*R, R*R/3, R*R/3, hMean, hAct, 0
    );
    const double Fx = f.B().lubricationForce.x();
    // 0.6-1.6 of parallel plates at the mean gap: the wedge's own factor
    // (1.07-1.8 for gap ratios 2-10, test above) with room for the
    // footprint's cut; the point's film is 100 times less
    EXPECT_GT(Fx, 0.6*plates.normal*u);
    EXPECT_LT(Fx, 1.6*plates.normal*u);
    // The point's film is 100 times less
    const double Rstar = 0.5*std::cbrt(3*8*std::pow(R, 3)/(4*M_PI));
    EXPECT_GT(Fx, 10*6*M_PI*mu*Rstar*Rstar/hTop*u);
    // Its torque on B about y turns B's top away from A's, as the
    // pressure, highest near the top edge, does: positive (x up, z out)
    // for a force +x above B's centre. The arm: between the centre and
    // the top edge
    const double Ty = f.B().lubricationTorque.y();
    EXPECT_GT(Ty, 0);
    EXPECT_LT(Ty, 0.5*R*Fx);
}


TEST(lubrication, rockingFacesLoseTheirTiltingWithoutReversingIt)
{
    // Two cubes tilted against each other (a wedge, 0.1 mm at the top
    // edges) in a fluid so viscous that the film's dampers are at their
    // step limits; A rocks about y, which also moves its face along the
    // normal at the film's pressure centre, off the closest points. The
    // normal damper there and the tilt damper both take out the rocking:
    // it decays without reversing, and the kinetic energy never grows
    // (the dampers limited together, lubricationFilms::applyFilm), at the DEM's
    // own step and at a tenth of it
    const double theta = 0.0075;
    for (const double fraction : {1.0, 0.1})
    {
        facingCubes f(1e4);
        const double R = f.R, hTop = 1e-4;
        const double half = 0.5*hTop + R*(std::cos(theta) + std::sin(theta));
        f.A().pose = bodyPose(vec3(-half, 0, 0), quat(Eigen::AngleAxisd(theta, vec3::UnitY())));
        f.B().pose = bodyPose(vec3(half, 0, 0), quat(Eigen::AngleAxisd(-theta, vec3::UnitY())));
        f.A().angularVelocity = vec3(0, 0.1, 0);
        auto energy = [&f]{ return f.A().kineticEnergy() + f.B().kineticEnergy(); };
        auto rocking = [&f]{ return f.B().angularVelocity.y() - f.A().angularVelocity.y(); };
        const double dt = fraction*f.dem.timeStep();
        const double E0 = energy(), r0 = rocking();
        double E = E0, r = r0;
        const int n = int(std::lround(2e-4/dt));
        for (int k = 0; k < n; ++k)
        {
            f.dem.step(dt);
            const double rk = rocking();
            if (std::abs(r) > 1e-3*std::abs(r0))
            {
                ASSERT_GE(rk*r, 0) << "dt " << dt << ", step " << k;
            }
            ASSERT_LE(energy(), E*(1 + 1e-12)) << "dt " << dt << ", step " << k;
            E = energy();
            r = rk;
        }
        // The relative rocking has gone; the pair's common turning stays
        // (half the energy)
        EXPECT_LT(std::abs(r), 0.01*std::abs(r0)) << "dt " << dt;
        EXPECT_GT(E, 0.49*E0) << "dt " << dt;
    }
}


TEST(lubrication, contactFilmCarriedAtRestAsMeasured)
{
    // A faceted ball pressed into a cube face, both free, closing slowly
    // (a bed at rest: the film of a contact is the contact's, its radius
    // from the two surfaces' curvature near the contact point). Carried
    // (the default), the curvatures are measured once and carried while
    // the bodies move less than 5% of the activation distance; measured
    // every sub-step (reuse off), the same films follow
    auto run = [](bool carry, demCounters& work)
    {
        demSettings s;
        s.reuseContacts = carry;
        demSolver dem({contactMaterial{"glass", 1e7, 0.24, 1, 0}}, s);
        rigidBody ball
        (
            "ball",
            std::make_shared<triangleMeshShape>(primitiveMeshes::icosphere(0.005, 3), "ball"),
            2500
        );
        // 2 um into the face at x = 0, along a line off the vertices
        ball.pose = at(vec3(-0.005 + 2e-6, 0.0003, 0.0002));
        ball.velocity = vec3(1e-4, 0, 0);
        ball.fluidCellSize = 1e-3;
        const int i = dem.addBody(ball);
        rigidBody box("box", cube(0.005), 2500);
        box.pose = at(vec3(0.005, 0, 0));
        box.fluidCellSize = 1e-3;
        dem.addBody(box);
        dem.setFluidViscosity(1e-3);
        for (int k = 0; k < 150; ++k)
        {
            dem.step(1e-6);
        }
        work = dem.work();
        return vec3(dem.bodies()[i].lubricationForce);
    };
    demCounters carriedWork, measuredWork;
    const vec3 carried = run(true, carriedWork);
    const vec3 measured = run(false, measuredWork);
    // The contact's film acted at every sub-step, and was carried at most
    // of them (measured again after reuseMaxSteps, 100)
    // (one film per contact pass: 150 steps and the loads at the start)
    EXPECT_GE(carriedWork.lubricatedPairs, 150);
    EXPECT_GE(carriedWork.reusedFilms, carriedWork.lubricatedPairs - 3);
    EXPECT_EQ(measuredWork.reusedFilms, 0);
    ASSERT_GT(measured.norm(), 0);
    // 1e-9 relative: the bodies move 15 nm relative to each other over
    // the run, a millionth of the ball's triangles (about 1 mm), and the
    // faces' curvature is constant on each; what is left is round-off
    // (the curvature rotated into the body frames and back)
    EXPECT_NEAR((carried - measured).norm()/measured.norm(), 0, 1e-9);
}
