/*---------------------------------------------------------------------------*\
Description
    Tests of non-convex bodies as unions of convex pieces
    (convexDecomposition, pieceOverlap through virtualMeshOverlap): the
    decomposition of a Raschig ring and a trilobe is exact (the pieces'
    volumes add up to the body's), a curved torus is refused with its
    reason; and their contacts against CGAL's exact intersection of the
    whole meshes (exactOverlap) at 200 random poses per pair: ring-ring,
    rings linked through the hole, trilobe-trilobe, ring-prism and a ring
    on a plane. The decomposition is the same, bit for bit, in every run
    (each run of a program lays out its heap at other addresses, and CGAL's
    orders follow them).

    Tolerances: volume and centroid 1e-9 (relative), the target:
    both sides are exact up to the rounding of the intersection points to
    doubles (about 1e-16 of the size), summed over tens of pieces and
    hundreds of faces. The area vector S 1e-8: the reference's S assigns
    each face of CGAL's intersection to A or B by the surface nearer its
    centroid, and at the worst ring-ring pose (69 of seed 1) it differs
    from the central difference of the volume by 4.3e-9 of |S| where the
    pieces' S differs by 5.4e-10 (step 1e-8 m).
\*---------------------------------------------------------------------------*/

#include "convexDecomposition.H"
#include "exactOverlap.H"
#include "halfSpaceShape.H"
#include "pieceOverlap.H"
#include "primitiveMeshes.H"
#include "triangleMeshShape.H"
#include "virtualMeshOverlap.H"
#include "testHelpers.H"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <random>
#include <string>
#include <unistd.h>

using namespace immersedDEM;

namespace
{

const double mm = 0.001;

// The catalyst ring of the issue: 4 x 2 x 4 mm, 24 segments
triangleMeshShape ring()
{
    return triangleMeshShape(primitiveMeshes::hollowCylinder(2*mm, 1*mm, 4*mm, 24), "ring");
}


// Totals over the regions: volume, first moment, area vector S
struct totals
{
    double V = 0;
    vec3 first = vec3::Zero();
    vec3 S = vec3::Zero();
    size_t regions = 0;
};

totals sum(const contactGeometry& g)
{
    totals t;
    for (const contactRegion& r : g.regions)
    {
        t.V += r.volume;
        t.first += r.volume*r.point;
        // (the exact engine gives S as area and normal)
        t.S += r.areaVector.norm() > 0 ? r.areaVector : vec3(r.area*r.normal);
    }
    t.regions = g.regions.size();
    return t;
}


// The pieces' contact against the exact one of the whole meshes at n
// random poses of B about A (distance of the centres a fraction f of the
// bounding radii's sum); returns the number of poses in contact
int compareAtRandomPoses
(
    const triangleMeshShape& A, const triangleMeshShape& B,
    const shape* exactB,            // B for the exact engine (default B)
    int n, double fLo, double fHi, unsigned seed,
    const std::function<bodyPose(std::mt19937&)>& poseOfB = {}
)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> f(fLo, fHi);
    const double reach = A.boundingRadius() + B.boundingRadius();
    // A's file frame placed at (qA, tA); B placed in A's file frame
    const quat qA = test::randomRotation(rng);
    const vec3 tA(0.1, -0.2, 0.3);
    const bodyPose pA = A.poseFromFilePlacement(qA, tA);
    int touching = 0;
    for (int k = 0; k < n; ++k)
    {
        bodyPose pB;
        if (poseOfB)
        {
            const bodyPose inA = poseOfB(rng);
            pB = B.poseFromFilePlacement(qA*inA.orientation(), tA + qA*inA.position());
        }
        else
        {
            pB = bodyPose(pA.position() + f(rng)*reach*test::randomDirection(rng), test::randomRotation(rng));
        }
        const totals e = sum(exactOverlap().evaluate(A, pA, exactB ? *exactB : B, pB, {}));
        const contactGeometry pg = virtualMeshOverlap().evaluate(A, pA, B, pB, {0.2*mm, 4});
        const totals p = sum(pg);
        EXPECT_EQ(pg.leaves, 0) << "pose " << k << ": the octree was used";
        const double V = std::max(e.V, 1e-30);
        EXPECT_NEAR(p.V, e.V, 1e-9*V) << "pose " << k;
        if (e.V > 0)
        {
            ++touching;
            EXPECT_LT((p.first/p.V - e.first/e.V).norm(), 1e-9*A.boundingRadius()) << "pose " << k;
            EXPECT_LT((p.S - e.S).norm(), 1e-8*std::max(e.S.norm(), std::cbrt(V)*std::cbrt(V)))
                << "pose " << k;
            EXPECT_EQ(p.regions, e.regions) << "pose " << k;
        }
    }
    return touching;
}

} // End anonymous namespace


TEST(pieceOverlap, ringAndTrilobeDecomposeExactly)
{
    const triangleMeshShape R = ring();
    ASSERT_EQ(R.convex(), nullptr);
    ASSERT_FALSE(R.pieces().empty()) << R.piecesNote();
    // 24 reflex edges (the bore's); at least one piece per segment
    EXPECT_GE(R.pieces().size(), 24u);
    EXPECT_LE(R.pieces().size(), size_t(convexDecomposition::defaultMaxPieces));
    double V = 0;
    for (size_t i = 0; i < R.pieces().size(); ++i)
    {
        const auto& p = R.pieces()[i];
        EXPECT_NE(p->convex(), nullptr) << i;
        V += p->volume();
        // The ring's pieces form a closed chain: each has two neighbours
        // at least, and neighbourhood is mutual
        EXPECT_GE(R.pieceNeighbours(int(i)).size(), 2u) << i;
        for (const int j : R.pieceNeighbours(int(i)))
        {
            const auto& nj = R.pieceNeighbours(j);
            EXPECT_NE(std::find(nj.begin(), nj.end(), int(i)), nj.end()) << i << " " << j;
        }
    }
    // The 24-gon annulus times the height
    const double exact = 12*std::sin(2*M_PI/24)*(4 - 1)*4*mm*mm*mm;
    EXPECT_NEAR(R.volume(), exact, 1e-12*exact);
    EXPECT_NEAR(V, exact, 1e-9*exact);

    const triangleMeshShape T(primitiveMeshes::lobed(3, 0.8*mm, 0.9*mm, 4*mm, 48), "trilobe");
    ASSERT_EQ(T.convex(), nullptr);
    EXPECT_GE(T.pieces().size(), 3u) << T.piecesNote();
    double VT = 0;
    for (const auto& p : T.pieces()) VT += p->volume();
    EXPECT_NEAR(VT, T.volume(), 1e-9*T.volume());

    // A scaled copy keeps its pieces, scaled
    const auto R2 = R.scaled(1.1, "ring x 1.1");
    ASSERT_EQ(R2->pieces().size(), R.pieces().size());
    double V2 = 0;
    for (const auto& p : R2->pieces()) V2 += p->volume();
    EXPECT_NEAR(V2, 1.331*exact, 1e-9*exact);
}


// A digest of every bit of a decomposition's pieces, their order and
// their neighbours, and of a union's surface
std::string digest(const convexDecomposition& d, const triangleSoup& u)
{
    std::uint64_t h = 1469598103934665603ull;
    auto add = [&h](const void* p, size_t n)
    {
        const auto* c = static_cast<const unsigned char*>(p);
        for (size_t i = 0; i < n; ++i) h = (h ^ c[i])*1099511628211ull;
    };
    auto addSoup = [&](const triangleSoup& s)
    {
        for (const vec3& x : s.points) add(x.data(), 3*sizeof(double));
        for (const triFace& f : s.faces) add(f.data(), sizeof(f));
    };
    for (const triangleSoup& p : d.pieces) addSoup(p);
    for (const auto& n : d.neighbours) for (const int j : n) add(&j, sizeof(j));
    addSoup(u);
    return std::to_string(d.pieces.size()) + " pieces, digest " + std::to_string(h);
}


TEST(pieceOverlap, decompositionIsTheSameInEveryRun)
{
    // In a child: print the digest of a ring's and a trilobe's
    // decompositions and of a union of three boxes
    if (std::getenv("IMMERSEDDEM_PRINT_DECOMPOSITION"))
    {
        const triangleSoup none;
        std::printf("ring: %s\n", digest(convexDecomposition::of(primitiveMeshes::hollowCylinder(2*mm, 1*mm, 4*mm, 24), 64), none).c_str());
        const triangleSoup lobes = primitiveMeshes::lobed(3, 0.8*mm, 0.9*mm, 4*mm, 48);
        std::printf("trilobe: %s\n", digest(convexDecomposition::of(lobes, 64), none).c_str());
        std::vector<triangleSoup> parts;
        for (int i = 0; i < 3; ++i)
        {
            triangleSoup b = primitiveMeshes::box(vec3(1*mm, 0.5*mm, (1 + 0.3*i)*mm));
            for (vec3& x : b.points) x.x() += 2*i*mm;
            parts.push_back(b);
        }
        triangleSoup u;
        const convexDecomposition d = convexDecomposition::ofParts(parts, u);
        std::printf("parts: %s\n", digest(d, u).c_str());
        return;
    }
    // Three runs of this test program in children: a program's heap
    // lies at other addresses in each run (address space layout
    // randomisation), where CGAL's orders of corners, faces and pieces
    // follow the addresses (seen: four digests in four runs)
    std::vector<std::string> out;
    for (int run = 0; run < 3; ++run)
    {
        const std::string command =
            "IMMERSEDDEM_PRINT_DECOMPOSITION=1 /proc/" + std::to_string(getpid())
          + "/exe --gtest_filter=pieceOverlap.decompositionIsTheSameInEveryRun 2>&1";
        FILE* f = popen(command.c_str(), "r");
        ASSERT_NE(f, nullptr);
        std::string text;
        char line[512];
        while (std::fgets(line, sizeof line, f))
        {
            if (!std::strncmp(line, "ring:", 5) || !std::strncmp(line, "trilobe:", 8) || !std::strncmp(line, "parts:", 6))
            {
                text += line;
            }
        }
        ASSERT_EQ(pclose(f), 0) << text;
        out.push_back(text);
    }
    ASSERT_NE(out[0].find("parts:"), std::string::npos) << out[0];
    EXPECT_EQ(out[1], out[0]);
    EXPECT_EQ(out[2], out[0]);
}


TEST(pieceOverlap, curvedOrConvexOrSwitchedOffStayWhole)
{
    // A faceted torus: every edge of its inner half folds inwards
    const triangleMeshShape torus(primitiveMeshes::torus(4*mm, 1*mm, 48, 24), "torus");
    EXPECT_TRUE(torus.pieces().empty());
    EXPECT_NE(torus.piecesNote().find("reflex edges"), std::string::npos) << torus.piecesNote();
    // A convex prism needs no pieces
    const triangleMeshShape prism(primitiveMeshes::hollowCylinder(2*mm, 1*mm, 4*mm, 24), "ring", true, 0);
    EXPECT_TRUE(prism.pieces().empty());
    EXPECT_EQ(prism.piecesNote(), "not convex, not decomposed");
    const halfSpaceShape plane;
    EXPECT_FALSE(pieceOverlap::handles(torus, plane));
    EXPECT_FALSE(pieceOverlap::handles(prism, plane));
    EXPECT_TRUE(pieceOverlap::handles(ring(), plane));
    EXPECT_TRUE(pieceOverlap::handles(plane, ring()));
}


TEST(pieceOverlap, ringRingAgainstExact)
{
    const triangleMeshShape R = ring();
    const int touching = compareAtRandomPoses(R, R, nullptr, 200, 0.3, 1.0, 1);
    EXPECT_GT(touching, 100);
}


TEST(pieceOverlap, linkedRingsThroughTheHole)
{
    // A thin ring (4 x 3 x 0.8 mm) whose wall passes through the big
    // ring's bore, its axis across the big ring's: contacts on the bore's
    // inside only, or on both sides of the thin ring's wall
    const triangleMeshShape R = ring();
    const triangleMeshShape thin
    (
        primitiveMeshes::hollowCylinder(2*mm, 1.5*mm, 0.8*mm, 24), "thin ring"
    );
    std::uniform_real_distribution<double> u(-1, 1);
    auto linked = [&](std::mt19937& rng)
    {
        // The thin ring's axis along y (rotated about x), its wall's
        // middle (radius 1.75 mm) through the bore's axis, jittered
        const quat q = quat(Eigen::AngleAxisd(M_PI/2 + 0.3*u(rng), vec3::UnitX()))
                      *quat(Eigen::AngleAxisd(0.3*u(rng), vec3::UnitZ()));
        const vec3 c(1.75*mm + 0.45*mm*u(rng), 0.45*mm*u(rng), 1.5*mm*u(rng));
        return bodyPose(c, q);
    };
    const int touching = compareAtRandomPoses(R, thin, nullptr, 200, 0, 0, 2, linked);
    EXPECT_GT(touching, 100);
}


TEST(pieceOverlap, trilobeTrilobeAndRingPrismAgainstExact)
{
    const triangleMeshShape T(primitiveMeshes::lobed(3, 0.8*mm, 0.9*mm, 4*mm, 48), "trilobe");
    EXPECT_GT(compareAtRandomPoses(T, T, nullptr, 200, 0.3, 1.0, 3), 100);
    std::vector<Eigen::Vector2d> hexagon;
    for (int i = 0; i < 12; ++i)
    {
        hexagon.emplace_back(1.5*mm*std::cos(M_PI*i/6), 1.5*mm*std::sin(M_PI*i/6));
    }
    const triangleMeshShape prism(primitiveMeshes::extrudedPolygon(hexagon, 3*mm), "prism");
    ASSERT_NE(prism.convex(), nullptr);
    EXPECT_GT(compareAtRandomPoses(ring(), prism, nullptr, 200, 0.3, 1.0, 4), 100);
}


TEST(pieceOverlap, ringOnAPlaneAgainstExact)
{
    // The plane z = 0 of the world (solid below); for the exact engine a
    // big box whose top face is that plane
    const triangleMeshShape R = ring();
    triangleSoup s = primitiveMeshes::box(vec3(0.1, 0.1, 0.05));
    primitiveMeshes::transform(s, mat3::Identity(), vec3(0, 0, -0.05));
    const triangleMeshShape slab(s, "slab");
    const halfSpaceShape plane;
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> depth(-0.3, 1.0);
    int touching = 0;
    for (int k = 0; k < 200; ++k)
    {
        const quat q = test::randomRotation(rng);
        const bodyPose p0(vec3::Zero(), q);
        // The ring's lowest point, then lowered by a fraction of a mm
        double low = 1;
        for (const vec3& x : R.surface().points) low = std::min(low, p0.toWorld(x).z());
        const bodyPose p(vec3(0.001, 0.002, -low - depth(rng)*mm), q);
        const totals e = sum
        (
            exactOverlap().evaluate
            (
                R, p, slab, slab.poseFromFilePlacement(quat::Identity(), vec3::Zero()), {}
            )
        );
        for (const bool ringFirst : {true, false})
        {
            const contactGeometry g = ringFirst
                ? virtualMeshOverlap().evaluate(R, p, plane, bodyPose(), {0.2*mm, 4})
                : virtualMeshOverlap().evaluate(plane, bodyPose(), R, p, {0.2*mm, 4});
            const totals t = sum(g);
            EXPECT_EQ(g.leaves, 0);
            EXPECT_NEAR(t.V, e.V, 1e-9*std::max(e.V, 1e-30)) << k;
            if (e.V > 0)
            {
                EXPECT_LT((t.S - (ringFirst ? 1 : -1)*e.S).norm(), 1e-9*e.S.norm()) << k;
                EXPECT_EQ(t.regions, e.regions) << k;
            }
        }
        touching += e.V > 0;
    }
    EXPECT_GT(touching, 100);
}


TEST(pieceOverlap, areaMomentIsTheRotationGradient)
{
    // The pair's M about its centroid, sum (M_r + (x_r - x) x S_r) over the
    // regions, against the central difference of the volume when B turns
    // about that point: the potential law's couple is w'(V) M, so an
    // error in M breaks its energy. Pieces that a slab of the other
    // crosses whole have S = 0 but not M. Tolerance 1e-6 of |M|: the
    // central difference's own error at a step of 1e-7 rad (8e-8 at worst,
    // measured on these poses)
    const triangleMeshShape R = ring();
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> f(0.3, 0.9);
    const virtualMeshOverlap vm;
    const overlapSettings s{0.2*mm, 4};
    int checked = 0;
    for (int k = 0; k < 40; ++k)
    {
        const bodyPose pA(vec3::Zero(), test::randomRotation(rng));
        const bodyPose pB(f(rng)*2*R.boundingRadius()*test::randomDirection(rng), test::randomRotation(rng));
        const contactGeometry g = vm.evaluate(R, pA, R, pB, s);
        if (g.regions.empty()) continue;
        vec3 c = vec3::Zero();
        for (const contactRegion& r : g.regions) c += r.volume*r.point;
        c /= g.volume();
        vec3 M = vec3::Zero();
        for (const contactRegion& r : g.regions) M += r.areaMoment + (r.point - c).cross(r.areaVector);
        vec3 fd;
        const double h = 1e-7;
        for (int i = 0; i < 3; ++i)
        {
            auto turned = [&](double a)
            {
                const quat q(Eigen::AngleAxisd(a, vec3::Unit(i)));
                return vm.evaluate(R, pA, R, bodyPose(c + q*(pB.position() - c), q*pB.orientation()), s).volume();
            };
            fd[i] = (turned(h) - turned(-h))/(2*h);
        }
        // (turning B by +a about c changes V by -M.a)
        EXPECT_LT((fd + M).norm(), 1e-6*M.norm()) << "pose " << k;
        ++checked;
    }
    EXPECT_GT(checked, 30);
}


namespace
{

// The ring as 24 convex wedges (segment i between angles 2 pi i/24 and
// 2 pi (i+1)/24, its chords straight): closed, outward-oriented parts
std::vector<triangleSoup> ringWedges(int n)
{
    std::vector<triangleSoup> parts;
    const double R = 2*mm, r = 1*mm, h = 4*mm;
    for (int i = 0; i < n; ++i)
    {
        triangleSoup s;
        for (const int k : {i, (i + 1) % n})
        {
            // (k mod n: the last wedge ends exactly where the first starts)
            const double t = 2*M_PI*k/n, c = std::cos(t), z = std::sin(t);
            s.points.emplace_back(R*c, R*z, -h/2);  // 0, 4: outer bottom
            s.points.emplace_back(R*c, R*z, h/2);   // 1, 5: outer top
            s.points.emplace_back(r*c, r*z, -h/2);  // 2, 6: inner bottom
            s.points.emplace_back(r*c, r*z, h/2);   // 3, 7: inner top
        }
        s.faces =
        {
            {0, 4, 5}, {0, 5, 1},       // outer side
            {2, 3, 7}, {2, 7, 6},       // inner side
            {1, 5, 7}, {1, 7, 3},       // top
            {0, 2, 6}, {0, 6, 4},       // bottom
            {0, 1, 3}, {0, 3, 2},       // the side at angle i
            {4, 6, 7}, {4, 7, 5}        // the side at angle i + 1
        };
        parts.push_back(s);
    }
    return parts;
}

} // End anonymous namespace


TEST(pieceOverlap, bodyGivenAsConvexParts)
{
    // The ring given as 24 convex wedges: the body's surface is their
    // union, its volume the annulus', its pieces the wedges; its contacts
    // against CGAL's exact intersection of the union at 100 random poses
    const auto R = triangleMeshShape::fromParts(ringWedges(24), "wedge ring");
    ASSERT_EQ(R->pieces().size(), 24u) << R->piecesNote();
    const double exact = 12*std::sin(2*M_PI/24)*(4 - 1)*4*mm*mm*mm;
    EXPECT_NEAR(R->volume(), exact, 1e-9*exact);
    for (int i = 0; i < 24; ++i)
    {
        // Each wedge shares a side with the two next to it
        EXPECT_EQ(R->pieceNeighbours(i).size(), 2u) << i;
    }
    EXPECT_GT(compareAtRandomPoses(*R, *R, nullptr, 100, 0.3, 1.0, 6), 50);

    // A part that is not convex, and parts that overlap: errors that say so
    std::vector<triangleSoup> bad = ringWedges(24);
    bad[3] = primitiveMeshes::hollowCylinder(2*mm, 1*mm, 4*mm, 24);
    EXPECT_TRUE(test::throwsCoreError
    (
        [&]{ triangleMeshShape::fromParts(bad, "bad"); }, {"part 4 is not convex"}
    ));
    std::vector<triangleSoup> twice = ringWedges(24);
    twice.push_back(twice[0]);
    EXPECT_TRUE(test::throwsCoreError
    (
        [&]{ triangleMeshShape::fromParts(twice, "twice"); }, {"the parts overlap"}
    ));
}
