// Reading and writing STL (ASCII, binary) and OBJ, and every read error.

#include "surfaceFileIO.H"
#include "massProperties.H"
#include "primitiveMeshes.H"
#include "triangleMeshShape.H"
#include "testHelpers.H"

#include <cstdio>
#include <filesystem>
#include <fstream>

using namespace immersedDEM;
using namespace immersedDEM::test;

namespace
{

std::string tmpFile(const std::string& name)
{
    return testing::TempDir() + "immersedDEM_testSurfaceFileIO_" + name;
}

std::string writeText(const std::string& name, const std::string& text)
{
    const std::string f = tmpFile(name);
    std::ofstream os(f, std::ios::binary);
    os << text;
    return f;
}

const char* tetraSTL =
    "solid tet\n"
    "facet normal 0 0 -1\n outer loop\n  vertex 0 0 0\n  vertex 0 1 0\n  vertex 1 0 0\n endloop\nendfacet\n"
    "facet normal 0 -1 0\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n  vertex 0 0 1\n endloop\nendfacet\n"
    "facet normal -1 0 0\n outer loop\n  vertex 0 0 0\n  vertex 0 0 1\n  vertex 0 1 0\n endloop\nendfacet\n"
    "FACET NORMAL 1 1 1\n OUTER LOOP\n  VERTEX 1 0 0\n  VERTEX 0 1 0\n  VERTEX 0 0 1\n ENDLOOP\nENDFACET\n"
    "endsolid tet\n";

} // End anonymous namespace


TEST(surfaceFileIO, roundTripIcosphere)
{
    const triangleSoup ball = primitiveMeshes::icosphere(0.01, 3);
    const double V = massProperties::of(ball).volume;

    struct fmt { std::string name; bool ascii; double tol; };
    for (const fmt& f :
    {
        fmt{"ball_ascii.stl", true, 1e-6},
        fmt{"ball_binary.stl", false, 1e-6},
        fmt{"ball.obj", false, 1e-12},
        fmt{"ball_upper.OBJ", false, 1e-12},
        fmt{"ball_upper.STL", false, 1e-6}
    })
    {
        const std::string file = tmpFile(f.name);
        surfaceFileIO::write(file, ball, f.ascii);
        const triangleSoup back = surfaceFileIO::read(file);
        // Coincident points are merged back into an indexed surface
        EXPECT_EQ(back.points.size(), ball.points.size()) << f.name;
        EXPECT_EQ(back.faces.size(), ball.faces.size()) << f.name;
        EXPECT_LT(relErr(massProperties::of(back).volume, V), f.tol) << f.name;

        // And a body can be made from it
        const auto shape = triangleMeshShape::fromFile(file);
        EXPECT_LT(relErr(shape->volume(), V), f.tol) << f.name;
        EXPECT_TRUE(shape->warnings().empty()) << f.name;
        // No temporary left behind
        EXPECT_FALSE(std::ifstream(file + ".tmp").good()) << f.name;
        std::remove(file.c_str());
    }
}


TEST(surfaceFileIO, binarySTLIsSinglePrecisionAndSized)
{
    const triangleSoup ball = primitiveMeshes::icosphere(1.0, 2);
    const std::string file = tmpFile("sized.stl");
    surfaceFileIO::write(file, ball);
    std::ifstream is(file, std::ios::binary | std::ios::ate);
    EXPECT_EQ(std::streamoff(is.tellg()), std::streamoff(84 + 50*ball.faces.size()));
    const triangleSoup back = surfaceFileIO::read(file);
    double maxDiff = 0;
    for (const triFace& f : back.faces)
    {
        for (int v : f) maxDiff = std::max(maxDiff, std::abs(back.points[v].norm() - 1.0));
    }
    EXPECT_LT(maxDiff, 1e-7);
    std::remove(file.c_str());
}


TEST(surfaceFileIO, asciiSTLTetrahedron)
{
    const std::string file = writeText("tet.stl", tetraSTL);
    const triangleSoup s = surfaceFileIO::read(file);
    EXPECT_EQ(s.points.size(), 4u);
    EXPECT_EQ(s.faces.size(), 4u);
    EXPECT_NEAR(massProperties::of(s).volume, 1.0/6.0, 1e-15);
    EXPECT_NEAR((massProperties::of(s).centroid - vec3::Constant(0.25)).norm(), 0.0, 1e-15);
    std::remove(file.c_str());
}


TEST(surfaceFileIO, objQuadsAndNegativeIndices)
{
    // Unit cube [0,1]^3: quads, some faces by negative (relative) indices,
    // with texture/normal indices and records that carry no geometry
    const std::string file = writeText
    (
        "cube.obj",
        "# a cube\n"
        "mtllib none.mtl\n"
        "o cube\n"
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
        "v 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
        "vn 0 0 1\nvt 0 0\n"
        "g sides\n"
        "f 1/1/1 4/1/1 3/1/1 2/1/1\n"     // -z
        "f -4 -3 -2 -1\n"                 // +z: 5 6 7 8
        "f 1//1 2//1 6//1 5//1\n"         // -y
        "f -5 -1 -2 -6\n"                 // +y: 4 8 7 3
        "s off\n"
        "f 1 5 8 4\n"                     // -x
        "f 2 3 7 6\n"                     // +x
    );
    const triangleSoup s = surfaceFileIO::read(file);
    EXPECT_EQ(s.points.size(), 8u);
    EXPECT_EQ(s.faces.size(), 12u);
    const massProperties mp = massProperties::of(s);
    EXPECT_NEAR(mp.volume, 1.0, 1e-15);
    EXPECT_NEAR((mp.centroid - vec3::Constant(0.5)).norm(), 0.0, 1e-15);
    EXPECT_NEAR(mp.principalMoments[0], 1.0/6.0, 1e-15);

    const triangleMeshShape shape(s, file);
    EXPECT_TRUE(shape.warnings().empty());
    std::remove(file.c_str());
}


TEST(surfaceFileIO, missingFile)
{
    const std::string file = tmpFile("does_not_exist.stl");
    EXPECT_TRUE(throwsCoreError([&]{ surfaceFileIO::read(file); }, {file, "cannot be opened"}));
    const std::string obj = tmpFile("does_not_exist.obj");
    EXPECT_TRUE(throwsCoreError([&]{ surfaceFileIO::read(obj); }, {obj, "cannot be opened"}));
    EXPECT_TRUE(throwsCoreError([&]{ triangleMeshShape::fromFile(obj); }, {obj}));
}


TEST(surfaceFileIO, unknownExtension)
{
    const std::string file = writeText("tet.ply", tetraSTL);
    EXPECT_TRUE(throwsCoreError
    (
        [&]{ surfaceFileIO::read(file); }, {file, "unknown extension 'ply'", ".stl and .obj"}
    ));
    const std::string noExt = writeText("noext", tetraSTL);
    EXPECT_TRUE(throwsCoreError([&]{ surfaceFileIO::read(noExt); }, {"unknown extension ''"}));
    // A dot in a directory name is not an extension
    EXPECT_TRUE(throwsCoreError
    (
        [&]{ surfaceFileIO::read(testing::TempDir() + "dir.stl/noext"); }, {"unknown extension ''"}
    ));
    EXPECT_TRUE(throwsCoreError
    (
        [&]{ surfaceFileIO::write(tmpFile("out.vtk"), primitiveMeshes::box(vec3::Ones())); },
        {"unknown extension 'vtk'"}
    ));
    // A refused write leaves no file behind, not even its temporary
    EXPECT_FALSE(std::ifstream(tmpFile("out.vtk")).good());
    EXPECT_FALSE(std::ifstream(tmpFile("out.vtk") + ".tmp").good());
    std::remove(file.c_str());
    std::remove(noExt.c_str());
    std::remove((tmpFile("out.vtk") + ".tmp").c_str());
}


TEST(surfaceFileIO, asciiSTLMalformed)
{
    struct bad { std::string text; std::string line; std::string what; };
    const std::string head = "solid x\nfacet normal 0 0 1\n outer loop\n";
    for (const bad& b :
    {
        bad{head + "  vertex 0 0 0\n  vertex 1 0 zero\n", "line 5", "cannot read the numbers"},
        bad{head + "  vertex 0 0 0\n  vertex 1 0\n", "line 5", "three numbers"},
        bad{head + "  vertex 0 0 0\n  vertex 1 0 0.5x\n", "line 5", "cannot read the numbers"},
        bad{head + "  vertex 0 0 0\n  vertex 1 0 inf\n", "line 5", "non-finite"},
        bad{head + "  vertex 0 0 0\n  vertex 1 0 0\n endloop\nendfacet\n", "line 7", "3 vertices"},
        bad{head + "  vertex 0 0 0\n  vertex 1 0 0\n  vertex 0 1 0\n  vertex 0 0 1\n", "line 7", "more than 3"},
        bad{head + "  vertex 0 0 0\n  vertex 1 0 0\n  vertex 0 1 0\n endloop\nfacet\n", "line 8", "inside a facet"},
        bad{head + "  vertex 0 0 0\n  vertex 1 0 0\n  vertex 0 1 0\n", "line 6", "ends inside a facet"},
        bad{"solid x\n  vertex 0 0 0\n", "line 2", "outside a facet"},
        bad{"solid x\nfoo bar\n", "line 2", "unexpected 'foo'"}
    })
    {
        const std::string file = writeText("bad.stl", b.text);
        EXPECT_TRUE(throwsCoreError([&]{ surfaceFileIO::read(file); }, {file, b.line, b.what}))
            << b.text;
        std::remove(file.c_str());
    }
}


TEST(surfaceFileIO, objMalformed)
{
    struct bad { std::string text; std::string line; std::string what; };
    for (const bad& b :
    {
        bad{"v 0 0 0\nv 1 0\nf 1 2 3\n", "line 2", "three finite numbers"},
        bad{"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "line 4", "index 4 out of range"},
        bad{"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n", "line 4", "out of range"},
        bad{"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "line 4", "out of range"},
        bad{"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", "line 4", "at least 3"},
        bad{"v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 a 2\n", "line 5", "vertex index 'a'"}
    })
    {
        const std::string file = writeText("bad.obj", b.text);
        EXPECT_TRUE(throwsCoreError([&]{ surfaceFileIO::read(file); }, {file, b.line, b.what}))
            << b.text;
        std::remove(file.c_str());
    }
}


TEST(surfaceFileIO, noTriangles)
{
    const std::string stl = writeText("empty.stl", "solid empty\nendsolid empty\n");
    EXPECT_TRUE(throwsCoreError([&]{ surfaceFileIO::read(stl); }, {stl, "contains no triangles"}));
    const std::string obj = writeText("empty.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    EXPECT_TRUE(throwsCoreError([&]{ surfaceFileIO::read(obj); }, {obj, "contains no triangles"}));

    // A binary STL with zero triangles (84 bytes, count 0)
    const std::string bin = tmpFile("emptybin.stl");
    {
        std::ofstream os(bin, std::ios::binary);
        const std::string header(80, 'x');
        os.write(header.data(), 80);
        const std::uint32_t n = 0;
        os.write(reinterpret_cast<const char*>(&n), 4);
    }
    EXPECT_TRUE(throwsCoreError([&]{ surfaceFileIO::read(bin); }, {bin, "contains no triangles"}));
    std::remove(stl.c_str());
    std::remove(obj.c_str());
    std::remove(bin.c_str());
}


TEST(surfaceFileIO, neitherAsciiNorBinary)
{
    const std::string file = tmpFile("garbage.stl");
    {
        std::ofstream os(file, std::ios::binary);
        const std::string junk(100, '\x01');
        os.write(junk.data(), std::streamsize(junk.size()));
    }
    EXPECT_TRUE(throwsCoreError
    (
        [&]{ surfaceFileIO::read(file); }, {file, "neither ASCII STL", "nor binary STL"}
    ));
    // Short text not starting with 'solid'
    const std::string txt = writeText("text.stl", "hello world\n");
    EXPECT_TRUE(throwsCoreError([&]{ surfaceFileIO::read(txt); }, {txt, "neither"}));
    std::remove(file.c_str());
    std::remove(txt.c_str());
}


TEST(surfaceFileIO, binarySTLTruncatedOrNonFinite)
{
    // A binary STL whose header starts with 'solid' is still binary (by size)
    const triangleSoup box = primitiveMeshes::box(vec3(1, 2, 3));
    const std::string file = tmpFile("solidheader.stl");
    surfaceFileIO::write(file, box);
    {
        std::fstream fs(file, std::ios::in | std::ios::out | std::ios::binary);
        fs.write("solid box", 9);
    }
    const triangleSoup back = surfaceFileIO::read(file);
    EXPECT_EQ(back.faces.size(), 12u);
    EXPECT_EQ(back.points.size(), 8u);
    EXPECT_NEAR(massProperties::of(back).volume, 48.0, 1e-12);

    // A NaN coordinate in triangle 3
    {
        std::fstream fs(file, std::ios::in | std::ios::out | std::ios::binary);
        fs.seekp(84 + 3*50 + 12 + 4);
        const float nan = std::nanf("");
        fs.write(reinterpret_cast<const char*>(&nan), 4);
    }
    EXPECT_TRUE(throwsCoreError
    (
        [&]{ surfaceFileIO::read(file); }, {file, "triangle 3", "non-finite"}
    ));
    std::remove(file.c_str());
}


TEST(surfaceFileIO, mergeCoincidentPoints)
{
    triangleSoup s;
    s.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {-0.0, 0, 0}};
    s.faces = {{0, 1, 2}, {3, 5, 4}, {6, 3, 4}};
    surfaceFileIO::mergeCoincidentPoints(s);
    ASSERT_EQ(s.points.size(), 4u);
    EXPECT_EQ(s.faces[0], (triFace{0, 1, 2}));
    EXPECT_EQ(s.faces[1], (triFace{1, 3, 2}));
    EXPECT_EQ(s.faces[2], (triFace{0, 1, 2}));      // -0 is 0
    EXPECT_EQ(s.points[3], vec3(1, 1, 0));
}


// Issue 17: a directory given as the file was "neither ASCII nor binary STL"
TEST(surfaceFileIO, directoryIsNotAFile)
{
    const std::string dir = tmpFile("folder.stl");
    std::filesystem::create_directories(dir);
    EXPECT_TRUE(throwsCoreError([&]{ surfaceFileIO::read(dir); }, {dir, "is a directory, not a file"}));
    EXPECT_TRUE(throwsCoreError([&]{ surfaceFileIO::read(dir + "/"); }, {"is a directory"}));
    // Without an extension: the directory, not the extension, is named
    const std::string plain = tmpFile("folder");
    std::filesystem::create_directories(plain);
    EXPECT_TRUE(throwsCoreError([&]{ surfaceFileIO::read(plain); }, {"is a directory, not a file"}));
}
