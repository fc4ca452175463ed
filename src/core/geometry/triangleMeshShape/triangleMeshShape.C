#include "triangleMeshShape.H"
#include "closedSurfaceCheck.H"
#include "coreError.H"
#include "surfaceFileIO.H"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/Side_of_triangle_mesh.h>

#include <cmath>
#include <unordered_map>

namespace immersedDEM
{

struct triangleMeshShape::search
{
    using K = CGAL::Exact_predicates_inexact_constructions_kernel;
    using point = K::Point_3;
    using mesh = CGAL::Surface_mesh<point>;
    using primitive = CGAL::AABB_face_graph_triangle_primitive<mesh>;
    using tree = CGAL::AABB_tree<CGAL::AABB_traits<K, primitive>>;
    using side = CGAL::Side_of_triangle_mesh<mesh, K, CGAL::Default, tree>;

    mesh m;
    tree t;
    std::unique_ptr<side> sideOf;

    explicit search(const triangleSoup& s)
    {
        std::vector<mesh::Vertex_index> v;
        v.reserve(s.points.size());
        for (const vec3& p : s.points)
        {
            v.push_back(m.add_vertex(point(p.x(), p.y(), p.z())));
        }
        // Faces are added in order, so face index i is soup face i
        for (const triFace& f : s.faces)
        {
            if (m.add_face(v[f[0]], v[f[1]], v[f[2]]) == mesh::null_face())
            {
                throw coreError("internal: closed surface rejected by the search structure");
            }
        }
        t.insert(faces(m).first, faces(m).second, m);
        t.build();
        t.accelerate_distance_queries();
        sideOf.reset(new side(t));
        // The first queries build lazy structures: do it now, not concurrently
        (void)t.closest_point_and_primitive(point(0, 0, 0));
        (void)(*sideOf)(point(0, 0, 0));
    }
};


namespace
{

// Closest point of triangle abc to p, and which feature it lies on:
// 0 face interior, 1..3 corners a, b, c, 4..6 edges ab, bc, ca.
// The regions follow the Voronoi regions of the triangle's features.
vec3 closestOnTriangle
(
    const vec3& p, const vec3& a, const vec3& b, const vec3& c, int& region
)
{
    const vec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) { region = 1; return a; }

    const vec3 bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) { region = 2; return b; }

    const double vc = d1*d4 - d3*d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0)
    {
        region = 4;
        return a + (d1/(d1 - d3))*ab;
    }

    const vec3 cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) { region = 3; return c; }

    const double vb = d5*d2 - d1*d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0)
    {
        region = 6;
        return a + (d2/(d2 - d6))*ac;
    }

    const double va = d3*d6 - d5*d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    {
        region = 5;
        return b + ((d4 - d3)/((d4 - d3) + (d5 - d6)))*(c - b);
    }

    const double denom = 1.0/(va + vb + vc);
    region = 0;
    return a + ab*(vb*denom) + ac*(vc*denom);
}

std::uint64_t edgeKey(int a, int b)
{
    return (std::uint64_t(std::max(a, b)) << 32) | std::uint64_t(std::min(a, b));
}

} // End anonymous namespace


triangleMeshShape::triangleMeshShape
(
    triangleSoup soup,
    const std::string& name,
    bool checkSelfIntersection
)
:
    name_(name)
{
    warnings_ = closedSurfaceCheck::checkAndRepair(soup, name, checkSelfIntersection);
    fileMassProperties_ = massProperties::of(soup);

    // Body frame: principal axes at the centroid
    bodyInFile_ = bodyPose(fileMassProperties_.centroid, quat(fileMassProperties_.principalAxes));
    body_ = std::move(soup);
    for (vec3& p : body_.points)
    {
        p = bodyInFile_.toBody(p);
        localBox_.add(p);
        boundingRadius_ = std::max(boundingRadius_, p.norm());
    }

    // Angle-weighted pseudo-normals (Baerentzen & Aanaes): the sign of
    // (p - closest).n is then right whichever feature is closest
    const size_t nF = body_.faces.size();
    faceNormal_.resize(nF);
    edgeNormal_.resize(nF);
    vertexNormal_.assign(body_.points.size(), vec3::Zero());
    std::unordered_map<std::uint64_t, vec3> edgeSum;
    edgeSum.reserve(3*nF);
    for (size_t fi = 0; fi < nF; ++fi)
    {
        const triFace& f = body_.faces[fi];
        const vec3 n = (body_.points[f[1]] - body_.points[f[0]])
            .cross(body_.points[f[2]] - body_.points[f[0]]).normalized();
        faceNormal_[fi] = n;
        for (int k = 0; k < 3; ++k)
        {
            const vec3& p0 = body_.points[f[k]];
            const vec3 e1 = (body_.points[f[(k + 1) % 3]] - p0).normalized();
            const vec3 e2 = (body_.points[f[(k + 2) % 3]] - p0).normalized();
            const double angle = std::acos(std::max(-1.0, std::min(1.0, e1.dot(e2))));
            vertexNormal_[f[k]] += angle*n;
            // Not operator[]: it would leave a new (Eigen) vec3 uninitialised
            edgeSum.emplace(edgeKey(f[k], f[(k + 1) % 3]), vec3::Zero()).first->second += n;
        }
    }
    for (vec3& n : vertexNormal_) n.normalize();
    for (size_t fi = 0; fi < nF; ++fi)
    {
        const triFace& f = body_.faces[fi];
        for (int k = 0; k < 3; ++k)
        {
            edgeNormal_[fi][k] = edgeSum[edgeKey(f[k], f[(k + 1) % 3])].normalized();
        }
    }

    search_.reset(new search(body_));
}


triangleMeshShape::~triangleMeshShape() = default;


std::unique_ptr<triangleMeshShape> triangleMeshShape::fromFile
(
    const std::string& fileName,
    double scale,
    bool checkSelfIntersection
)
{
    if (!(std::isfinite(scale) && scale > 0))
    {
        throw coreError("Surface file \"" + fileName + "\": scale must be positive");
    }
    triangleSoup soup = surfaceFileIO::read(fileName);
    if (scale != 1)
    {
        for (vec3& p : soup.points) p *= scale;
    }
    return std::make_unique<triangleMeshShape>(std::move(soup), fileName, checkSelfIntersection);
}


bool triangleMeshShape::inside(const vec3& p) const
{
    if (!localBox_.contains(p))
    {
        return false;
    }
    return (*search_->sideOf)(search::point(p.x(), p.y(), p.z())) != CGAL::ON_UNBOUNDED_SIDE;
}


surfacePoint triangleMeshShape::closestOnFace(const vec3& p, int fi) const
{
    const triFace& f = body_.faces[fi];
    int region = 0;
    surfacePoint sp;
    sp.point = closestOnTriangle
    (
        p, body_.points[f[0]], body_.points[f[1]], body_.points[f[2]], region
    );
    const vec3 pseudo =
        region == 0 ? faceNormal_[fi]
      : region <= 3 ? vertexNormal_[f[region - 1]]
      : edgeNormal_[fi][region - 4];

    const vec3 d = p - sp.point;
    const double dist = d.norm();
    const double tol = 1e-9*boundingRadius_;
    if (dist > tol)
    {
        const bool in = d.dot(pseudo) < 0;
        sp.distance = in ? -dist : dist;
        // Outward normal: along p - closest (its sign fixed by the side)
        sp.normal = in ? vec3(-d/dist) : vec3(d/dist);
    }
    else
    {
        // On or within round-off of the surface: the exact test decides
        sp.distance = inside(p) ? -dist : dist;
        sp.normal = pseudo;
    }
    return sp;
}


surfacePoint triangleMeshShape::closest(const vec3& p) const
{
    const auto cp = search_->t.closest_point_and_primitive(search::point(p.x(), p.y(), p.z()));
    return closestOnFace(p, int(cp.second.idx()));
}


double triangleMeshShape::signedDistance(const vec3& p) const
{
    return closest(p).distance;
}

} // End namespace immersedDEM
