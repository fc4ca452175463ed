#include "wallMeshShape.H"

#include <map>
#include "coreError.H"
#include "closedSurfaceCheck.H"

#include <limits>

namespace immersedDEM
{

namespace
{

const triangleSoup& nonEmpty(const triangleSoup& s, const std::string& name)
{
    if (s.faces.empty())
    {
        throw coreError("Wall surface \"" + name + "\" has no triangles");
    }
    closedSurfaceCheck::checkCoordinateRange(s, name);
    return s;
}

} // End anonymous namespace


wallMeshShape::wallMeshShape
(
    triangleSoup surface,
    const std::string& name,
    double thickness,
    const std::vector<edge>& continued
)
:
    shape(staticKind),
    surface_(std::move(surface)),
    distance_(nonEmpty(surface_, name))
{
    if (!(thickness > 0))
    {
        throw coreError("Wall surface \"" + name + "\": thickness must be positive");
    }
    for (const vec3& p : surface_.points)
    {
        box_.add(p);
    }
    box_ = box_.inflated(thickness);
    for (const vec3& p : surface_.points)
    {
        radius_ = std::max(radius_, p.norm());
    }
    radius_ += thickness;
    largestFlatFace_ = flatFaceOf(surface_);

    std::map<std::pair<int, int>, int> edgeUses;
    for (const triFace& f : surface_.faces)
    {
        for (int k = 0; k < 3; ++k)
        {
            const int a = f[k], b = f[(k + 1)%3];
            ++edgeUses[{std::min(a, b), std::max(a, b)}];
        }
    }
    for (const edge& e : continued)
    {
        // Used once: on the rim, and now known to be continued (marked 0)
        const auto it = edgeUses.find({std::min(e[0], e[1]), std::max(e[0], e[1])});
        if (it == edgeUses.end() || it->second != 1)
        {
            throw coreError
            (
                "Wall surface \"" + name + "\": an edge said to be continued"
                " is not on the surface's rim"
            );
        }
        it->second = 0;
    }
    for (const auto& e : edgeUses) rimEdges_ += (e.second == 1);
    onRim_.assign(surface_.faces.size(), 0);
    std::vector<char> openVertex(surface_.points.size(), 0);
    for (size_t fi = 0; fi < surface_.faces.size(); ++fi)
    {
        const triFace& f = surface_.faces[fi];
        for (int k = 0; k < 3; ++k)
        {
            const int a = f[k], b = f[(k + 1)%3];
            const int uses = edgeUses[{std::min(a, b), std::max(a, b)}];
            if (uses == 1) onRim_[fi] = 1;
            if (uses != 2 && uses != 0) openVertex[a] = openVertex[b] = 1;
        }
    }
    // The faces at a vertex of an open (or non-manifold) edge. Near a
    // continued edge the pseudo-normal sign is that of the continued wall
    // (the boundary turns to the fluid's side there), as for a closed one
    triangleSoup open;
    open.points = surface_.points;
    for (const triFace& f : surface_.faces)
    {
        if (openVertex[f[0]] || openVertex[f[1]] || openVertex[f[2]])
        {
            open.faces.push_back(f);
        }
    }
    if (!open.faces.empty())
    {
        openTree_ = std::make_unique<triangleBVH>(open);
    }
}


bool wallMeshShape::flatNear(const vec3& p, double r, vec3& point, vec3& normal) const
{
    std::vector<int> faces;
    if (!distance_.tree().facesWithin(p, r, faces, 4096) || faces.empty())
    {
        return false;
    }
    const vec3& n0 = distance_.faceNormal(faces[0]);
    const vec3& x0 = surface_.points[surface_.faces[faces[0]][0]];
    // Flat to round-off of the wall's size
    const double tol = 1e-12*(box_.max - box_.min).norm();
    for (const int f : faces)
    {
        if (onRim_[f] || distance_.faceNormal(f).dot(n0) < 1 - 1e-12)
        {
            return false;
        }
        for (const int v : surface_.faces[f])
        {
            if (std::abs((surface_.points[v] - x0).dot(n0)) > tol) return false;
        }
    }
    point = x0;
    normal = n0;
    return true;
}


bool wallMeshShape::clearOf(const vec3& p, double r) const
{
    std::vector<int> faces;
    // maxFaces 0: false at the first face found that near
    if (!distance_.tree().facesWithin(p, r, faces, 0))
    {
        return false;
    }
    return distance_.closest(p).distance > r;
}


bool wallMeshShape::convexFluidNear
(
    const vec3& p, double r, std::vector<plane>& planes, size_t maxFaces
) const
{
    planes.clear();
    std::vector<int> faces;
    if (!distance_.tree().facesWithin(p, r, faces, maxFaces) || faces.empty())
    {
        return false;
    }
    const double tol = 1e-9*(box_.max - box_.min).norm();
    for (const int f : faces)
    {
        if (onRim_[f]) return false;
        const vec3& n = distance_.faceNormal(f);
        const double c = n.dot(surface_.points[surface_.faces[f][0]]);
        bool merged = false;
        for (const plane& q : planes)
        {
            if (n.dot(q.normal) > 1 - 1e-12 && std::abs(c - q.offset) <= tol)
            {
                merged = true;
                break;
            }
        }
        if (!merged) planes.push_back({n, c});
    }
    // Every near corner in front of every near plane, and p too
    for (const plane& q : planes)
    {
        if (q.normal.dot(p) < q.offset) return false;
        for (const int f : faces)
        {
            for (const int v : surface_.faces[f])
            {
                if (q.normal.dot(surface_.points[v]) < q.offset - tol) return false;
            }
        }
    }
    return true;
}


double wallMeshShape::volume() const
{
    // A wall has no mass properties: it never moves by forces. Zero, not
    // infinity, so no arithmetic on it can raise a floating-point trap
    // (OpenFOAM runs with them enabled)
    return 0;
}


vec3 wallMeshShape::principalMoments() const
{
    return vec3::Zero();
}


surfacePoint wallMeshShape::closest(const vec3& p, double bound) const
{
    if (!(bound < 1e100))
    {
        return distance_.closest(p);    // no bound; and no overflow below
    }
    const double b = bound*(1 + 1e-9) + 1e-12*radius_;
    return distance_.closest(p, b*b);
}

bool wallMeshShape::facetsNear
(
    const vec3& p, double r, std::vector<surfaceFacet>& facets, size_t maxFacets
) const
{
    std::vector<int> faces;
    if (!distance_.tree().facesWithin(p, r, faces, maxFacets))
    {
        return false;
    }
    for (const int f : faces)
    {
        const triFace& t = surface_.faces[f];
        facets.push_back
        (
            {surface_.points[t[0]], surface_.points[t[1]], surface_.points[t[2]], distance_.faceNormal(f)}
        );
    }
    return true;
}

} // End namespace immersedDEM
