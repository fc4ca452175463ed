#include "exactOverlap.H"
#include "coreError.H"
#include "floatingPointGuard.H"
#include "overlapTools.H"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>

#include <algorithm>
#include <cmath>

namespace immersedDEM
{

namespace
{

// Exact predicates suffice: corefinement keeps its new intersection points
// exact internally, so only the output coordinates are rounded
using kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using point = kernel::Point_3;
using mesh = CGAL::Surface_mesh<point>;

namespace PMP = CGAL::Polygon_mesh_processing;


// A body's surface in the world frame, and the box of its points: tighter
// than the shape's worldBox, which boxes the rotated local box
struct worldSurface
{
    triangleSoup soup;
    axisAlignedBox box;

    worldSurface(const shape& s, const bodyPose& p)
    :
        soup(s.surface())
    {
        for (vec3& x : soup.points)
        {
            x = p.toWorld(x);
            box.add(x);
        }
    }
};


mesh toMesh(const triangleSoup& s, const std::string& which)
{
    mesh m;
    std::vector<mesh::Vertex_index> v;
    v.reserve(s.points.size());
    for (const vec3& x : s.points)
    {
        v.push_back(m.add_vertex(point(x.x(), x.y(), x.z())));
    }
    for (const triFace& f : s.faces)
    {
        if (m.add_face(v[f[0]], v[f[1]], v[f[2]]) == mesh::null_face())
        {
            throw coreError
            (
                "internal: overlap method 'exact': the surface of body " + which
              + " is not an oriented manifold"
            );
        }
    }
    return m;
}


vec3 toVec(const point& p)
{
    return vec3(p.x(), p.y(), p.z());
}


// What one connected component of the intersection solid sums to
struct componentSum
{
    double sixVolume = 0;           // 6 x volume
    vec3 first = vec3::Zero();      // 24 x first moment about the reference
    vec3 areaFromA = vec3::Zero();  // 2 x vector area of A's faces
    double absArea = 0;             // 2 x total area, a scale for "zero"
};

} // End anonymous namespace


contactGeometry exactOverlap::evaluate
(
    const shape& A, const bodyPose& pA,
    const shape& B, const bodyPose& pB,
    const overlapSettings&
) const
{
    if (A.type() != "triangleMesh" || B.type() != "triangleMesh")
    {
        throw coreError
        (
            "Overlap method 'exact' needs two triangle-mesh bodies, not "
          + A.type() + " and " + B.type() + "; use sphere (two spheres) or virtualMesh"
        );
    }

    const floatingPointGuard noTraps;
    contactGeometry g;
    const worldSurface a(A, pA), b(B, pB);
    const axisAlignedBox box = a.box.intersection(b.box);
    if (box.empty())
    {
        return g;
    }

    mesh mA = toMesh(a.soup, "A");
    mesh mB = toMesh(b.soup, "B");
    mesh out;
    bool ok = false;
    try
    {
        ok = PMP::corefine_and_compute_intersection(mA, mB, out);
    }
    catch (const std::exception& e)
    {
        throw coreError
        (
            std::string("Overlap method 'exact': CGAL failed to intersect the two surfaces: ")
          + e.what()
        );
    }
    if (!ok)
    {
        throw coreError
        (
            "Overlap method 'exact': the intersection of the two surfaces is not"
            " manifold (CGAL corefinement); use virtualMesh for this contact"
        );
    }
    if (out.number_of_faces() == 0)
    {
        return g;
    }

    auto component = out.add_property_map<mesh::Face_index, std::size_t>("f:component", 0).first;
    const std::size_t nComponents = PMP::connected_components(out, component);

    // Moments about a point in the overlap's box: the tetrahedra then stay
    // small where the bodies are far from the world origin
    const vec3 ref = box.centre();
    std::vector<componentSum> sums(nComponents);
    for (const mesh::Face_index f : out.faces())
    {
        vec3 x[3];
        int k = 0;
        for (const mesh::Vertex_index v : out.vertices_around_face(out.halfedge(f)))
        {
            x[k++] = toVec(out.point(v)) - ref;
        }
        const vec3 twiceArea = (x[1] - x[0]).cross(x[2] - x[0]);
        componentSum& s = sums[component[f]];
        const double sixV = x[0].dot(x[1].cross(x[2]));
        s.sixVolume += sixV;
        s.first += sixV*(x[0] + x[1] + x[2]);
        s.absArea += twiceArea.norm();

        // The face lies on one of the two surfaces; the other is farther
        // from it (both are ~0 only on a patch the surfaces share)
        const vec3 c = (x[0] + x[1] + x[2])/3 + ref;
        if (std::abs(A.signedDistance(pA, c)) <= std::abs(B.signedDistance(pB, c)))
        {
            s.areaFromA += twiceArea;
        }
    }

    // Touching bodies leave slivers of round-off volume: far below any real
    // contact, which is at least this deep over the smaller body's size
    const double minVolume = 1e-12*std::min(A.volume(), B.volume());
    const vec3 centreLine = pB.position() - pA.position();
    for (const componentSum& s : sums)
    {
        const double volume = s.sixVolume/6;
        if (!(volume > minVolume))
        {
            continue;
        }
        contactRegion r;
        r.volume = volume;
        r.point = ref + s.first/(4*s.sixVolume);
        const double S = 0.5*s.areaFromA.norm();
        if (S > 1e-9*0.5*s.absArea)
        {
            r.normal = s.areaFromA.normalized();
            r.area = S;
        }
        else
        {
            r.normal = overlapTools::firstDirection({centreLine});
            r.area = 0;
        }
        g.regions.push_back(r);
    }

    // A deterministic order: largest region first
    overlapTools::sortLargestFirst(g.regions, false);
    return g;
}

} // End namespace immersedDEM
