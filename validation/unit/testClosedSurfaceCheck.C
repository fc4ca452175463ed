// Every error and repair of closedSurfaceCheck::checkAndRepair, through
// triangleMeshShape (as a user meets them) and directly.

#include "closedSurfaceCheck.H"
#include "triangleMeshShape.H"
#include "primitiveMeshes.H"
#include "surfaceFileIO.H"
#include "massProperties.H"
#include "testHelpers.H"

using namespace immersedDEM;
using namespace immersedDEM::test;

namespace
{

// Box [lo, lo + 2h]
triangleSoup boxAt(const vec3& lo, const vec3& h)
{
    triangleSoup s = primitiveMeshes::box(h);
    primitiveMeshes::transform(s, mat3::Identity(), lo + h);
    return s;
}

triangleSoup merged(const triangleSoup& a, const triangleSoup& b)
{
    triangleSoup s = concat(a, b);
    surfaceFileIO::mergeCoincidentPoints(s);
    return s;
}

::testing::AssertionResult shapeThrows
(
    const triangleSoup& s,
    std::initializer_list<std::string> substrings
)
{
    return throwsCoreError([&]{ triangleMeshShape shape(s, "body.stl"); }, substrings);
}

bool contains(const std::string& s, const std::string& sub)
{
    return s.find(sub) != std::string::npos;
}

} // End anonymous namespace


TEST(closedSurfaceCheck, closedBoxPasses)
{
    triangleSoup s = primitiveMeshes::box(vec3(1, 2, 3));
    const triangleSoup before = s;
    const std::vector<std::string> w = closedSurfaceCheck::checkAndRepair(s, "box");
    EXPECT_TRUE(w.empty());
    EXPECT_EQ(s.faces, before.faces);
    EXPECT_EQ(closedSurfaceCheck::countSelfIntersections(s), 0);
}


TEST(closedSurfaceCheck, noTriangles)
{
    EXPECT_TRUE(shapeThrows(triangleSoup(), {"Surface \"body.stl\"", "contains no triangles"}));

    // Only triangles with a repeated corner: all dropped, then none left
    triangleSoup s;
    s.points = {{0, 0, 0}, {1, 0, 0}};
    s.faces = {{0, 0, 1}, {1, 1, 1}};
    EXPECT_TRUE(shapeThrows(s, {"contains no triangles"}));
}


TEST(closedSurfaceCheck, openSurface)
{
    const triangleSoup box = primitiveMeshes::box(vec3(1, 0.5, 0.25));

    // One triangle removed: its 3 edges become border edges
    triangleSoup one = box;
    one.faces.erase(one.faces.begin() + 5);
    EXPECT_TRUE(shapeThrows(one, {"Surface \"body.stl\" is not closed: 3 border edges"}));

    // Both triangles of one side: the 4 edges of the square hole
    triangleSoup side = box;
    side.faces.erase(side.faces.begin(), side.faces.begin() + 2);
    EXPECT_TRUE(shapeThrows(side, {"is not closed: 4 border edges"}));

    // Two triangles sharing no edge (faces 0 and 2: sides -x and +x)
    triangleSoup two = box;
    two.faces.erase(two.faces.begin() + 2);
    two.faces.erase(two.faces.begin());
    EXPECT_TRUE(shapeThrows(two, {"is not closed: 6 border edges"}));

    // A single triangle
    triangleSoup tri;
    tri.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    tri.faces = {{0, 1, 2}};
    EXPECT_TRUE(shapeThrows(tri, {"is not closed: 3 border edges"}));
}


TEST(closedSurfaceCheck, nonManifoldEdge)
{
    // Two unit cubes sharing the edge x = y = 1, z in [0, 1]
    const triangleSoup s = merged
    (
        boxAt(vec3(0, 0, 0), vec3::Constant(0.5)),
        boxAt(vec3(1, 1, 0), vec3::Constant(0.5))
    );
    ASSERT_EQ(s.points.size(), 14u);
    EXPECT_TRUE(shapeThrows
    (
        s, {"Surface \"body.stl\" is non-manifold: 1 edges are shared by more than two"}
    ));

    // A box with a closed fin: a flat double triangle glued along an edge
    triangleSoup fin = primitiveMeshes::box(vec3::Constant(0.5));
    // Box corners 1 = (+,-,-) and 3 = (+,+,-) share a box edge
    fin.points.emplace_back(2, 0, -0.5);
    fin.faces.push_back({1, 3, 8});
    fin.faces.push_back({3, 1, 8});
    EXPECT_TRUE(shapeThrows(fin, {"is non-manifold: 1 edges are shared by more than two"}));
}


TEST(closedSurfaceCheck, nonManifoldVertex)
{
    // Two unit cubes touching at the corner (1, 1, 1)
    const triangleSoup s = merged
    (
        boxAt(vec3(0, 0, 0), vec3::Constant(0.5)),
        boxAt(vec3(1, 1, 1), vec3::Constant(0.5))
    );
    ASSERT_EQ(s.points.size(), 15u);
    EXPECT_TRUE(shapeThrows
    (
        s, {"Surface \"body.stl\" is non-manifold: 1 vertices join surface sheets"}
    ));

    // Two tetrahedra sharing their apex... and a third: still one vertex
    triangleSoup t;
    t.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}};
    t.faces =
    {
        {0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3},
        {0, 4, 5}, {0, 6, 4}, {0, 5, 6}, {4, 6, 5}
    };
    EXPECT_TRUE(shapeThrows(t, {"is non-manifold: 1 vertices join"}));
}


TEST(closedSurfaceCheck, notOrientable)
{
    // The 6-vertex triangulation of the projective plane: closed, manifold,
    // not orientable (the check is topological, before any geometry)
    triangleSoup s;
    for (int i = 0; i < 6; ++i)
    {
        s.points.emplace_back(std::cos(i), std::sin(i), 0.1*i*i);
    }
    s.faces =
    {
        {0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}, {0, 5, 1},
        {1, 2, 4}, {2, 3, 5}, {3, 4, 1}, {4, 5, 2}, {5, 1, 3}
    };
    EXPECT_TRUE(shapeThrows(s, {"Surface \"body.stl\" is not orientable"}));
}


TEST(closedSurfaceCheck, selfIntersecting)
{
    // Two closed boxes overlapping in one soup
    const triangleSoup s = concat
    (
        primitiveMeshes::box(vec3::Constant(0.5)),
        boxAt(vec3(0, -0.2, -0.3), vec3::Constant(0.5))
    );
    EXPECT_TRUE(shapeThrows
    (
        s, {"Surface \"body.stl\" is self-intersecting: ", "pairs of triangles intersect"}
    ));
    const long n = closedSurfaceCheck::countSelfIntersections(s);
    EXPECT_GT(n, 0);
    EXPECT_LT(n, 1000);
    EXPECT_EQ(closedSurfaceCheck::countSelfIntersections(s, 3), 3);

    // The exact message carries the count
    triangleSoup copy = s;
    EXPECT_TRUE(throwsCoreError
    (
        [&]{ closedSurfaceCheck::checkAndRepair(copy, "x"); },
        {"is self-intersecting: " + std::to_string(n) + " pairs"}
    ));

    // Without the check it is accepted (as two shells)
    const triangleMeshShape unchecked(s, "overlap", false);
    EXPECT_NEAR(unchecked.volume(), 2.0, 1e-12);

    // Two disjoint boxes: one body of two shells, no intersection
    const triangleSoup apart = concat
    (
        primitiveMeshes::box(vec3::Constant(0.5)),
        boxAt(vec3(3, 0, 0), vec3::Constant(0.5))
    );
    const triangleMeshShape two(apart, "two");
    EXPECT_NEAR(two.volume(), 2.0, 1e-12);
    EXPECT_TRUE(two.warnings().empty());
}


TEST(closedSurfaceCheck, zeroVolume)
{
    // A flat pillow: a square covered twice, back to back (the two sides
    // split along different diagonals, so every edge has two triangles)
    triangleSoup pillow;
    pillow.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    pillow.faces = {{0, 1, 2}, {0, 2, 3}, {1, 0, 3}, {1, 3, 2}};

    // A single triangle, both sides
    triangleSoup leaf;
    leaf.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    leaf.faces = {{0, 1, 2}, {0, 2, 1}};
    EXPECT_TRUE(shapeThrows(leaf, {"encloses zero volume (flat or collapsed surface)"}));
    EXPECT_TRUE(shapeThrows(pillow, {"Surface \"body.stl\" encloses zero volume"}));

    // A tetrahedron with its four corners in one plane
    triangleSoup flat;
    flat.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.3, 0.3, 0}};
    flat.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    EXPECT_TRUE(shapeThrows(flat, {"encloses zero volume"}));

    // A box squashed to a height far below 1e-12 of its size, rotated
    triangleSoup thin = primitiveMeshes::box(vec3(1, 1, 1e-14));
    primitiveMeshes::transform(thin, bodyPose::axisAngle(vec3(1, 2, 3), 0.5).toRotationMatrix(), vec3(1, 1, 1));
    EXPECT_TRUE(shapeThrows(thin, {"encloses zero volume"}));
}


TEST(closedSurfaceCheck, degenerateTrianglesDropped)
{
    triangleSoup s = primitiveMeshes::box(vec3(1, 2, 3));
    s.faces.push_back({0, 0, 1});
    s.faces.push_back({2, 5, 2});
    const triangleMeshShape shape(s, "withDegenerate");
    EXPECT_EQ(shape.nTriangles(), 12u);
    ASSERT_EQ(shape.warnings().size(), 1u);
    EXPECT_TRUE(contains(shape.warnings()[0], "Surface \"withDegenerate\": dropped 2 degenerate"))
        << shape.warnings()[0];
    EXPECT_NEAR(shape.volume(), 48.0, 1e-12);
}


TEST(closedSurfaceCheck, inconsistentOrientationRepaired)
{
    const vec3 h(1, 0.5, 0.25);
    const double V = 8*h.prod();
    for (int flipped : {0, 7, 11})
    {
        triangleSoup s = primitiveMeshes::box(h);
        std::swap(s.faces[flipped][1], s.faces[flipped][2]);
        // Uncorrected, the volume would be wrong
        EXPECT_GT(std::abs(massProperties::signedVolume(s) - V), 0.1*V);

        const triangleMeshShape shape(s, "oneFlipped");
        EXPECT_LT(relErr(shape.volume(), V), 1e-12) << "flipped " << flipped;
        EXPECT_LT(relErr(shape.principalMoments()[2], V/3*(1 + 0.25)), 1e-12);
        // The walk keeps the orientation of its seed, triangle 0: when that
        // is the odd one, the other 11 are turned and the shell, now
        // inward, is turned outwards with a second warning
        ASSERT_EQ(shape.warnings().size(), flipped == 0 ? 2u : 1u) << "flipped " << flipped;
        if (flipped == 0)
        {
            EXPECT_TRUE(contains(shape.warnings()[1], "inward orientation repaired"));
        }
        const std::string& w = shape.warnings()[0];
        EXPECT_TRUE(contains(w, "Surface \"oneFlipped\"")) << w;
        EXPECT_TRUE(contains(w, "inconsistent")) << w;
        EXPECT_TRUE(contains(w, "(1 triangles turned)")) << w;
        // The repaired surface is consistent and outward
        EXPECT_LT(relErr(massProperties::signedVolume(shape.surface()), V), 1e-12);
        EXPECT_TRUE(shape.inside(vec3::Zero()));
        EXPECT_NEAR(shape.signedDistance(vec3::Zero()), -0.25, 1e-12);
    }
}


TEST(closedSurfaceCheck, inwardOrientationRepaired)
{
    const vec3 h(1, 0.5, 0.25);
    const double V = 8*h.prod();
    triangleSoup s = primitiveMeshes::box(h);
    for (triFace& f : s.faces) std::swap(f[1], f[2]);
    ASSERT_LT(massProperties::signedVolume(s), 0);

    const triangleMeshShape shape(s, "inward");
    EXPECT_GT(shape.volume(), 0);
    EXPECT_LT(relErr(shape.volume(), V), 1e-12);
    ASSERT_EQ(shape.warnings().size(), 1u);
    EXPECT_TRUE(contains(shape.warnings()[0], "inward orientation repaired (1 of 1 shells"))
        << shape.warnings()[0];
    EXPECT_TRUE(shape.inside(vec3::Zero()));
    EXPECT_NEAR(shape.signedDistance(vec3(2, 0, 0)), 1.0, 1e-12);
    EXPECT_NEAR(shape.signedDistance(vec3::Zero()), -0.25, 1e-12);

    // Two shells, one inward and one with an inconsistent triangle
    triangleSoup a = boxAt(vec3(5, 0, 0), h);
    for (triFace& f : a.faces) std::swap(f[1], f[2]);
    triangleSoup b = primitiveMeshes::box(h);
    std::swap(b.faces[3][1], b.faces[3][2]);
    const triangleMeshShape both(concat(a, b), "both");
    EXPECT_LT(relErr(both.volume(), 2*V), 1e-12);
    ASSERT_EQ(both.warnings().size(), 2u);
    EXPECT_TRUE(contains(both.warnings()[0], "inconsistent")) << both.warnings()[0];
    EXPECT_TRUE(contains(both.warnings()[1], "inward orientation repaired (1 of 2 shells"))
        << both.warnings()[1];
}


// Issue 17: a hollow body (a cavity) was counted twice, 1.125 for the
// hollow 0.875: nested shells are rejected with the shell count
TEST(closedSurfaceCheck, nestedShellsRejected)
{
    const triangleSoup outer = primitiveMeshes::box(vec3::Constant(0.5));
    const triangleSoup inner = primitiveMeshes::box(vec3::Constant(0.25));

    // The inner shell facing inwards (a correctly oriented cavity)
    triangleSoup cavity = inner;
    for (triFace& f : cavity.faces) std::swap(f[1], f[2]);
    EXPECT_TRUE(shapeThrows
    (
        concat(outer, cavity),
        {"Surface \"body.stl\" has nested shells: 2 closed shells, 1 of them inside another",
         "cavity is not supported"}
    ));

    // Facing outwards: the same error, not a silent sum of the volumes
    EXPECT_TRUE(shapeThrows(concat(outer, inner), {"has nested shells: 2 closed shells, 1 of"}));

    // Inner shell first in the file, off centre, and a third shell nested
    // in it: two inside another
    triangleSoup small = primitiveMeshes::box(vec3::Constant(0.05));
    primitiveMeshes::transform(small, mat3::Identity(), vec3(0.1, 0, 0));
    EXPECT_TRUE(shapeThrows
    (
        concat(concat(inner, outer), small), {"has nested shells: 3 closed shells, 2 of them"}
    ));

    // Side by side is still one body of two shells
    EXPECT_NO_THROW(triangleMeshShape(merged(outer, boxAt(vec3(2, 0, 0), vec3::Constant(0.25))), "two"));

    // The winding test directly: shell 1 inside shell 0
    const triangleSoup s = concat(outer, inner);
    std::vector<int> shell(s.faces.size(), 0);
    for (size_t i = outer.faces.size(); i < s.faces.size(); ++i) shell[i] = 1;
    const std::vector<int> in = closedSurfaceCheck::enclosingShells(s, shell, 2);
    EXPECT_EQ(in[0], -1);
    EXPECT_EQ(in[1], 0);
}


// Issue 17: a vertex at 1e300 was reported as "encloses zero volume"
TEST(closedSurfaceCheck, coordinateOutOfRange)
{
    triangleSoup s = primitiveMeshes::box(vec3::Constant(0.5));
    s.points[3].x() = 1e300;
    EXPECT_TRUE(shapeThrows(s, {"Surface \"body.stl\": vertex 3 (1e+300", "out of range", "1e+12"}));
    s.points[3].x() = -2e12;
    EXPECT_TRUE(shapeThrows(s, {"vertex 3 (-2e+12", "out of range"}));
    // At the limit: accepted as far as the range goes (a thin sliver body)
    s.points[3].x() = 1e12;
    EXPECT_NO_THROW(closedSurfaceCheck::checkCoordinateRange(s, "body.stl"));
}
