// Periodic domains for the bodies (issue: suspensions and fluidised beds,
// item 1): the periodic box's wrap, nearest image and images; the broad
// phase against every image by brute force; and a frictional collision of
// two cubes through a corner of a triply periodic box against the same
// collision in the middle of the box (a translation: only round-off may
// differ), with the leading body wrapped while the contact lasts.

#include "demSolver.H"
#include "broadPhase.H"
#include "periodicBox.H"
#include "triangleMeshShape.H"
#include "primitiveMeshes.H"
#include "coreError.H"
#include "bodyInsertion.H"
#include "sphereShape.H"

#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <cmath>
#include <random>
#include <memory>
#include <set>

using namespace immersedDEM;

namespace
{

periodicBox cube(double L, int directions = 3)
{
    periodicBox p;
    const vec3 axis[3] = {vec3::UnitX(), vec3::UnitY(), vec3::UnitZ()};
    for (int k = 0; k < directions; ++k)
    {
        p.addDirection(L*axis[k], "cyclic" + std::to_string(k));
    }
    return p;
}

} // End anonymous namespace


TEST(periodicBox, wrapNearestAndImages)
{
    periodicBox p = cube(1.0);
    p.setOrigin(vec3(-0.5, 0, 2));
    vec3 x(0.75, -0.25, 4.5);
    const periodicBox::periods n = p.wrap(x);
    EXPECT_EQ(n[0], 1);
    EXPECT_EQ(n[1], -1);
    EXPECT_EQ(n[2], 2);
    EXPECT_NEAR((x - vec3(-0.25, 0.75, 2.5)).norm(), 0, 1e-15);
    EXPECT_NEAR((x + p.translation(n) - vec3(0.75, -0.25, 4.5)).norm(), 0, 1e-15);

    // The image of (0.45, 0.05, 2.9) nearest (-0.45, 0.95, 2.1)
    const vec3 s = p.nearestShift(vec3(-0.45, 0.95, 2.1), vec3(0.45, 0.05, 2.9));
    EXPECT_NEAR((s - vec3(-1, 1, -1)).norm(), 0, 1e-15);

    // A box over a corner meets the cell in 8 images, one inside in 1
    const auto corner = p.imageShifts(axisAlignedBox(vec3(0.4, 0.9, 2.9), vec3(0.6, 1.1, 3.1)));
    EXPECT_EQ(corner.size(), 8u);
    const auto inside = p.imageShifts(axisAlignedBox(vec3(0, 0.4, 2.4), vec3(0.1, 0.6, 2.6)));
    ASSERT_EQ(inside.size(), 1u);
    EXPECT_EQ(inside[0], vec3::Zero());
}


TEST(periodicBox, badInputNamesTheCause)
{
    periodicBox p;
    p.addDirection(vec3(1, 0, 0), "sides");
    // The other half of the same cyclic pair is the same direction
    p.addDirection(vec3(-1, 0, 0), "sides_half1");
    EXPECT_EQ(p.directions(), 1);
    try
    {
        p.addDirection(vec3(1, 1, 0), "skew");
        FAIL() << "a skew direction was accepted";
    }
    catch (const coreError& e)
    {
        EXPECT_NE(std::string(e.what()).find("not orthogonal"), std::string::npos) << e.what();
    }
    try
    {
        p.check("big", 0.6, 0.0);
        FAIL() << "a body larger than half the period was accepted";
    }
    catch (const coreError& e)
    {
        const std::string m = e.what();
        EXPECT_NE(m.find("'big'"), std::string::npos) << m;
        EXPECT_NE(m.find("'sides'"), std::string::npos) << m;
    }
    EXPECT_NO_THROW(p.check("small", 0.45, 0.01));
}


// The broad phase's periodic pairs are exactly the pairs whose boxes meet
// through some image (brute force over every shift of -1, 0, +1 periods)
TEST(periodicBox, broadPhaseFindsEveryImagePair)
{
    const double L = 1.0;
    periodicBox p = cube(L);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0, 1), h(0.02, 0.2);
    std::vector<axisAlignedBox> boxes;
    std::vector<int> all;
    for (int i = 0; i < 300; ++i)
    {
        // Centres anywhere in [-0.2, 1.2]^3: wrapped or not
        const vec3 c(1.4*u(rng) - 0.2, 1.4*u(rng) - 0.2, 1.4*u(rng) - 0.2);
        const vec3 e(h(rng), h(rng), h(rng));
        boxes.emplace_back(c - e, c + e);
        all.push_back(i);
    }
    std::set<std::pair<int, int>> brute;
    for (int i = 0; i < int(boxes.size()); ++i)
    {
        for (int j = i + 1; j < int(boxes.size()); ++j)
        {
            for (int a = -2; a <= 2; ++a)
                for (int b = -2; b <= 2; ++b)
                    for (int c = -2; c <= 2; ++c)
                    {
                        const vec3 s = L*vec3(a, b, c);
                        if (boxes[i].overlaps(axisAlignedBox(boxes[j].min + s, boxes[j].max + s)))
                        {
                            brute.insert({i, j});
                        }
                    }
        }
    }
    const auto found = broadPhase::gridPairs(boxes, all, p);
    EXPECT_EQ(found.size(), brute.size());
    const std::set<std::pair<int, int>> foundSet(found.begin(), found.end());
    EXPECT_TRUE(foundSet == brute);
    EXPECT_GT(brute.size(), 100u);
    for (const auto& q : found)
    {
        EXPECT_TRUE(broadPhase::imagesOverlap(boxes[q.first], boxes[q.second], p));
    }
}


namespace
{

struct run
{
    std::vector<vec3> xA, xB, vA, vB, wA, wB, F;
    bool wrappedInContact = false;
    int contactSteps = 0;
};

// Two frictional cubes (a box mesh: the convex engine) meeting obliquely,
// spinning, with a common drift along x; A starts at start
run collide(const vec3& start, const periodicBox* periodic)
{
    const double a = 0.004, L = 0.04;
    (void)L;
    contactMaterial m{"m", 1e7, 0.3, 0.6, 0.4};
    demSettings s;
    s.stepsPerContact = 50;
    s.referenceSpeed = 0.3;
    demSolver dem({m}, s);
    if (periodic) dem.setPeriodic(*periodic);
    auto geometry = std::make_shared<triangleMeshShape>(primitiveMeshes::box(vec3(a, a, a)), "cube");
    rigidBody A("A", geometry, 2000), B("B", geometry, 2000);
    A.pose = bodyPose(start, quat(Eigen::AngleAxisd(0.3, vec3(0, 0, 1).normalized())));
    B.pose = bodyPose
    (
        start + vec3(2*a*1.1 + 0.0015, 0.002, 0.001),
        quat(Eigen::AngleAxisd(0.5, vec3(1, 1, 0).normalized()))
    );
    A.velocity = vec3(0.6, 0, 0.02);
    B.velocity = vec3(0.4, -0.03, 0);
    A.angularVelocity = vec3(0, 0, 20);
    B.angularVelocity = vec3(10, 0, -5);
    dem.addBody(A);
    dem.addBody(B);

    run r;
    const double dt = 2e-6;
    vec3 offsetA = vec3::Zero();
    for (int n = 0; n < 6000; ++n)
    {
        dem.step(dt);
        const rigidBody& a0 = dem.bodies()[0];
        const rigidBody& b0 = dem.bodies()[1];
        const bool touching = !dem.contacts().empty();
        if (touching) ++r.contactSteps;
        if (touching && a0.periodicOffset != offsetA) r.wrappedInContact = true;
        offsetA = a0.periodicOffset;
        r.xA.push_back(a0.pose.position() + a0.periodicOffset);
        r.xB.push_back(b0.pose.position() + b0.periodicOffset);
        r.vA.push_back(a0.velocity);
        r.vB.push_back(b0.velocity);
        r.wA.push_back(a0.angularVelocity);
        r.wB.push_back(b0.angularVelocity);
        r.F.push_back(b0.contactForce);
        if (periodic)
        {
            // Every centre stays in the primary cell
            for (const rigidBody& b : dem.bodies())
            {
                const vec3 t = b.pose.position() - periodic->origin();
                EXPECT_TRUE((t.array() >= -1e-15).all() && (t.array() < 0.04 + 1e-15).all())
                    << "step " << n << ": " << t.transpose();
            }
        }
    }
    return r;
}

} // End anonymous namespace


// The same collision through the corner of a triply periodic box and in
// its middle: a translation by whole numbers of periods and half a period,
// so the trajectories agree to round-off. 1e-10 of the speeds and sizes:
// round-off of positions near 0.04 m is 1e-17 m, and the collision (a few
// hundred steps of a stiff contact) amplifies it by far less than 1e6
TEST(periodicBox, collisionThroughACornerIsTheCollisionInTheMiddle)
{
    const double L = 0.04;
    const periodicBox p = cube(L);
    const vec3 cornerStart(L - 0.0016, L - 0.0005, L - 0.0006);
    const vec3 middle = cornerStart - vec3(0.5*L, 0.5*L, 0.5*L);
    const run across = collide(cornerStart, &p);
    const run away = collide(middle, nullptr);

    // The scenario does what it is for: a lasting contact, during which
    // the leading body was wrapped
    EXPECT_GT(across.contactSteps, 50);
    EXPECT_TRUE(across.wrappedInContact);
    ASSERT_EQ(across.contactSteps, away.contactSteps);

    const vec3 shift(0.5*L, 0.5*L, 0.5*L);
    double dx = 0, dv = 0, dw = 0, dF = 0, Fmax = 0;
    for (size_t n = 0; n < across.xA.size(); ++n)
    {
        dx = std::max(dx, (across.xA[n] - away.xA[n] - shift).norm());
        dx = std::max(dx, (across.xB[n] - away.xB[n] - shift).norm());
        dv = std::max(dv, (across.vA[n] - away.vA[n]).norm());
        dv = std::max(dv, (across.vB[n] - away.vB[n]).norm());
        dw = std::max(dw, (across.wA[n] - away.wA[n]).norm());
        dw = std::max(dw, (across.wB[n] - away.wB[n]).norm());
        dF = std::max(dF, (across.F[n] - away.F[n]).norm());
        Fmax = std::max(Fmax, away.F[n].norm());
    }
    std::cout << "through the corner against the middle: positions " << dx
        << " m, velocities " << dv << " m/s, angular velocities " << dw
        << " rad/s, contact forces " << dF << " N of " << Fmax << " N" << std::endl;
    EXPECT_GT(Fmax, 0);
    EXPECT_LT(dx, 1e-10*0.008) << "positions";
    EXPECT_LT(dv, 1e-10*0.6) << "velocities";
    EXPECT_LT(dw, 1e-10*20) << "angular velocities";
    // A force is a stiffness times an overlap depth: the face contact's
    // stiffness (Y a^2/l_c, 1.6e5 N/m) turns the positions' round-off
    // (1e-17 m at 0.04 m, grown over 6000 steps to 2e-16 m, measured) into
    // 3e-11 N, 4e-10 of the peak force; 1e-8 is 25 times that, and still a
    // displacement of 5e-15 m, 1e-12 of the cube
    EXPECT_LT(dF, 1e-8*Fmax) << "contact forces";
}


// A body larger than half a period is refused when added, naming it
TEST(periodicBox, bodyTooLargeForThePeriodIsAnError)
{
    contactMaterial m{"m", 1e7, 0.3, 0.6, 0.4};
    demSolver dem({m}, demSettings());
    dem.setPeriodic(cube(0.02, 1));
    auto geometry = std::make_shared<triangleMeshShape>(primitiveMeshes::box(vec3(0.004, 0.004, 0.004)), "cube");
    EXPECT_THROW(dem.addBody(rigidBody("large", geometry, 2000)), coreError);
}


// Insertion in a periodic domain: a region reaching past the periodic
// boundaries (bodies may straddle them) filled with spheres, every pair
// apart by the clearance through the nearest image too; the same filling
// without the periodicity has pairs that overlap through the boundary
TEST(periodicBox, insertionKeepsBodiesApartThroughTheBoundary)
{
    const double L = 0.1, R = 0.004, clearance = 1e-4;
    auto fill = [&](bool periodic)
    {
        contactMaterial m{"glass", 6e10, 0.25, 0.9, 0.3};
        auto dem = std::make_unique<demSolver>(std::vector<contactMaterial>{m}, demSettings());
        if (periodic) dem->setPeriodic(cube(L, 2));
        bodyTemplate t;
        t.name = "ball";
        t.geometry = std::make_shared<sphereShape>(R);
        t.density = 2500;
        insertionSettings s;
        s.name = "balls";
        s.region = insertionRegion::box(vec3(-0.01, -0.01, 0), vec3(L + 0.01, L + 0.01, L));
        s.number = 400;
        s.seed = 3;
        s.clearance = clearance;
        const insertionReport r = bodyInsertion::insert(*dem, t, s);
        EXPECT_EQ(r.placed, 400) << r.summary();
        return dem;
    };
    auto closest = [&](const demSolver& dem, const periodicBox& p)
    {
        double dMin = 1;
        const auto& b = dem.bodies();
        for (size_t i = 0; i < b.size(); ++i)
        {
            for (size_t j = 0; j < i; ++j)
            {
                const vec3& xi = b[i].pose.position();
                const vec3& xj = b[j].pose.position();
                dMin = std::min(dMin, (xj + p.nearestShift(xi, xj) - xi).norm());
            }
        }
        return dMin;
    };
    const periodicBox p = cube(L, 2);
    const auto withImages = fill(true);
    const auto without = fill(false);
    EXPECT_GE(closest(*withImages, p), 2*R + clearance - 1e-15);
    EXPECT_LT(closest(*without, p), 2*R);
}
