#include "triangleMeshShape.H"
#include "closedSurfaceCheck.H"
#include "coreError.H"
#include "surfaceFileIO.H"
#include "surfaceDistance.H"
#include "floatingPointGuard.H"

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
        const floatingPointGuard noTraps;
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
        sideOf.reset(new side(t));
        // The first query builds lazy structures: do it now, not concurrently
        (void)(*sideOf)(point(0, 0, 0));
    }
};


triangleMeshShape::triangleMeshShape
(
    triangleSoup soup,
    const std::string& name,
    bool checkSelfIntersection,
    int maxConvexPieces
)
:
    shape(staticKind),
    name_(name)
{
    warnings_ = closedSurfaceCheck::checkAndRepair(soup, name, checkSelfIntersection);
    fileMassProperties_ = massProperties::of(soup);

    // Body frame: principal axes at the centroid
    bodyInFile_ = bodyPose(fileMassProperties_.centroid, quat(fileMassProperties_.principalAxes));
    body_ = soup;
    for (vec3& p : body_.points)
    {
        p = bodyInFile_.toBody(p);
        localBox_.add(p);
        boundingRadius_ = std::max(boundingRadius_, p.norm());
    }

    largestFlatFace_ = flatFaceOf(body_);
    search_.reset(new search(body_));
    distance_.reset(new surfaceDistance(body_));
    convex_ = convexPolyhedron::of(body_);
    if (convex_)
    {
        piecesNote_ = "convex";
    }
    else if (maxConvexPieces > 0)
    {
        // In the file's frame, where a pellet's faces usually lie along
        // the axes and the cuts through its reflex edges are fewest (a
        // ring: 26 pieces, against more than 64 in its principal frame);
        // then in the body frame
        convexDecomposition d = convexDecomposition::of(soup, maxConvexPieces);
        if (!d.empty())
        {
            for (triangleSoup& p : d.pieces)
            {
                for (vec3& x : p.points) x = bodyInFile_.toBody(x);
            }
        }
        else
        {
            d = convexDecomposition::of(body_, maxConvexPieces);
        }
        setPieces(std::move(d));
    }
    else
    {
        piecesNote_ = "not convex, not decomposed";
    }
}


void triangleMeshShape::setPieces(convexDecomposition d)
{
    if (d.empty())
    {
        piecesNote_ = "not convex, not decomposed: " + d.why;
        return;
    }
    for (size_t i = 0; i < d.pieces.size(); ++i)
    {
        pieces_.push_back
        (
            std::make_unique<triangleMeshShape>
            (
                std::move(d.pieces[i]), name_ + " piece " + std::to_string(i), false, 0
            )
        );
    }
    for (size_t i = 0; i < pieces_.size(); ++i)
    {
        // (checked in the frame decomposed; again in its own, tighter)
        if (!pieces_[i]->convex())
        {
            pieces_.clear();
            piecesNote_ =
                "not convex, not decomposed: piece " + std::to_string(i)
              + " is not convex to round-off in its own frame";
            return;
        }
    }
    pieceNeighbours_ = std::move(d.neighbours);
    piecesNote_ = std::to_string(pieces_.size()) + " convex pieces";
}


std::unique_ptr<triangleMeshShape> triangleMeshShape::fromParts
(
    std::vector<triangleSoup> parts, const std::string& name,
    bool checkSelfIntersection
)
{
    for (size_t i = 0; i < parts.size(); ++i)
    {
        closedSurfaceCheck::checkAndRepair
        (
            parts[i], "part " + std::to_string(i + 1), checkSelfIntersection
        );
    }
    triangleSoup whole;
    convexDecomposition d = convexDecomposition::ofParts(std::move(parts), whole);
    if (d.empty())
    {
        throw coreError("the convex parts: " + d.why);
    }
    auto out = std::make_unique<triangleMeshShape>(std::move(whole), name, checkSelfIntersection, 0);
    for (triangleSoup& p : d.pieces)
    {
        for (vec3& x : p.points) x = out->bodyInFile().toBody(x);
    }
    out->setPieces(std::move(d));
    if (out->pieces_.empty())
    {
        throw coreError("the convex parts: " + out->piecesNote_);
    }
    out->piecesNote_ += " (the parts given)";
    return out;
}


std::unique_ptr<triangleMeshShape> triangleMeshShape::scaled
(
    double f, const std::string& name
) const
{
    triangleSoup s = body_;
    for (vec3& p : s.points) p *= f;
    auto out = std::make_unique<triangleMeshShape>(std::move(s), name, false, 0);
    if (!pieces_.empty())
    {
        // The pieces in this body's frame, scaled, then in the new body's
        // frame (the same up to round-off)
        convexDecomposition d;
        for (const auto& q : pieces_)
        {
            triangleSoup p = q->surface();
            for (vec3& x : p.points)
            {
                x = out->bodyInFile().toBody(f*q->bodyInFile().toWorld(x));
            }
            d.pieces.push_back(std::move(p));
        }
        d.neighbours = pieceNeighbours_;
        out->setPieces(std::move(d));
    }
    else if (!convex_)
    {
        out->piecesNote_ = piecesNote_;
    }
    return out;
}


triangleMeshShape::~triangleMeshShape() = default;


std::unique_ptr<triangleMeshShape> triangleMeshShape::fromFile
(
    const std::string& fileName,
    double scale,
    bool checkSelfIntersection,
    int maxConvexPieces
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
    return std::make_unique<triangleMeshShape>
    (
        std::move(soup), fileName, checkSelfIntersection, maxConvexPieces
    );
}


bool triangleMeshShape::inside(const vec3& p) const
{
    if (!localBox_.contains(p))
    {
        return false;
    }
    const floatingPointGuard noTraps;
    return (*search_->sideOf)(search::point(p.x(), p.y(), p.z())) != CGAL::ON_UNBOUNDED_SIDE;
}


surfacePoint triangleMeshShape::closest(const vec3& p) const
{
    return closestWithin(p, std::numeric_limits<double>::max());
}


surfacePoint triangleMeshShape::closest(const vec3& p, double distanceBound) const
{
    if (!(distanceBound < 1e100))
    {
        return closest(p);      // no bound; and no overflow below
    }
    // Slack for round-off in the caller's bound
    const double b = distanceBound*(1 + 1e-9) + 1e-12*boundingRadius_;
    return closestWithin(p, b*b);
}


surfacePoint triangleMeshShape::closestWithin(const vec3& p, double maxDistSqr) const
{
    vec3 pseudo;
    surfacePoint sp = distance_->closest(p, maxDistSqr, &pseudo);
    settleSign(p, pseudo, sp);
    return sp;
}


bool triangleMeshShape::closestNear
(
    const vec3& p, double radius, double, surfacePoint& sp
) const
{
    // (the slack of closest's bound: found at any distance up to radius)
    const double b = radius*(1 + 1e-9) + 1e-12*boundingRadius_;
    vec3 pseudo;
    if (!distance_->closestNear(p, b*b, sp, &pseudo))
    {
        return false;
    }
    settleSign(p, pseudo, sp);
    return true;
}


void triangleMeshShape::settleSign(const vec3& p, const vec3& pseudo, surfacePoint& sp) const
{
    if (std::abs(sp.distance) <= 1e-9*boundingRadius_)
    {
        // On or within round-off of the surface: the exact test decides
        sp.distance = inside(p) ? -std::abs(sp.distance) : std::abs(sp.distance);
        sp.normal = pseudo;
    }
}


double triangleMeshShape::signedDistance(const vec3& p) const
{
    return closest(p).distance;
}

bool triangleMeshShape::facetsNear
(
    const vec3& p, double r, std::vector<surfaceFacet>& facets, size_t maxFacets
) const
{
    std::vector<int> faces;
    if (!distance_->tree().facesWithin(p, r, faces, maxFacets))
    {
        return false;
    }
    for (const int f : faces)
    {
        const triFace& t = body_.faces[f];
        facets.push_back
        (
            {body_.points[t[0]], body_.points[t[1]], body_.points[t[2]], distance_->faceNormal(f)}
        );
    }
    return true;
}

} // End namespace immersedDEM
