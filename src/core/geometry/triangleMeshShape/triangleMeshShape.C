#include "triangleMeshShape.H"
#include "closedSurfaceCheck.H"
#include "coreError.H"
#include "surfaceFileIO.H"
#include "triangleBVH.H"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/Side_of_triangle_mesh.h>

#include <cmath>
#include <limits>
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
    bvh_.reset(new triangleBVH(body_));
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


surfacePoint triangleMeshShape::closest(const vec3& p) const
{
    return closestWithin(p, std::numeric_limits<double>::max());
}


surfacePoint triangleMeshShape::closest(const vec3& p, double distanceBound) const
{
    // Slack for round-off in the caller's bound
    const double b = distanceBound*(1 + 1e-9) + 1e-12*boundingRadius_;
    return closestWithin(p, b*b);
}


surfacePoint triangleMeshShape::closestWithin(const vec3& p, double maxDistSqr) const
{
    triangleBVH::hit h = bvh_->closest(p, maxDistSqr);
    if (h.face < 0)
    {
        h = bvh_->closest(p);
    }
    const int fi = h.face;
    const int region = h.feature;
    const triFace& f = body_.faces[fi];
    surfacePoint sp;
    sp.point = h.point;
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


double triangleMeshShape::signedDistance(const vec3& p) const
{
    return closest(p).distance;
}

} // End namespace immersedDEM
