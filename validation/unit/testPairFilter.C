// The DEM's pair filter (issue 20): a pair it rejects must have no overlap
// by the engine. The gap bounds against brute force, the rejections against
// virtualMesh on random poses near contact, the motion bound, and a DEM run
// with and without the filter giving the same trajectories bit for bit
// (convex bodies, measured exactly). The DEM's filter also rejects gaps
// proven positive below the engine's reach, where the octree could only
// find a spurious overlap (provenGapsBelowTheReachAreNotContacts).

#include "pairFilter.H"
#include "triangleBVH.H"
#include "demSolver.H"
#include "overlapEngine.H"
#include "sphereShape.H"
#include "halfSpaceShape.H"
#include "triangleMeshShape.H"
#include "wallMeshShape.H"
#include "primitiveMeshes.H"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

using namespace immersedDEM;

namespace
{

quat randomRotation(std::mt19937& g)
{
    std::normal_distribution<double> n;
    quat q(n(g), n(g), n(g), n(g));
    return q.normalized();
}

vec3 randomUnit(std::mt19937& g)
{
    std::normal_distribution<double> n;
    return vec3(n(g), n(g), n(g)).normalized();
}

std::array<vec3, 3> randomTriangle(std::mt19937& g, const vec3& centre, double size)
{
    std::uniform_real_distribution<double> u(-size, size);
    return {centre + vec3(u(g), u(g), u(g)), centre + vec3(u(g), u(g), u(g)),
            centre + vec3(u(g), u(g), u(g))};
}

//- Distance of two triangles by dense sampling of both (an upper bound)
double sampledDistance(const std::array<vec3, 3>& a, const std::array<vec3, 3>& b, int n)
{
    std::vector<vec3> pa, pb;
    for (int i = 0; i <= n; ++i)
    {
        for (int j = 0; i + j <= n; ++j)
        {
            const double s = double(i)/n, t = double(j)/n;
            pa.push_back(a[0] + s*(a[1] - a[0]) + t*(a[2] - a[0]));
            pb.push_back(b[0] + s*(b[1] - b[0]) + t*(b[2] - b[0]));
        }
    }
    double d = std::numeric_limits<double>::max();
    for (const vec3& x : pa)
    {
        for (const vec3& y : pb) d = std::min(d, (x - y).norm());
    }
    return d;
}

//- Distance of the surfaces of two posed triangle sets, all pairs
double bruteDistance(const triangleSoup& A, const bodyPose& pA, const triangleSoup& B, const bodyPose& pB)
{
    double d = std::numeric_limits<double>::max();
    for (const triFace& fa : A.faces)
    {
        const std::array<vec3, 3> ta
            {pA.toWorld(A.points[fa[0]]), pA.toWorld(A.points[fa[1]]), pA.toWorld(A.points[fa[2]])};
        for (const triFace& fb : B.faces)
        {
            const std::array<vec3, 3> tb
                {pB.toWorld(B.points[fb[0]]), pB.toWorld(B.points[fb[1]]), pB.toWorld(B.points[fb[2]])};
            d = std::min(d, triangleBVH::triangleDistance(ta, tb));
        }
    }
    return d;
}

} // End anonymous namespace


// The distance of two triangles: never above the sampled distance, and
// within the sampling's resolution of it; zero for crossing triangles
TEST(pairFilter, triangleDistance)
{
    std::mt19937 g(7);
    int crossing = 0;
    for (int k = 0; k < 300; ++k)
    {
        const auto a = randomTriangle(g, vec3::Zero(), 1);
        const auto b = randomTriangle(g, 0.8*randomUnit(g), 1);
        const double d = triangleBVH::triangleDistance(a, b);
        const double s = sampledDistance(a, b, 60);
        ASSERT_LE(d, s + 1e-12) << k;
        // Sampling step 1/60 of edges up to ~3.5 long
        EXPECT_NEAR(d, s, 0.07) << k;
        if (d == 0) ++crossing;
    }
    EXPECT_GT(crossing, 20);

    // An edge piercing the other triangle's interior far from its corners
    // and edges: distance 0 although every corner and edge pair is far
    const std::array<vec3, 3> flat{vec3(-1, -1, 0), vec3(1, -1, 0), vec3(0, 1, 0)};
    const std::array<vec3, 3> spike{vec3(0, -0.2, -1), vec3(0, -0.2, 1), vec3(3, 3, 3)};
    EXPECT_EQ(triangleBVH::triangleDistance(flat, spike), 0);
    // Parallel, 0.3 apart
    std::array<vec3, 3> above = flat;
    for (vec3& x : above) x.z() += 0.3;
    EXPECT_NEAR(triangleBVH::triangleDistance(flat, above), 0.3, 1e-14);
}


// The BVH pair search equals the minimum over all triangle pairs
TEST(pairFilter, separationMatchesBruteForce)
{
    const triangleSoup torus = primitiveMeshes::torus(1.0, 0.3, 24, 12);
    const triangleSoup ico = primitiveMeshes::icosphere(0.5, 1);
    const triangleBVH tA(torus), tB(ico);
    std::mt19937 g(3);
    std::uniform_real_distribution<double> u(0.2, 2.2);
    for (int k = 0; k < 40; ++k)
    {
        const bodyPose pA(vec3::Zero(), quat::Identity());
        const bodyPose pB(u(g)*randomUnit(g), randomRotation(g));
        const double brute = bruteDistance(torus, pA, ico, pB);
        const mat3 R = pB.rotation();
        const double s = triangleBVH::separation(tA, tB, R, pB.position(), 10, -1);
        EXPECT_NEAR(s, brute, 1e-9) << k;
        // Capped: min(cap, distance)
        const double c = triangleBVH::separation(tA, tB, R, pB.position(), 0.1, -1);
        EXPECT_NEAR(c, std::min(0.1, brute), 1e-9) << k;
    }
}


// The displacement of any point within the radius stays within the bound
TEST(pairFilter, motionBound)
{
    std::mt19937 g(11);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int k = 0; k < 200; ++k)
    {
        const bodyPose p0(vec3(u(g), u(g), u(g)), randomRotation(g));
        const double angle = (k % 4 == 0) ? 0 : 0.3*u(g);
        const bodyPose p1
        (
            p0.position() + 0.1*vec3(u(g), u(g), u(g)),
            bodyPose::axisAngle(randomUnit(g), angle)*p0.orientation()
        );
        const double m = pairFilter::motionBound(p0, p1, 2.0);
        double worst = 0;
        for (int j = 0; j < 200; ++j)
        {
            const vec3 x = 2.0*randomUnit(g);
            worst = std::max(worst, (p1.toWorld(x) - p0.toWorld(x)).norm());
        }
        EXPECT_LE(worst, m*(1 + 1e-12)) << k;
        // Not loose: x and -x turn by opposite vectors d, so the worst
        // case is at least |dx + d| >= sqrt(|dx|^2 + |d|^2) >= m/sqrt(2)
        // (less the sampling's shortfall)
        EXPECT_GE(worst, 0.65*m - 1e-15) << k;
    }
}


// Random poses near contact, every pairing of shapes the filter handles:
// whenever the gap bound exceeds the virtual mesh's reach the engine finds
// no region; a good share of the separated poses are proven; the bound
// never exceeds the true gap
TEST(pairFilter, rejectionsAgreeWithEngine)
{
    const double r = 0.005;
    auto ico = std::make_shared<triangleMeshShape>(primitiveMeshes::icosphere(r, 0), "icosahedron");
    auto fine = std::make_shared<triangleMeshShape>(primitiveMeshes::icosphere(r, 2), "icosphere");
    auto torus = std::make_shared<triangleMeshShape>(primitiveMeshes::torus(1.2*r, 0.4*r, 24, 12), "torus");
    auto ball = std::make_shared<sphereShape>(r);
    auto plane = std::make_shared<halfSpaceShape>();
    // An open box (no lid) as a wall, normals inwards: rim at the top
    const triangleSoup cup = primitiveMeshes::openBox(vec3::Constant(-4*r), vec3::Constant(4*r), 8);
    ASSERT_EQ(cup.faces.size(), 640u);
    ASSERT_EQ(cup.points.size(), 9u*9u*9u - 7u*7u*7u - 7u*7u);    // edges shared
    auto wall = std::make_shared<wallMeshShape>(cup, "cup", 2*r);
    ASSERT_GT(wall->signedDistance(vec3::Zero()), 3.9*r);
    ASSERT_LT(wall->signedDistance(vec3(0, 0, -4.5*r)), 0);

    const std::vector<std::shared_ptr<const shape>> bodies{ico, fine, torus, ball};
    const auto engine = overlapEngine::New("virtualMesh");
    const overlapSettings settings{2*r/10, 1};
    const double reach = pairFilter::engineReach("virtualMesh", settings);

    std::mt19937 g(5);
    std::uniform_real_distribution<double> u(0, 1);
    int proven = 0, apart = 0, touching = 0;
    auto check = [&](const shape& A, const bodyPose& pA, const shape& B, const bodyPose& pB, const char* what)
    {
        const double gap = pairFilter::gapLowerBound(A, pA, B, pB, reach, 10*r);
        const contactGeometry cg = engine->evaluate(A, pA, B, pB, settings);
        if (cg.regions.empty()) ++apart; else ++touching;
        if (gap > reach)
        {
            ++proven;
            ASSERT_TRUE(cg.regions.empty())
                << what << ": rejected with gap bound " << gap << " but the engine finds "
                << cg.volume();
        }
    };

    for (int k = 0; k < 120; ++k)
    {
        const auto& A = *bodies[k % bodies.size()];
        const auto& B = *bodies[(k/bodies.size()) % bodies.size()];
        const bodyPose pA(vec3::Zero(), randomRotation(g));
        // Centre distance from deep overlap to just apart
        const double d = (1.4 + 1.2*u(g))*r;
        const bodyPose pB(d*randomUnit(g), randomRotation(g));
        check(A, pA, B, pB, "bodies");

        // Against the plane z = 0 and the open cup (near its floor, walls
        // and rim)
        const bodyPose pP = halfSpaceShape::poseOf(vec3::Zero(), vec3::UnitZ());
        const bodyPose pz(vec3(0, 0, (0.6 + 0.8*u(g))*r), randomRotation(g));
        check(*plane, pP, B, pz, "plane");
        const vec3 spot
        (
            (k % 3 == 0 ? 3.2*r + 1.0*r*u(g) : 2*r*(u(g) - 0.5)),
            2*r*(u(g) - 0.5),
            (k % 5 == 0 ? 4*r + 2*r*(u(g) - 0.5) : -3.2*r - 1.0*r*u(g))
        );
        check(*wall, bodyPose(), B, bodyPose(spot, randomRotation(g)), "wall");
    }
    std::cout << "poses: " << apart + touching << ", apart " << apart
              << ", proven apart " << proven << std::endl;
    EXPECT_GT(touching, 50);
    // Most separated poses proven (the rest are within the reach, or where
    // the sign behind the cup's rim is unclear)
    EXPECT_GT(proven, 0.4*apart);

    // The bound never exceeds the true gap (two meshes: brute force)
    for (int k = 0; k < 30; ++k)
    {
        const bodyPose pA(vec3::Zero(), randomRotation(g));
        const bodyPose pB((2.05 + 0.5*u(g))*r*randomUnit(g), randomRotation(g));
        const double gap = pairFilter::gapLowerBound(*torus, pA, *fine, pB, -1, 10*r);
        const double brute = bruteDistance(torus->surface(), pA, fine->surface(), pB);
        EXPECT_LE(gap, brute + 1e-15);
        if (gap > 0) EXPECT_NEAR(gap, brute, 1e-12);
    }

    // One body inside the other: never proven apart
    const bodyPose centre(vec3::Zero(), quat::Identity());
    auto small = std::make_shared<triangleMeshShape>(primitiveMeshes::icosphere(0.2*r, 1), "small");
    EXPECT_LE(pairFilter::gapLowerBound(*fine, centre, *small, centre, reach, r), 0);
    EXPECT_LE(pairFilter::gapLowerBound(*small, centre, *fine, centre, reach, r), 0);
    EXPECT_LE(pairFilter::gapLowerBound(*ball, centre, *small, centre, reach, r), 0);
}


TEST(pairFilter, convexPiecesGapIsExact)
{
    // Raschig rings (4 x 2 x 4 mm, 26 convex pieces): the gap bound (their
    // hulls' distance, or where the hulls meet their pieces') never
    // exceeds the distance of their surfaces (brute force over the
    // triangles), is positive where they are apart, equals it when a thin
    // ring passes through the bore untouched (hulls meeting), and is never
    // positive where the exact engine finds an overlap
    const double mm = 0.001;
    auto ring = std::make_shared<triangleMeshShape>
    (
        primitiveMeshes::hollowCylinder(2*mm, 1*mm, 4*mm, 24), "ring"
    );
    // A wide thin ring (7.2 x 6.4 x 0.6 mm) linked through the ring's
    // bore: its wall passes the bore 0.6 mm from the bore's wall, and its
    // inner circle clears the ring's outside by 0.08 mm at the corners
    auto thin = std::make_shared<triangleMeshShape>
    (
        primitiveMeshes::hollowCylinder(3.6*mm, 3.2*mm, 0.6*mm, 48), "thin ring"
    );
    ASSERT_FALSE(ring->pieces().empty());
    ASSERT_FALSE(thin->pieces().empty());
    const auto engine = overlapEngine::New("virtualMesh");
    std::mt19937 g(11);
    std::uniform_real_distribution<double> u(0, 1);
    int apart = 0, linkedApart = 0;
    for (int k = 0; k < 200; ++k)
    {
        const bool linked = k % 2 == 1;
        const auto& B = linked ? *thin : *ring;
        const quat qA = randomRotation(g);
        const vec3 tA(0.01, 0.02, 0.03);
        const bodyPose pA = ring->poseFromFilePlacement(qA, tA);
        bodyPose pB;
        if (linked)
        {
            // The thin ring's axis along y of the ring's file frame, its
            // wall through the bore; jittered by up to 0.1 mm and 0.04 rad
            const quat q =
                quat(Eigen::AngleAxisd(M_PI/2 + 0.04*(u(g) - 0.5), vec3::UnitX()))
               *quat(Eigen::AngleAxisd(0.04*(u(g) - 0.5), vec3::UnitZ()));
            const vec3 c(3.4*mm + 0.1*mm*(u(g) - 0.5), 0.1*mm*(u(g) - 0.5), 0.1*mm*(u(g) - 0.5));
            pB = B.poseFromFilePlacement(qA*q, tA + qA*c);
        }
        else
        {
            pB = bodyPose(pA.position() + (3 + 3*u(g))*mm*randomUnit(g), randomRotation(g));
        }
        const double gap = pairFilter::gapLowerBound(*ring, pA, B, pB, -1, 10*mm);
        const bool touching = !engine->evaluate(*ring, pA, B, pB, {0.2*mm, 4}).regions.empty();
        if (touching)
        {
            EXPECT_LE(gap, 0) << k;
            continue;
        }
        const double brute = bruteDistance(ring->surface(), pA, B.surface(), pB);
        if (gap > 0 || brute > 1e-9*mm)
        {
            // A lower bound, positive where they are apart
            EXPECT_LE(gap, brute) << k;
            EXPECT_GT(gap, 0) << k;
            // Through the bore the hulls meet: the pieces' distance, exact
            // (the bound takes 1e-9 of the smaller radius off for
            // round-off; as much again for GJK's and the brute force's)
            if (linked)
            {
                EXPECT_NEAR(gap, brute, 2e-9*ring->boundingRadius()) << k;
            }
            ++apart;
            linkedApart += linked;
        }
    }
    EXPECT_GT(apart, 50);
    EXPECT_GT(linkedApart, 10);
}


// A DEM run of mesh bodies colliding on a plane gives the same trajectories
// bit for bit with and without the filter, and the filter rejects most
// pair tests
TEST(pairFilter, demUnchangedByFilter)
{
    const double r = 0.005;
    auto ico = std::make_shared<triangleMeshShape>(primitiveMeshes::icosphere(r, 0), "icosahedron");
    auto run = [&](bool filter, demSolver::counters& work, pairFilter::counters& fw)
    {
        contactMaterial glass{"glass", 1e6, 0.3, 0.5, 0.4};
        demSettings s;
        s.overlap = {2*r/10, 1};
        s.gravity = vec3(0, 0, -9.81);
        s.rejectSeparated = filter;
        demSolver dem({glass}, s);
        rigidBody floor("floor", std::make_shared<halfSpaceShape>(), 1);
        floor.motion = motionType::fixed;
        floor.pose = halfSpaceShape::poseOf(vec3::Zero(), vec3::UnitZ());
        dem.addBody(floor, true);
        std::mt19937 g(2);
        for (int i = 0; i < 6; ++i)
        {
            rigidBody b("b" + std::to_string(i), ico, 2500);
            b.pose = bodyPose(vec3((i % 3)*2.3*r, (i / 3)*2.3*r, (1.3 + 0.7*i)*r), randomRotation(g));
            b.velocity = vec3(0.02*(i % 2 ? 1 : -1), 0, -0.1);
            dem.addBody(b);
        }
        dem.advance(0.04);
        work = dem.work();
        fw = dem.filterWork();
        std::vector<vec3> x;
        for (const rigidBody& b : dem.bodies()) x.push_back(b.pose.position());
        return x;
    };
    demSolver::counters w0, w1;
    pairFilter::counters f0, f1;
    const auto x0 = run(false, w0, f0);
    const auto x1 = run(true, w1, f1);
    ASSERT_EQ(x0.size(), x1.size());
    for (size_t i = 0; i < x0.size(); ++i)
    {
        EXPECT_EQ(x0[i], x1[i]) << "body " << i;
    }
    EXPECT_EQ(f0.tested, 0);
    EXPECT_EQ(w0.droppedBySpheres, 0);
    // Most pairs rejected: by the bounding spheres (in the broad phase) or
    // by the filter
    EXPECT_GT(f1.rejected() + w1.droppedBySpheres, 0.5*(f1.tested + w1.droppedBySpheres));
    EXPECT_LT(w1.pairEvaluations, w0.pairEvaluations/2);
    EXPECT_GT(w1.pairEvaluations, 0);
    std::cout << "pair evaluations " << w0.pairEvaluations << " -> " << w1.pairEvaluations
              << "; dropped by spheres in the broad phase " << w1.droppedBySpheres
              << "; tested " << f1.tested << ", by spheres " << f1.rejectedBySpheres
              << ", by reuse " << f1.rejectedByReuse << ", by proof " << f1.rejectedByProof
              << ", proofs " << f1.proofs << std::endl;
}


// The broad phase's neighbour list (rebuilt only when a box leaves its
// grown box) misses no contact: in a pour of spheres of two sizes, every
// overlapping pair (by brute force over all pairs) is among the contacts of
// every step, and the list was rebuilt far less often than every step
TEST(pairFilter, neighbourListMissesNoContact)
{
    contactMaterial glass{"glass", 1e7, 0.3, 0.5, 0.4};
    demSettings s;
    s.overlapMethod = "sphere";
    s.contactLaw = "hertzMindlin";
    s.gravity = vec3(0, 0, -9.81);
    s.deltaT = 2e-5;
    demSolver dem({glass}, s);
    const double W = 0.012;
    const vec3 normals[] = {vec3::UnitZ(), vec3::UnitX(), -vec3::UnitX(), vec3::UnitY(), -vec3::UnitY()};
    const vec3 points[] = {vec3::Zero(), vec3::Zero(), vec3(W, 0, 0), vec3::Zero(), vec3(0, W, 0)};
    for (int k = 0; k < 5; ++k)
    {
        rigidBody w("w" + std::to_string(k), std::make_shared<halfSpaceShape>(), 1);
        w.motion = motionType::fixed;
        w.pose = halfSpaceShape::poseOf(points[k], normals[k]);
        dem.addBody(w, true);
    }
    std::mt19937 g(4);
    std::uniform_real_distribution<double> u(-1, 1);
    const auto small = std::make_shared<sphereShape>(0.0008);
    const auto large = std::make_shared<sphereShape>(0.0012);
    for (int i = 0; i < 64; ++i)
    {
        rigidBody b("s" + std::to_string(i), i % 3 ? small : large, 2500);
        b.pose = bodyPose
        (
            vec3(0.0015 + 0.003*(i % 4), 0.0015 + 0.003*((i/4) % 4), 0.0015 + 0.003*(i/16))
          + 0.0002*vec3(u(g), u(g), 0),
            quat::Identity()
        );
        b.velocity = 0.2*vec3(u(g), u(g), u(g));
        dem.addBody(b);
    }
    const int steps = 1500;
    long checked = 0;
    for (int n = 0; n < steps; ++n)
    {
        dem.step(s.deltaT);
        std::set<std::pair<int, int>> found;
        for (const contactRecord& c : dem.contacts()) found.insert({c.a, c.b});
        const auto& B = dem.bodies();
        for (int i = 5; i < int(B.size()); ++i)
        {
            const auto& si = static_cast<const sphereShape&>(*B[i].geometry);
            for (int j = i + 1; j < int(B.size()); ++j)
            {
                const auto& sj = static_cast<const sphereShape&>(*B[j].geometry);
                const double gap =
                    (B[i].pose.position() - B[j].pose.position()).norm() - si.radius() - sj.radius();
                if (gap < -1e-12*si.radius())
                {
                    ++checked;
                    ASSERT_TRUE(found.count({i, j})) << "step " << n << ": " << i << " " << j;
                }
            }
        }
    }
    // counts, not tolerances: enough overlapping pairs to test; the list
    // rebuilt now and then (more than twice), not every step (a fifth)
    EXPECT_GT(checked, 1000);
    EXPECT_GT(dem.work().broadPhaseBuilds, 2);
    EXPECT_LT(dem.work().broadPhaseBuilds, steps/5);
    std::cout << "overlapping pairs checked " << checked << ", neighbour list built "
              << dem.work().broadPhaseBuilds << " times in " << steps << " steps" << std::endl;
}


// Bodies close but apart (a packed bed): the DEM's filter rejects a pair
// whose gap it proves positive even below the engine's reach (the finest
// leaf's diagonal, within which the octree would be walked every
// sub-step), and keeps rejecting it by the motion bound while the bodies
// creep closer; once the surfaces cross, the engine measures the contact.
// Two tori (non-convex: the octree, not the convex path) stacked on their
// axis; the filter alone at the reach keeps the old behaviour
TEST(pairFilter, provenGapsBelowTheReachAreNotContacts)
{
    auto torus = std::make_shared<triangleMeshShape>
    (
        primitiveMeshes::torus(0.004, 0.0015, 24, 12), "torus"
    );
    contactMaterial glass{"glass", 1e7, 0.3, 0.5, 0.4};
    demSettings s;
    const double d = 2*std::cbrt(3*torus->volume()/(4*M_PI));
    s.overlap.h = overlapSettings::defaultCellSize(d);
    const double reach = pairFilter::engineReach("virtualMesh", s.overlap);

    // The height at which B's mesh touches A's (the exact engine)
    const auto exact = overlapEngine::New("exact");
    const bodyPose pA(vec3::Zero(), quat::Identity());
    // (tilted: the world boxes overlap, the broad phase keeps the pair)
    const quat qB = bodyPose::axisAngle(vec3(1, 0.2, 0), 0.6);
    double lo = 0.001, hi = 0.01;
    for (int i = 0; i < 60; ++i)
    {
        const double m = 0.5*(lo + hi);
        const bool overlap =
            exact->evaluate(*torus, pA, *torus, bodyPose(vec3(0, 0, m), qB), s.overlap).volume() > 0;
        (overlap ? lo : hi) = m;
    }
    const double zTouch = hi;

    demSolver dem({glass}, s);
    rigidBody A("A", torus, 2500);
    A.motion = motionType::fixed;
    dem.addBody(A);
    rigidBody B("B", torus, 2500);
    B.pose = bodyPose(vec3(0, 0, zTouch + 0.3*reach), qB);
    dem.addBody(B);

    // The filter at the reach alone lets the pair through to the engine
    pairFilter atReach;
    atReach.setReach(reach);
    atReach.beginSweep();
    EXPECT_FALSE(atReach.separated(0, 1, *torus, pA, *torus, B.pose));

    // The DEM: creeping down from 0.3 to 0.05 of the reach in 50 steps, no
    // contact, no engine call, one proof
    for (int k = 0; k <= 50; ++k)
    {
        dem.bodies()[1].pose = bodyPose(vec3(0, 0, zTouch + (0.3 - 0.005*k)*reach), qB);
        dem.bodiesChanged();
        dem.computeContacts();
        ASSERT_TRUE(dem.contacts().empty()) << "step " << k;
    }
    EXPECT_EQ(dem.work().pairEvaluations, 0);
    // one proof (two if the first is renewed), the other 48+ steps reuse it
    EXPECT_LE(dem.filterWork().proofs, 2);
    EXPECT_GE(dem.filterWork().rejectedByReuse, 48);

    // Crossed: the engine is asked and measures an overlap
    dem.bodies()[1].pose = bodyPose(vec3(0, 0, zTouch - 0.5*reach), qB);
    dem.computeContacts();
    EXPECT_EQ(dem.work().pairEvaluations, 1);
    ASSERT_FALSE(dem.contacts().empty());
    EXPECT_GT(dem.contacts()[0].region.volume, 0);
    EXPECT_GT(dem.filterWork().tested, 50);
    std::cout << "reach " << reach << " m; gap proofs " << dem.filterWork().proofs
              << ", rejected by reuse " << dem.filterWork().rejectedByReuse
              << "; overlap when crossed by half the reach " << dem.contacts()[0].region.volume
              << " m3" << std::endl;
}
