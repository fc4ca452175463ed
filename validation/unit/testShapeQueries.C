// Inside/outside, signed distance and closest point of triangleMeshShape
// against exact polyhedra (box, extruded L), including points within 1e-9
// of the surface, and of sphereShape against the analytic sphere.

#include "triangleMeshShape.H"
#include "sphereShape.H"
#include "primitiveMeshes.H"
#include "triangleBVH.H"
#include "testHelpers.H"

#include <thread>

using namespace immersedDEM;
using namespace immersedDEM::test;

namespace
{

const vec3 boxH(1.0, 0.5, 0.25);
const double LH = 0.7;
const std::vector<Eigen::Vector2d> Lpolygon =
{
    {0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 3}, {0, 3}
};

const triangleMeshShape& boxShape()
{
    static const triangleMeshShape s(primitiveMeshes::box(boxH), "box");
    return s;
}

const triangleMeshShape& LShape()
{
    static const triangleMeshShape s(primitiveMeshes::extrudedPolygon(Lpolygon, LH), "L");
    return s;
}

// File-frame queries through the body frame
bool insideFile(const shape& s, const vec3& x)
{
    return s.inside(s.bodyInFile(), x);
}

double sdFile(const shape& s, const vec3& x)
{
    return s.signedDistance(s.bodyInFile(), x);
}

// Distance to an axis-aligned (possibly flat) box [lo, hi]
double distToBox(const vec3& p, const vec3& lo, const vec3& hi)
{
    return (p - p.cwiseMax(lo).cwiseMin(hi)).norm();
}

// Exact signed distance of the extruded L: unsigned distance to its boundary
// (2 x 2 rectangles top and bottom, 6 side rectangles), sign from membership
double LSignedDistance(const vec3& p)
{
    const vec3 Alo(0, 0, 0), Ahi(2, 1, LH), Blo(0, 1, 0), Bhi(1, 3, LH);
    double d = std::numeric_limits<double>::max();
    for (double z : {0.0, LH})
    {
        d = std::min(d, distToBox(p, vec3(Alo.x(), Alo.y(), z), vec3(Ahi.x(), Ahi.y(), z)));
        d = std::min(d, distToBox(p, vec3(Blo.x(), Blo.y(), z), vec3(Bhi.x(), Bhi.y(), z)));
    }
    const size_t n = Lpolygon.size();
    for (size_t i = 0; i < n; ++i)
    {
        const Eigen::Vector2d& a = Lpolygon[i];
        const Eigen::Vector2d& b = Lpolygon[(i + 1) % n];
        d = std::min
        (
            d,
            distToBox
            (
                p,
                vec3(std::min(a.x(), b.x()), std::min(a.y(), b.y()), 0),
                vec3(std::max(a.x(), b.x()), std::max(a.y(), b.y()), LH)
            )
        );
    }
    const auto inBox = [&](const vec3& lo, const vec3& hi)
    {
        return (p.array() >= lo.array()).all() && (p.array() <= hi.array()).all();
    };
    return inBox(Alo, Ahi) || inBox(Blo, Bhi) ? -d : d;
}

// Points at +-eps from the box surface on faces, near edges and at corners:
// (point, expected inside)
std::vector<std::pair<vec3, bool>> nearBoxSurface(double eps, std::mt19937& gen)
{
    std::vector<std::pair<vec3, bool>> pts;
    std::uniform_real_distribution<double> u(-1, 1);
    for (int axis = 0; axis < 3; ++axis)
    {
        for (int sgn : {-1, 1})
        {
            for (int k = 0; k < 20; ++k)
            {
                // Face interior, including very close to its edges
                vec3 q(u(gen), u(gen), u(gen));
                if (k < 5) q[(axis + 1) % 3] = (k % 2 ? 1 : -1)*(1 - 1e-7);
                vec3 p = q.cwiseProduct(boxH);
                p[axis] = sgn*boxH[axis];
                vec3 out = p; out[axis] += sgn*eps;
                vec3 in = p; in[axis] -= sgn*eps;
                pts.push_back({out, false});
                pts.push_back({in, true});
            }
        }
    }
    // Edges and corners: out beyond two or three faces, in inside all
    for (int c = 0; c < 8; ++c)
    {
        const vec3 s((c & 1) ? 1 : -1, (c & 2) ? 1 : -1, (c & 4) ? 1 : -1);
        const vec3 corner = s.cwiseProduct(boxH);
        pts.push_back({corner + eps*s, false});
        pts.push_back({corner - eps*s, true});
        for (int axis = 0; axis < 3; ++axis)
        {
            // Along the edge parallel to 'axis' through this corner
            vec3 e = corner;
            e[axis] *= u(gen);
            vec3 dir = s; dir[axis] = 0;
            pts.push_back({e + eps*dir, false});
            pts.push_back({e - eps*dir, true});
            // Just past one face of the edge only: outside
            vec3 one = e - eps*dir;
            one[(axis + 1) % 3] += 2*eps*s[(axis + 1) % 3];
            pts.push_back({one, false});
        }
    }
    return pts;
}

} // End anonymous namespace


TEST(shapeQueries, boxSignedDistanceExact)
{
    const triangleMeshShape& s = boxShape();
    std::mt19937 gen(1);
    for (int i = 0; i < 3000; ++i)
    {
        const vec3 x = randomVec(gen, -2, 2).cwiseProduct(boxH);
        const double exact = boxSignedDistance(x, vec3::Zero(), boxH);
        EXPECT_NEAR(sdFile(s, x), exact, 1e-12) << x.transpose();
        EXPECT_EQ(insideFile(s, x), exact <= 0) << x.transpose();
    }
    // Far away
    EXPECT_NEAR(sdFile(s, vec3(10, 0, 0)), 9.0, 1e-12);
    EXPECT_NEAR(sdFile(s, vec3(11, 3.5, -4.25)), std::sqrt(100.0 + 9.0 + 16.0), 1e-12);
    // Centre: the nearest face is z = 0.25
    EXPECT_NEAR(sdFile(s, vec3::Zero()), -0.25, 1e-12);
}


TEST(shapeQueries, boxNearSurface)
{
    const triangleMeshShape& s = boxShape();
    std::mt19937 gen(2);
    for (const double eps : {1e-9, 1e-7, 1e-5})
    {
        for (const auto& pe : nearBoxSurface(eps, gen))
        {
            const vec3& x = pe.first;
            const double exact = boxSignedDistance(x, vec3::Zero(), boxH);
            ASSERT_EQ(exact <= 0, pe.second) << "test point construction " << x.transpose();
            EXPECT_EQ(insideFile(s, x), pe.second) << "eps " << eps << " at " << x.transpose();
            const double d = sdFile(s, x);
            if (pe.second) EXPECT_LT(d, 0) << "eps " << eps << " at " << x.transpose();
            else EXPECT_GT(d, 0) << "eps " << eps << " at " << x.transpose();
            EXPECT_NEAR(d, exact, 1e-12) << "eps " << eps << " at " << x.transpose();
        }
    }
}


TEST(shapeQueries, onSurfaceCountsAsInside)
{
    for (const triangleMeshShape* s : {&boxShape(), &LShape()})
    {
        const triangleSoup body = s->surface();
        for (const vec3& v : body.points)
        {
            EXPECT_TRUE(s->inside(v)) << s->name() << " vertex " << v.transpose();
            EXPECT_LE(s->signedDistance(v), 0.0);
            EXPECT_NEAR(s->signedDistance(v), 0.0, 1e-15);
        }
    }
    // Body-frame box: the principal frame of an axis-aligned box found
    // exactly, so face and edge points can be written exactly
    const triangleMeshShape& b = boxShape();
    const vec3 h = 0.5*b.localBox().span();
    ASSERT_NEAR((h - boxH).norm(), 0.0, 1e-14);
    const triangleSoup body = b.surface();
    bool axisAligned = true;
    for (const vec3& v : body.points)
    {
        axisAligned = axisAligned && (v.cwiseAbs() - b.localBox().max).norm() == 0;
    }
    if (axisAligned)
    {
        const vec3 H = b.localBox().max;
        for (const vec3& p :
        {
            vec3(H.x(), 0.1, 0.05), vec3(-H.x(), -0.3, 0.2), vec3(0.5, H.y(), 0),
            vec3(0, 0, -H.z()), vec3(H.x(), H.y(), 0.1), vec3(0.3, -H.y(), H.z())
        })
        {
            EXPECT_TRUE(b.inside(p)) << p.transpose();
            EXPECT_NEAR(b.signedDistance(p), 0.0, 1e-15) << p.transpose();
        }
    }
    else
    {
        ADD_FAILURE() << "body frame of an axis-aligned box centred at 0 is not exact";
    }
}


TEST(shapeQueries, extrudedLSignedDistanceExact)
{
    const triangleMeshShape& s = LShape();
    std::mt19937 gen(3);
    std::uniform_real_distribution<double> ux(-0.5, 2.5), uy(-0.5, 3.5), uz(-0.4, LH + 0.4);
    int nIn = 0;
    for (int i = 0; i < 3000; ++i)
    {
        const vec3 x(ux(gen), uy(gen), uz(gen));
        const double exact = LSignedDistance(x);
        EXPECT_NEAR(sdFile(s, x), exact, 1e-12) << x.transpose();
        EXPECT_EQ(insideFile(s, x), exact <= 0) << x.transpose();
        nIn += exact <= 0;
    }
    EXPECT_GT(nIn, 300);

    // In the notch, the nearest feature is the reflex edge x = y = 1
    EXPECT_NEAR(sdFile(s, vec3(1.3, 1.4, 0.2)), 0.3, 1e-12);
    EXPECT_NEAR(sdFile(s, vec3(1.3, 1.3, 0.2)), 0.3, 1e-12);
    // Inside near the reflex edge: nearest is the edge itself, or a face
    EXPECT_NEAR(sdFile(s, vec3(0.9, 0.8, 0.35)), -std::sqrt(0.05), 1e-12);
    EXPECT_NEAR(sdFile(s, vec3(1.2, 0.8, 0.35)), -0.2, 1e-12);
    EXPECT_NEAR(sdFile(s, vec3(0.8, 1.1, 0.35)), -0.2, 1e-12);
}


TEST(shapeQueries, extrudedLNearSurface)
{
    const triangleMeshShape& s = LShape();
    std::mt19937 gen(4);
    std::uniform_real_distribution<double> u(0, 1);
    for (const double eps : {1e-9, 1e-7})
    {
        std::vector<std::pair<vec3, bool>> pts;
        for (int k = 0; k < 30; ++k)
        {
            const double z = LH*u(gen);
            // Reflex edge (1, 1, z): the notch side is outside
            pts.push_back({vec3(1 + eps, 1 + eps, z), false});
            pts.push_back({vec3(1 - eps, 1 + eps, z), true});
            pts.push_back({vec3(1 + eps, 1 - eps, z), true});
            pts.push_back({vec3(1 - eps, 1 - eps, z), true});
            // Convex edge (2, 0, z)
            pts.push_back({vec3(2 + eps, -eps, z), false});
            pts.push_back({vec3(2 - eps, eps, z), true});
            pts.push_back({vec3(2 - eps, -eps, z), false});
            // Faces
            const double t = u(gen);
            pts.push_back({vec3(1 + eps, 1 + 2*t, z), false});       // x = 1, y in [1,3]
            pts.push_back({vec3(1 - eps, 1 + 2*t, z), true});
            pts.push_back({vec3(1 + t, 1 + eps, z), false});         // y = 1, x in [1,2]
            pts.push_back({vec3(1 + t, 1 - eps, z), true});
            pts.push_back({vec3(0.5*t, 2.5*t, LH + eps), false});   // top
            pts.push_back({vec3(0.5*t, 2.5*t, LH - eps), true});
            pts.push_back({vec3(2*t, 0.5, -eps), false});            // bottom
            pts.push_back({vec3(2*t, 0.5, eps), true});
        }
        // Corners at the reflex edge's ends and a convex corner
        pts.push_back({vec3(1 + eps, 1 + eps, LH + eps), false});
        pts.push_back({vec3(1 - eps, 1 - eps, LH - eps), true});
        pts.push_back({vec3(1 + eps, 1 + eps, -eps), false});
        pts.push_back({vec3(1 + eps, 1 - eps, eps), true});
        pts.push_back({vec3(0, 3, 0) + eps*vec3(-1, 1, -1), false});
        pts.push_back({vec3(0, 3, 0) + eps*vec3(1, -1, 1), true});

        for (const auto& pe : pts)
        {
            const vec3& x = pe.first;
            ASSERT_EQ(LSignedDistance(x) <= 0, pe.second) << "construction " << x.transpose();
            EXPECT_EQ(insideFile(s, x), pe.second) << "eps " << eps << " at " << x.transpose();
            const double d = sdFile(s, x);
            if (pe.second) EXPECT_LT(d, 0) << "eps " << eps << " at " << x.transpose();
            else EXPECT_GT(d, 0) << "eps " << eps << " at " << x.transpose();
            EXPECT_NEAR(d, LSignedDistance(x), 1e-12) << x.transpose();
        }
    }
}


TEST(shapeQueries, boxClosestPointAndNormal)
{
    const triangleMeshShape& s = boxShape();
    const bodyPose& P = s.bodyInFile();

    // Outside a face
    surfacePoint sp = s.closest(P, vec3(1.5, 0.1, 0.05));
    EXPECT_NEAR((sp.point - vec3(1, 0.1, 0.05)).norm(), 0.0, 1e-12);
    EXPECT_NEAR((sp.normal - vec3(1, 0, 0)).norm(), 0.0, 1e-12);
    EXPECT_NEAR(sp.distance, 0.5, 1e-12);

    // Inside, nearest face -y
    sp = s.closest(P, vec3(0.2, -0.4, 0.0));
    EXPECT_NEAR((sp.point - vec3(0.2, -0.5, 0)).norm(), 0.0, 1e-12);
    EXPECT_NEAR((sp.normal - vec3(0, -1, 0)).norm(), 0.0, 1e-12);
    EXPECT_NEAR(sp.distance, -0.1, 1e-12);

    // Outside an edge: the normal points from the edge to the query
    sp = s.closest(P, vec3(1.3, 0.9, 0.0));
    EXPECT_NEAR((sp.point - vec3(1, 0.5, 0)).norm(), 0.0, 1e-12);
    EXPECT_NEAR((sp.normal - vec3(0.6, 0.8, 0)).norm(), 0.0, 1e-12);
    EXPECT_NEAR(sp.distance, 0.5, 1e-12);

    // Outside a corner
    sp = s.closest(P, vec3(-1.1, -0.7, 0.45));
    EXPECT_NEAR((sp.point - vec3(-1, -0.5, 0.25)).norm(), 0.0, 1e-12);
    EXPECT_NEAR((sp.normal - vec3(-0.1, -0.2, 0.2).normalized()).norm(), 0.0, 1e-12);
    EXPECT_NEAR(sp.distance, 0.3, 1e-12);

    // On the face (within 1e-12): the face normal
    sp = s.closest(P, vec3(0.3, 0.2, 0.25 + 1e-12));
    EXPECT_NEAR((sp.normal - vec3(0, 0, 1)).norm(), 0.0, 1e-9);
    EXPECT_NEAR((sp.point - vec3(0.3, 0.2, 0.25)).norm(), 0.0, 1e-12);

    // Consistency for random points: distance = |x - point| with the sign
    std::mt19937 gen(5);
    for (int i = 0; i < 500; ++i)
    {
        const vec3 x = randomVec(gen, -2, 2);
        const surfacePoint q = s.closest(P, x);
        EXPECT_NEAR(std::abs(q.distance), (x - q.point).norm(), 1e-12);
        EXPECT_NEAR(q.normal.norm(), 1.0, 1e-12);
        EXPECT_NEAR(q.distance, boxSignedDistance(x, vec3::Zero(), boxH), 1e-12);
        EXPECT_NEAR(boxSignedDistance(q.point, vec3::Zero(), boxH), 0.0, 1e-12);
        // x = point + distance*normal
        EXPECT_NEAR((q.point + q.distance*q.normal - x).norm(), 0.0, 1e-11);
    }
}


TEST(shapeQueries, sphereAnalytic)
{
    const double R = 0.3;
    const sphereShape s(R);
    EXPECT_EQ(s.type(), "sphere");
    EXPECT_EQ(s.radius(), R);
    EXPECT_EQ(s.boundingRadius(), R);
    EXPECT_EQ(s.localBox().min, vec3::Constant(-R));
    EXPECT_EQ(s.localBox().max, vec3::Constant(R));
    EXPECT_NEAR(s.volume(), 4.0/3.0*M_PI*R*R*R, 1e-15);
    EXPECT_NEAR(s.principalMoments()[1], 0.4*s.volume()*R*R, 1e-18);

    // Exactly on the surface: inside
    EXPECT_TRUE(s.inside(vec3(R, 0, 0)));
    EXPECT_TRUE(s.inside(vec3(0, 0, -R)));
    EXPECT_FALSE(s.inside(vec3(R*(1 + 1e-12), 0, 0)));
    EXPECT_TRUE(s.inside(vec3(0, R*(1 - 1e-12), 0)));
    EXPECT_EQ(s.signedDistance(vec3(0, R, 0)), 0.0);

    std::mt19937 gen(6);
    for (int i = 0; i < 1000; ++i)
    {
        const vec3 x = randomVec(gen, -2*R, 2*R);
        EXPECT_EQ(s.inside(x), x.norm() <= R);
        EXPECT_NEAR(s.signedDistance(x), x.norm() - R, 1e-15);
        const surfacePoint sp = s.closest(x);
        EXPECT_NEAR((sp.point - R*x.normalized()).norm(), 0.0, 1e-15);
        EXPECT_NEAR((sp.normal - x.normalized()).norm(), 0.0, 1e-15);
        EXPECT_NEAR(sp.distance, x.norm() - R, 1e-15);
    }
    // At the centre: +x by convention
    const surfacePoint c = s.closest(vec3::Zero());
    EXPECT_EQ(c.normal, vec3::UnitX());
    EXPECT_EQ(c.point, vec3(R, 0, 0));
    EXPECT_EQ(c.distance, -R);

    // Output surface: an icosphere of radius R (level 3)
    const triangleSoup surf = s.surface();
    EXPECT_EQ(surf.faces.size(), 20u*64u);
    for (const vec3& p : surf.points) EXPECT_NEAR(p.norm(), R, 1e-15);
}


TEST(shapeQueries, sphereVersusFineIcosphere)
{
    // The mesh inscribed in the sphere: distances agree to the chordal error
    const double R = 1.0;
    const sphereShape sphere(R);
    const triangleMeshShape mesh(primitiveMeshes::icosphere(R, 5), "icosphere");
    // Max chordal gap at level 5 is below 1e-3 R
    std::mt19937 gen(7);
    for (int i = 0; i < 300; ++i)
    {
        const vec3 x = randomVec(gen, -1.5, 1.5);
        const double ds = sphere.signedDistance(x);
        const double dm = mesh.signedDistance(x);
        EXPECT_NEAR(dm, ds, 1e-3);     // the chordal gap (above)
        EXPECT_GE(dm, ds - 1e-15);   // the mesh lies inside the sphere
        if (std::abs(ds) > 1e-3) EXPECT_EQ(mesh.inside(x), sphere.inside(x));
    }
}


TEST(shapeQueries, closestNearIsTheFullSearchWithinItsRadius)
{
    // The octree's search of a mesh within a cell's ball (closestNear):
    // where the surface comes within the radius it finds what the full
    // search finds, bit for bit (the same closest point, distance and
    // normal); where it does not, the full search's point is indeed
    // farther. Points and radii spread across both cases, posed bodies
    const triangleMeshShape& L = LShape();
    std::mt19937 gen(11);
    int near = 0, far = 0;
    for (int i = 0; i < 2000; ++i)
    {
        const bodyPose P(randomVec(gen, -1, 1), randomQuat(gen));
        const vec3 x = P.toWorld(randomVec(gen, -0.5, 2.5));
        const double radius = std::uniform_real_distribution<double>(0, 1)(gen);
        const surfacePoint full = L.closest(P, x);
        surfacePoint sp;
        sp.distance = 1234;
        const bool found =
            L.closestNear(P, x, radius, std::numeric_limits<double>::max(), sp);
        if (found)
        {
            ++near;
            EXPECT_LE(std::abs(full.distance), radius*(1 + 1e-6));
            EXPECT_EQ(sp.distance, full.distance);
            EXPECT_EQ(sp.point, full.point);
            EXPECT_EQ(sp.normal, full.normal);
        }
        else
        {
            ++far;
            EXPECT_GT(std::abs(full.distance), radius);
            EXPECT_EQ(sp.distance, 1234);
        }
    }
    EXPECT_GT(near, 200);       // both branches tested enough
    EXPECT_GT(far, 200);
}


TEST(shapeQueries, treeSearchIsEveryTriangleTried)
{
    // triangleBVH::closest prunes by boxes and by the triangles' planes:
    // its closest squared distance must be exactly the least over every
    // triangle, and its triangle the first that attains it in the tree's
    // own order (ties: points on shared edges and corners). A torus
    // (curved, with a hole) and a box, points near and far from them,
    // bounded and unbounded searches
    const triangleSoup surfaces[2] =
    {
        primitiveMeshes::torus(1.0, 0.4, 32, 16),
        primitiveMeshes::box(vec3(1.0, 0.6, 0.3))
    };
    std::mt19937 gen(5);
    int bounded = 0;
    for (const triangleSoup& s : surfaces)
    {
        const triangleBVH tree(s);
        for (int i = 0; i < 3000; ++i)
        {
            const double spread = i % 2 ? 0.05 : 2.0;
            const vec3 x =
                s.points[s.faces[i % s.faces.size()][0]] + randomVec(gen, -spread, spread);
            double least = std::numeric_limits<double>::max();
            int first = -1;
            for (size_t f = 0; f < s.faces.size(); ++f)
            {
                int feature;
                const triFace& t = s.faces[f];
                const double d2 =
                    (
                        triangleBVH::closestOnTriangle
                        (
                            x, s.points[t[0]], s.points[t[1]], s.points[t[2]], feature
                        ) - x
                    ).squaredNorm();
                if (d2 < least)
                {
                    least = d2;
                    first = int(f);
                }
            }
            const triangleBVH::hit h = tree.closest(x);
            ASSERT_GE(h.face, 0);
            EXPECT_EQ(h.distSqr, least);
            // (the face may differ only where another ties exactly)
            if (h.face != first)
            {
                int feature;
                const triFace& t = s.faces[h.face];
                EXPECT_EQ
                (
                    (
                        triangleBVH::closestOnTriangle
                        (
                            x, s.points[t[0]], s.points[t[1]], s.points[t[2]], feature
                        ) - x
                    ).squaredNorm(),
                    least
                );
            }
            // A bound above the least: the same answer; below: none
            const triangleBVH::hit b = tree.closest(x, least*(1 + 1e-9) + 1e-300);
            EXPECT_EQ(b.face, h.face);
            EXPECT_EQ(b.distSqr, h.distSqr);
            if (least > 0)
            {
                EXPECT_LT(tree.closest(x, 0.999*least).face, 0);
                ++bounded;
            }
        }
    }
    EXPECT_GT(bounded, 5000);
}


TEST(shapeQueries, concurrentQueriesMatchSerial)
{
    // Queries are const and may run concurrently
    const triangleMeshShape& s = LShape();
    std::mt19937 gen(8);
    std::vector<vec3> pts(4000);
    for (vec3& p : pts) p = randomVec(gen, -2.5, 2.5);
    std::vector<double> serial(pts.size());
    std::vector<char> serialIn(pts.size());
    for (size_t i = 0; i < pts.size(); ++i)
    {
        serial[i] = s.signedDistance(pts[i]);
        serialIn[i] = s.inside(pts[i]);
    }
    const int nThreads = 4;
    std::vector<double> par(pts.size());
    std::vector<char> parIn(pts.size());
    std::vector<std::thread> threads;
    for (int t = 0; t < nThreads; ++t)
    {
        threads.emplace_back([&, t]
        {
            for (size_t i = t; i < pts.size(); i += nThreads)
            {
                par[i] = s.signedDistance(pts[i]);
                parIn[i] = s.inside(pts[i]);
            }
        });
    }
    for (std::thread& th : threads) th.join();
    int nIn = 0;
    for (size_t i = 0; i < pts.size(); ++i)
    {
        EXPECT_EQ(par[i], serial[i]);
        EXPECT_EQ(parIn[i], serialIn[i]);
        nIn += serialIn[i];
    }
    EXPECT_GT(nIn, 50);
}


TEST(shapeQueries, pseudoNormalsIndependentOfHeapContents)
{
    // Regression: the edge pseudo-normals were summed into values the hash
    // map left uninitialised, so freed memory (here filled with large
    // numbers) turned signs near edges wrong. Build after poisoning the heap.
    for (int round = 0; round < 3; ++round)
    {
        {
            std::vector<std::unique_ptr<double[]>> junk;
            for (int i = 0; i < 20000; ++i)
            {
                const int n = 2 + i % 10;
                junk.emplace_back(new double[n]);
                for (int k = 0; k < n; ++k) junk.back()[k] = (k % 2 ? -1e30 : 1e30);
            }
        }
        const triangleMeshShape s(primitiveMeshes::box(boxH), "box");
        std::mt19937 gen(9 + round);
        std::uniform_real_distribution<double> u(-1, 1);
        for (int c = 0; c < 8; ++c)
        {
            const vec3 sg((c & 1) ? 1 : -1, (c & 2) ? 1 : -1, (c & 4) ? 1 : -1);
            const vec3 corner = sg.cwiseProduct(boxH);
            for (int axis = 0; axis < 3; ++axis)
            {
                // Outside, nearest to the edge along 'axis' through this corner
                vec3 x = corner;
                x[axis] *= u(gen);
                vec3 dir = sg; dir[axis] = 0;
                x += 0.01*dir;
                const double exact = boxSignedDistance(x, vec3::Zero(), boxH);
                EXPECT_NEAR(sdFile(s, x), exact, 1e-12) << x.transpose();
                EXPECT_GT(sdFile(s, x), 0) << x.transpose();
            }
            const vec3 x = corner + 0.01*sg;
            EXPECT_NEAR(sdFile(s, x), 0.01*std::sqrt(3.0), 1e-12);
        }
    }
}
