// The projection's signed distances near the surface only (issue 20, item
// 5): narrowBand gives every cell centre within its reach of the surface
// its exact distance and closest point, every other the right sign, with
// far fewer queries than one per centre; boxFraction::given from a centre
// query is boxFraction::of.

#include "narrowBand.H"
#include "boxFraction.H"
#include "sphereShape.H"
#include "triangleMeshShape.H"
#include "primitiveMeshes.H"

#include "testHelpers.H"

#include <gtest/gtest.h>

#include <memory>
#include <random>

using namespace immersedDEM;

namespace
{

using test::lumpyStar;

// Cell centres of a grid of spacing h over the body's box grown by two
// cells, slightly jittered (a mesh is not a lattice), and their reach: the
// cell's half-diagonal, or a cell and a half
void grid
(
    const shape& s, const bodyPose& pose, double h, double reachFactor,
    std::vector<vec3>& x, std::vector<double>& reach
)
{
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> jitter(-0.05*h, 0.05*h);
    const axisAlignedBox b = s.worldBox(pose);
    for (double px = b.min.x() - 2*h; px < b.max.x() + 2*h; px += h)
        for (double py = b.min.y() - 2*h; py < b.max.y() + 2*h; py += h)
            for (double pz = b.min.z() - 2*h; pz < b.max.z() + 2*h; pz += h)
            {
                x.push_back(vec3(px + jitter(rng), py + jitter(rng), pz + jitter(rng)));
                reach.push_back(reachFactor*h);
            }
}

void expectBand(const shape& s, const bodyPose& pose, double h, double reachFactor, double maxQueryShare)
{
    std::vector<vec3> x;
    std::vector<double> reach;
    grid(s, pose, h, reachFactor, x, reach);
    long queries = 0;
    const auto band = narrowBand::signedDistances(s, pose, x, reach, &queries);
    ASSERT_EQ(band.size(), x.size());
    size_t near = 0;
    for (size_t i = 0; i < x.size(); ++i)
    {
        const surfacePoint exact = s.closest(pose, x[i]);
        if (std::abs(exact.distance) <= reach[i])
        {
            ++near;
            ASSERT_TRUE(band[i].exact) << "point " << i << " at " << exact.distance << " within reach " << reach[i];
        }
        if (band[i].exact)
        {
            EXPECT_EQ(band[i].phi, exact.distance) << "point " << i;
            EXPECT_EQ(band[i].sp.distance, exact.distance);
            EXPECT_LT((band[i].sp.point - exact.point).norm(), 1e-12);
        }
        else
        {
            EXPECT_GT(std::abs(band[i].phi), reach[i]);
            EXPECT_GT(band[i].phi*exact.distance, 0) << "point " << i << ": wrong side";
            EXPECT_GE(std::abs(exact.distance), std::abs(band[i].phi) - 1e-15);
        }
    }
    EXPECT_GT(near, 0u);
    std::printf("    %zu points, %zu within reach, %ld queries\n", x.size(), near, queries);
    EXPECT_LT(double(queries), maxQueryShare*double(x.size()))
        << queries << " queries for " << x.size() << " points, " << near << " near";
}

} // End anonymous namespace


TEST(narrowBand, lumpyStarAtEightCellsPerDiameter)
{
    const auto star = lumpyStar();
    const bodyPose p = star->poseFromFilePlacement(bodyPose::axisAngle(vec3(1, -2, 0.5), 1.1), vec3(0.01, -0.02, 0.3));
    // d = 10 mm; half-diagonal and a cell and a half (the sharp surface's
    // neighbours)
    expectBand(*star, p, 0.00125, 0.87, 0.45);
    expectBand(*star, p, 0.00125, 1.5, 0.6);
}


TEST(narrowBand, sphereAndIcosphere)
{
    const sphereShape s(0.005);
    expectBand(s, bodyPose(vec3(0.001, 0.002, -0.003), quat::Identity()), 0.0005, 0.87, 0.55);
    const triangleMeshShape ico(primitiveMeshes::icosphere(0.005, 3), "ico");
    expectBand(ico, ico.poseFromFilePlacement(bodyPose::axisAngle(vec3(0, 1, 1), 0.3), vec3::Zero()), 0.0005, 0.87, 0.3);
}


TEST(narrowBand, fewPointsAndCoincidentPoints)
{
    const sphereShape s(0.005);
    EXPECT_TRUE(narrowBand::signedDistances(s, bodyPose(), {}, {}).empty());
    // Twenty copies of one point on the surface: all exact
    const std::vector<vec3> x(20, vec3(0.005, 0, 0));
    const auto band = narrowBand::signedDistances(s, bodyPose(), x, std::vector<double>(20, 1e-4));
    for (const auto& v : band)
    {
        EXPECT_TRUE(v.exact);
        EXPECT_NEAR(v.phi, 0, 1e-15);
    }
}


TEST(boxFraction, givenACentreQueryIsOf)
{
    const auto star = lumpyStar();
    const bodyPose p = star->poseFromFilePlacement(bodyPose::axisAngle(vec3(0.3, 1, -1), 2.1), vec3::Zero());
    const double h = 0.00125;
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-0.006, 0.006);
    int cut = 0;
    for (int k = 0; k < 400; ++k)
    {
        const vec3 lo(u(rng), u(rng), u(rng));
        const vec3 hi = lo + vec3(h, 1.1*h, 0.9*h);
        const vec3 c = 0.5*(lo + hi);
        for (int levels = 0; levels <= 2; ++levels)
        {
            long qOf = 0, qGiven = 0;
            const double f = boxFraction::of(*star, p, lo, hi, levels, &qOf);
            const double g = boxFraction::given(*star, p, lo, hi, levels, c, star->closest(p, c), &qGiven);
            EXPECT_NEAR(g, f, 1e-14) << "box " << k << " levels " << levels;
            EXPECT_EQ(qGiven, qOf - 1);
            if (levels == 1 && f > 0 && f < 1) ++cut;
        }
        // From another point of the box: the same where it decides, and a
        // fraction in [0, 1] anyway; whole boxes stay whole
        const vec3 x = lo + 0.3*(hi - lo);
        const double g = boxFraction::given(*star, p, lo, hi, 1, x, star->closest(p, x));
        const double f = boxFraction::of(*star, p, lo, hi, 1);
        EXPECT_GE(g, 0);
        EXPECT_LE(g, 1);
        if (f == 0 || f == 1) EXPECT_EQ(g, f) << "box " << k;
        else EXPECT_NEAR(g, f, 1e-12) << "box " << k;
    }
    EXPECT_GT(cut, 20);
}
