// The projection's plane path (issue 46, item 3): convexCells classifies
// cell centres against a convex body, or a union of convex pieces, by its
// face planes. Its signs and exact distances must be those of the
// triangle mesh's own queries (the path it replaces), its settled values
// true bounds beyond the reach, and its cell fractions the exact volume of
// the box inside the body.

#include "convexCells.H"
#include "triangleMeshShape.H"
#include "sphereShape.H"
#include "primitiveMeshes.H"
#include "overlapEngine.H"

#include "testHelpers.H"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

using namespace immersedDEM;

namespace
{

//- The packed bed's pellet: a 12-sided prism 3 mm across its corners and
//  3 mm long (immersedDEMPrism pellet.stl 3 3 12), in metres
std::unique_ptr<triangleMeshShape> pellet()
{
    std::vector<Eigen::Vector2d> poly;
    for (int i = 0; i < 12; ++i)
    {
        poly.emplace_back(1.5e-3*std::cos(2*M_PI*i/12), 1.5e-3*std::sin(2*M_PI*i/12));
    }
    return std::make_unique<triangleMeshShape>(primitiveMeshes::extrudedPolygon(poly, 3e-3), "pellet");
}

//- The packed bed's ring (immersedDEMPrism ring.stl 4 4 24 2): 26 convex
//  pieces
std::unique_ptr<triangleMeshShape> ring()
{
    return std::make_unique<triangleMeshShape>(primitiveMeshes::hollowCylinder(2e-3, 1e-3, 4e-3, 24), "ring");
}

double diameter(const shape& s)
{
    return std::cbrt(6*s.volume()/M_PI);
}


//- Plane classification against the mesh's closest-point query at random
//  poses, on jittered grid points around the body with random reaches
void compareWithMesh(const triangleMeshShape& s, int poses, unsigned seed)
{
    ASSERT_TRUE(convexCells::handles(s)) << s.name();
    std::mt19937 rng(seed);
    const double d = diameter(s);
    const double h = d/8;
    std::uniform_real_distribution<double> jitter(-0.3*h, 0.3*h), r(0.5*h, 1.5*h);
    long exact = 0, settled = 0;
    for (int k = 0; k < poses; ++k)
    {
        const bodyPose p(test::randomVec(rng, -d, d), test::randomQuat(rng));
        const convexCells planes(s, p);
        const axisAlignedBox b = s.worldBox(p);
        for (double x = b.min.x() - 2*h; x < b.max.x() + 2*h; x += h)
            for (double y = b.min.y() - 2*h; y < b.max.y() + 2*h; y += h)
                for (double z = b.min.z() - 2*h; z < b.max.z() + 2*h; z += h)
                {
                    const vec3 q(x + jitter(rng), y + jitter(rng), z + jitter(rng));
                    const double reach = r(rng);
                    const surfacePoint m = s.closest(p, q);
                    const narrowBand::value v = planes.classify(q, reach);
                    // Within round-off of the surface either sign is right
                    // (the mesh settles it by an exact predicate within
                    // 1e-9 of its size; the planes by their arithmetic)
                    if (std::abs(m.distance) > 1e-9*d)
                    {
                        ASSERT_EQ(v.phi < 0, m.distance < 0)
                            << s.name() << " at " << q.transpose() << ": planes " << v.phi
                            << ", mesh " << m.distance;
                    }
                    if (v.exact)
                    {
                        // Two exact distances in doubles: round-off of
                        // coordinates of size d is 1e-16 d; 1e-12 d leaves
                        // room for the planes' offsets, rotated
                        ASSERT_NEAR(v.phi, m.distance, 1e-12*d) << s.name() << " at " << q.transpose();
                        ASSERT_NEAR(v.sp.distance, m.distance, 1e-12*d);
                        ASSERT_LT((v.sp.point - m.point).norm(), 1e-6*d)
                            << "closest points differ (a tie between two faces would be "
                            << "equally near: the distances above agree)";
                        ++exact;
                    }
                    else
                    {
                        // Settled: the sign (above), beyond the reach, and
                        // a bound of the distance (no farther than it)
                        ASSERT_GT(std::abs(v.phi), reach);
                        ASSERT_LE(std::abs(v.phi), std::abs(m.distance) + 1e-12*d);
                        ++settled;
                    }
                    // What the projection needs: phi exact within reach
                    if (std::abs(m.distance) < reach - 1e-12*d)
                    {
                        ASSERT_TRUE(v.exact) << s.name() << " at " << q.transpose();
                    }
                }
    }
    EXPECT_GT(exact, 50*poses) << s.name();
    EXPECT_GT(settled, 50*poses) << s.name();
}

} // End anonymous namespace


TEST(convexCells, servesConvexMeshesAndBodiesOfConvexPieces)
{
    EXPECT_TRUE(convexCells::handles(*pellet()));
    EXPECT_TRUE(convexCells::handles(triangleMeshShape(primitiveMeshes::box(vec3(1, 2, 3)), "box")));
    const auto r = ring();
    ASSERT_FALSE(r->pieces().empty());
    EXPECT_TRUE(convexCells::handles(*r));
    // A curved non-convex mesh (no pieces), an analytic sphere, and a
    // convex mesh of more faces than a pass over its planes is worth:
    // the narrow band
    EXPECT_FALSE(convexCells::handles(*test::lumpyStar()));
    EXPECT_FALSE(convexCells::handles(sphereShape(1)));
    const triangleMeshShape fine(primitiveMeshes::icosphere(1, 3), "icosphere");
    ASSERT_TRUE(fine.convex());
    EXPECT_FALSE(convexCells::handles(fine));
    const sphereShape ball(1);
    EXPECT_TRUE(test::throwsCoreError([&] { const convexCells c(ball, bodyPose()); (void)c; }, {"convexCells"}));
}


TEST(convexCells, classifyAgreesWithTheMeshOfAPellet)
{
    compareWithMesh(*pellet(), 30, 1);
}


TEST(convexCells, classifyAgreesWithTheMeshOfABox)
{
    compareWithMesh(triangleMeshShape(primitiveMeshes::box(vec3(1e-3, 2e-3, 0.5e-3)), "box"), 30, 2);
}


TEST(convexCells, classifyAgreesWithTheMeshOfARingOfPieces)
{
    compareWithMesh(*ring(), 10, 3);
}


TEST(convexCells, fractionIsTheExactOverlapOfTheCellAndThePellet)
{
    // The reference: the exact intersection of two convex meshes
    // (convexOverlap), the cell as a box mesh (in mm: the surface check
    // refuses a box of 1e-10 m3 as collapsed)
    const auto P = pellet()->scaled(1e3, "pellet in mm");
    const double d = diameter(*P);
    const auto exact = overlapEngine::New("convex");
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> u(-1, 1);
    int cut = 0;
    for (const vec3 half : std::vector<vec3>{d*vec3(0.06, 0.06, 0.06), d*vec3(0.15, 0.05, 0.1), d*vec3(0.3, 0.3, 0.3)})
    {
        const triangleMeshShape cell(primitiveMeshes::box(half), "cell");
        for (int k = 0; k < 100; ++k)
        {
            const bodyPose p(vec3::Zero(), test::randomQuat(rng));
            const convexCells planes(*P, p);
            const vec3 c = 0.6*d*vec3(u(rng), u(rng), u(rng));
            const double f = planes.fraction(c - half, c + half);
            const double V = 8*half.prod();
            const double reference =
                exact->evaluate(cell, cell.poseFromFilePlacement(quat::Identity(), c), *P, p, {}).volume()/V;
            // Both exact clips in doubles; convexOverlap drops a sliver
            // thinner than 1e-12 of the radius, 1e-11 of these cells'
            // volume at most
            ASSERT_NEAR(f, reference, 1e-9) << "cell at " << c.transpose() << " half " << half.transpose();
            if (f > 1e-3 && f < 1 - 1e-3) ++cut;
        }
    }
    EXPECT_GT(cut, 60);
}


TEST(convexCells, cellsTileTheVolumeOfPelletBoxAndRing)
{
    // Exact fractions of cells tiling a box around the body add up to its
    // exact volume (the mass properties' to round-off: 1e-9 relative
    // covers the sum over some thousand cells)
    std::mt19937 rng(5);
    const auto P = pellet();
    const auto R = ring();
    const triangleMeshShape B(primitiveMeshes::box(vec3(1e-3, 2e-3, 0.5e-3)), "box");
    for (const triangleMeshShape* s : std::vector<const triangleMeshShape*>{P.get(), R.get(), &B})
    {
        for (const double n : {5.0, 8.0})
        {
            const double h = diameter(*s)/n;
            const bodyPose p(test::randomVec(rng, -h, h), test::randomQuat(rng));
            const convexCells planes(*s, p);
            const axisAlignedBox b = s->worldBox(p);
            double V = 0;
            for (double x = b.min.x() - 0.3*h; x < b.max.x(); x += h)
                for (double y = b.min.y() - 0.3*h; y < b.max.y(); y += h)
                    for (double z = b.min.z() - 0.3*h; z < b.max.z(); z += h)
                    {
                        const vec3 lo(x, y, z);
                        V += h*h*h*planes.fraction(lo, lo + vec3::Constant(h));
                    }
            EXPECT_NEAR(V/s->volume(), 1, 1e-9) << s->name() << " at d/" << n;
        }
    }
}
