#include "bodySeparation.H"
#include "triangleBVH.H"
#include "coreError.H"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <cmath>

namespace immersedDEM
{

namespace
{
using kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

kernel::Triangle_3 cgalTriangle(const std::array<vec3, 3>& t)
{
    auto P = [](const vec3& p) { return kernel::Point_3(p.x(), p.y(), p.z()); };
    return kernel::Triangle_3(P(t[0]), P(t[1]), P(t[2]));
}

posedBody::kind kindOf(const shape& s)
{
    const std::string t = s.type();
    if (t == "sphere") return posedBody::kind::sphere;
    if (t == "plane") return posedBody::kind::plane;
    if (t == "triangleMesh") return posedBody::kind::mesh;
    if (t == "wallMesh") return posedBody::kind::wallMesh;
    throw coreError("bodySeparation: unknown shape type '" + t + "'");
}
}


posedBody::posedBody(const shape& s, const bodyPose& p)
:
    posedBody(s, p, (kindOf(s) == kind::mesh || kindOf(s) == kind::wallMesh) ? s.surface() : triangleSoup())
{}


posedBody::posedBody(const shape& s, const bodyPose& p, const triangleSoup& surface)
:
    geometry(&s),
    pose(p),
    type(kindOf(s)),
    radius(s.boundingRadius()),
    box(s.worldBox(p))
{
    if (type == kind::mesh || type == kind::wallMesh)
    {
        vertices.reserve(surface.points.size());
        for (const vec3& x : surface.points) vertices.push_back(p.toWorld(x));
        triangles.reserve(surface.faces.size());
        triangleBoxes.reserve(surface.faces.size());
        for (const triFace& f : surface.faces)
        {
            std::array<vec3, 3> t{vertices[f[0]], vertices[f[1]], vertices[f[2]]};
            axisAlignedBox b;
            for (const vec3& x : t) b.add(x);
            triangles.push_back(t);
            triangleBoxes.push_back(b);
        }
        if (type == kind::mesh)
        {
            // The exact box of the posed vertices (tighter than worldBox)
            box = axisAlignedBox();
            for (const vec3& x : vertices) box.add(x);
        }
    }
}


posedBody posedBody::translated(const vec3& d) const
{
    posedBody b = *this;
    b.pose.setPosition(pose.position() + d);
    b.box = axisAlignedBox(box.min + d, box.max + d);
    for (vec3& v : b.vertices) v += d;
    for (auto& t : b.triangles) for (vec3& v : t) v += d;
    for (axisAlignedBox& tb : b.triangleBoxes) tb = axisAlignedBox(tb.min + d, tb.max + d);
    return b;
}


double bodySeparation::segmentDistance
(
    const vec3& p1, const vec3& q1, const vec3& p2, const vec3& q2
)
{
    return triangleBVH::segmentDistance(p1, q1, p2, q2);
}


double bodySeparation::triangleDistance
(
    const std::array<vec3, 3>& s, const std::array<vec3, 3>& t
)
{
    double d = std::numeric_limits<double>::max();
    int feature = 0;
    for (int i = 0; i < 3; ++i)
    {
        d = std::min(d, (s[i] - triangleBVH::closestOnTriangle(s[i], t[0], t[1], t[2], feature)).norm());
        d = std::min(d, (t[i] - triangleBVH::closestOnTriangle(t[i], s[0], s[1], s[2], feature)).norm());
        for (int j = 0; j < 3; ++j)
        {
            d = std::min(d, segmentDistance(s[i], s[(i + 1)%3], t[j], t[(j + 1)%3]));
        }
    }
    return d;
}


bool bodySeparation::trianglesIntersect
(
    const std::array<vec3, 3>& s, const std::array<vec3, 3>& t
)
{
    const kernel::Triangle_3 a = cgalTriangle(s), b = cgalTriangle(t);
    // A degenerate triangle (no area) bounds nothing: its neighbours do
    if (a.is_degenerate() || b.is_degenerate()) return false;
    return CGAL::do_intersect(a, b);
}


namespace
{

using kind = posedBody::kind;

// A sphere (s) against anything
bool sphereApart(const posedBody& s, const posedBody& o, double c)
{
    const vec3& x = s.pose.position();
    if (o.type == kind::sphere)
    {
        return (x - o.pose.position()).norm() >= s.radius + o.radius + c;
    }
    return o.geometry->signedDistance(o.pose, x) >= s.radius + c;
}


// Mesh m against a plane
bool planeApart(const posedBody& m, const posedBody& plane, double c)
{
    for (const vec3& v : m.vertices)
    {
        if (plane.geometry->signedDistance(plane.pose, v) < c) return false;
    }
    return true;
}


// Do the surfaces of m and o cross (or come within c)
bool surfacesMeet(const posedBody& m, const posedBody& o, double c)
{
    const axisAlignedBox mBox = m.box.inflated(c), oBox = o.box.inflated(c);
    std::vector<int> mi, oi;
    for (size_t i = 0; i < m.triangles.size(); ++i)
    {
        if (m.triangleBoxes[i].overlaps(oBox)) mi.push_back(int(i));
    }
    if (!mi.empty())
    {
        for (size_t j = 0; j < o.triangles.size(); ++j)
        {
            if (o.triangleBoxes[j].overlaps(mBox)) oi.push_back(int(j));
        }
    }
    for (const int i : mi)
    {
        const axisAlignedBox bi = m.triangleBoxes[i].inflated(c);
        for (const int j : oi)
        {
            if (!bi.overlaps(o.triangleBoxes[j])) continue;
            if (bodySeparation::trianglesIntersect(m.triangles[i], o.triangles[j])) return true;
            if (c > 0 && bodySeparation::triangleDistance(m.triangles[i], o.triangles[j]) < c)
            {
                return true;
            }
        }
    }
    return false;
}


// Mesh m against a mesh or wall mesh o
bool meshApart(const posedBody& m, const posedBody& o, double c)
{
    if (surfacesMeet(m, o, c)) return false;
    // The surfaces do not cross: one may still hold the other whole
    if (o.type == kind::wallMesh)
    {
        return o.geometry->signedDistance(o.pose, m.vertices[0]) > 0;
    }
    if (o.geometry->inside(o.pose, m.vertices[0])) return false;
    if (m.geometry->inside(m.pose, o.vertices[0])) return false;
    return true;
}

} // End anonymous namespace


bool bodySeparation::inside(const posedBody& body, const posedBody& region)
{
    if (body.type == kind::sphere)
    {
        return region.geometry->signedDistance(region.pose, body.pose.position()) <= -body.radius;
    }
    if (!body.box.overlaps(region.box)) return false;
    return !surfacesMeet(body, region, 0) && region.geometry->inside(region.pose, body.vertices[0]);
}


bool bodySeparation::apart(const posedBody& a, const posedBody& b, double c)
{
    if (!a.box.inflated(c).overlaps(b.box))
    {
        return true;
    }
    const bool aFinite = a.type == kind::sphere || a.type == kind::mesh;
    const bool bFinite = b.type == kind::sphere || b.type == kind::mesh;
    if
    (
        aFinite && bFinite
     && (a.pose.position() - b.pose.position()).norm() >= a.radius + b.radius + c
    )
    {
        return true;
    }
    if (a.type == kind::sphere) return sphereApart(a, b, c);
    if (b.type == kind::sphere) return sphereApart(b, a, c);
    if (a.type == kind::plane && b.type == kind::plane) return true;
    if (b.type == kind::plane) return planeApart(a, b, c);
    if (a.type == kind::plane) return planeApart(b, a, c);
    if (a.type == kind::wallMesh && b.type == kind::wallMesh) return true;
    if (a.type == kind::wallMesh) return meshApart(b, a, c);
    return meshApart(a, b, c);
}

} // End namespace immersedDEM
