#include "immersedDEMPatchSurface.H"
#include "Pstream.H"
#include "immersedDEMPeriodic.H"
#include "wordRes.H"
#include "SubField.H"
#include "wallPolyPatch.H"
#include <algorithm>
#include <map>
#include <tuple>

using namespace immersedDEM;
using namespace Foam;


// The faces of the selected patches as one triangle surface, the same on
// every processor: each rank triangulates its own faces (fans), all ranks
// gather all triangles, merge coincident points and sort the triangles, so
// the wall does not depend on the decomposition. Patch normals point out of
// the domain, into the wall: they are flipped to point into the fluid.
triangleSoup Foam::immersedDEMPatchSurface::of
(
    const polyMesh& mesh,
    const dictionary& d,
    const word& name,
    std::vector<label>* patchOfFace,
    std::vector<std::array<int, 2>>* continued,
    const scalar skirtDepth,
    label* openingEdges
)
{
    const wordRes selection(d.get<wordRes>("patches"));
    const labelHashSet ids(mesh.boundaryMesh().patchSet(selection, false, true));
    if (ids.empty())
    {
        FatalIOErrorInFunction(d)
            << "Wall '" << name << "', keyword 'patches' in " << d.name()
            << ": " << selection << " matches no patch of the mesh; the patches are "
            << mesh.boundaryMesh().names() << nl << exit(FatalIOError);
    }
    // Triangles as flat point triples, ordered by corner, with their patch
    DynamicList<point> mine;
    DynamicList<label> minePatch;
    const pointField& pts = mesh.points();
    for (const label patchi : ids.sortedToc())
    {
        const polyPatch& pp = mesh.boundaryMesh()[patchi];
        if (pp.coupled()) continue;
        for (const face& f : pp)
        {
            for (label k = 1; k + 1 < f.size(); ++k)
            {
                mine.append(pts[f[0]]);
                mine.append(pts[f[k + 1]]);     // flipped: normal into the fluid
                mine.append(pts[f[k]]);
                minePatch.append(patchi);
            }
        }
    }
    // The rest of the boundary where it meets a patch's edge: each edge of
    // an unselected, uncoupled patch's own boundary, as its two points and
    // its face's centre (which side the boundary turns to)
    // (and whether the patch is open: not a wall and no constraint type,
    // an outlet or an inlet)
    DynamicList<point> rest;
    DynamicList<label> restOpen;
    for (const polyPatch& pp : mesh.boundaryMesh())
    {
        if (ids.found(pp.index()) || pp.coupled()) continue;
        const bool open =
            !isA<wallPolyPatch>(pp) && !polyPatch::constraintType(pp.type());
        const edgeList& edges = pp.edges();
        const pointField& local = pp.localPoints();
        for (label e = pp.nInternalEdges(); e < edges.size(); ++e)
        {
            for (const label fi : pp.edgeFaces()[e])
            {
                rest.append(local[edges[e].start()]);
                rest.append(local[edges[e].end()]);
                rest.append(pp.faceCentres()[fi]);
                restOpen.append(open);
            }
        }
    }
    List<pointField> allRest(Pstream::nProcs());
    allRest[Pstream::myProcNo()] = rest;
    Pstream::gatherList(allRest);
    Pstream::scatterList(allRest);
    List<labelList> allRestOpen(Pstream::nProcs());
    allRestOpen[Pstream::myProcNo()] = restOpen;
    Pstream::gatherList(allRestOpen);
    Pstream::scatterList(allRestOpen);

    List<pointField> all(Pstream::nProcs());
    all[Pstream::myProcNo()] = mine;
    Pstream::gatherList(all);
    Pstream::scatterList(all);
    List<labelList> allPatch(Pstream::nProcs());
    allPatch[Pstream::myProcNo()] = minePatch;
    Pstream::gatherList(allPatch);
    Pstream::scatterList(allPatch);

    using key = std::array<double, 3>;
    // (the patch after the corners: the order, and so the surface, does
    // not depend on the decomposition)
    std::vector<std::pair<std::array<key, 3>, label>> tris;
    for (label proci = 0; proci < all.size(); ++proci)
    {
        const pointField& part = all[proci];
        for (label i = 0; i + 2 < part.size(); i += 3)
        {
            std::array<key, 3> t;
            for (int c = 0; c < 3; ++c)
            {
                const point& p = part[i + c];
                t[c] = key{p.x(), p.y(), p.z()};
            }
            // Start at the smallest corner, keeping the orientation
            const int first = int(std::min_element(t.begin(), t.end()) - t.begin());
            std::rotate(t.begin(), t.begin() + first, t.end());
            tris.emplace_back(t, allPatch[proci][i/3]);
        }
    }
    if (tris.empty())
    {
        FatalIOErrorInFunction(d)
            << "Wall '" << name << "', keyword 'patches' in " << d.name()
            << ": the patches " << selection << " have no faces" << nl
            << exit(FatalIOError);
    }
    // In a periodic domain the wall continues beyond the periodic
    // boundaries: its copies a period away along each periodic direction
    // (and their combinations) join it, so that a body cut by the boundary
    // meets the wall on both sides of it
    const periodicBox periodic = immersedDEMPeriodic::fromMesh(mesh, d, false);
    if (periodic.active())
    {
        std::vector<vec3> shifts{vec3::Zero()};
        for (int k = 0; k < periodic.directions(); ++k)
        {
            std::vector<vec3> next;
            for (const vec3& s : shifts)
            {
                for (const int m : {-1, 0, 1}) next.push_back(s + double(m)*periodic.period(k));
            }
            shifts.swap(next);
        }
        const size_t n = tris.size();
        for (const vec3& sh : shifts)
        {
            if (sh.isZero()) continue;
            for (size_t i = 0; i < n; ++i)
            {
                auto t = tris[i];
                for (key& c : t.first)
                {
                    for (int j = 0; j < 3; ++j) c[j] += sh[j];
                }
                tris.push_back(t);
            }
        }
        Info<< "    wall '" << name << "': its patches' faces and their copies"
            << " a period away (" << tris.size() << " triangles)" << endl;
    }
    std::sort(tris.begin(), tris.end());
    triangleSoup s;
    std::map<key, int> index;
    if (patchOfFace) patchOfFace->clear();
    for (const auto& [t, patchi] : tris)
    {
        immersedDEM::triFace f;
        for (int c = 0; c < 3; ++c)
        {
            const auto it = index.find(t[c]);
            if (it == index.end())
            {
                f[c] = int(s.points.size());
                index.emplace(t[c], f[c]);
                s.points.emplace_back(t[c][0], t[c][1], t[c][2]);
            }
            else
            {
                f[c] = it->second;
            }
        }
        s.faces.push_back(f);
        if (patchOfFace) patchOfFace->push_back(patchi);
    }
    if (continued)
    {
        continued->clear();
        // The faces of the rest of the boundary at each of its edges (by
        // the points' coordinates: the same on every processor): centre,
        // open
        std::map<std::pair<key, key>, std::vector<std::pair<point, bool>>> restAt;
        const auto edgeKey = [](const point& a, const point& b)
        {
            key ka{a.x(), a.y(), a.z()}, kb{b.x(), b.y(), b.z()};
            return ka < kb ? std::make_pair(ka, kb) : std::make_pair(kb, ka);
        };
        for (label proci = 0; proci < allRest.size(); ++proci)
        {
            const pointField& part = allRest[proci];
            for (label i = 0; i + 2 < part.size(); i += 3)
            {
                restAt[edgeKey(part[i], part[i + 1])].emplace_back
                (
                    part[i + 2], allRestOpen[proci][i/3] != 0
                );
            }
        }
        std::map<std::pair<int, int>, int> uses;
        for (const immersedDEM::triFace& f : s.faces)
        {
            for (int k = 0; k < 3; ++k)
            {
                ++uses[{std::min(f[k], f[(k + 1)%3]), std::max(f[k], f[(k + 1)%3])}];
            }
        }
        // Rim edges at an opening in the wall's own plane: the edge, the
        // wall face's normal and the direction across the edge into the
        // opening, and the face's patch
        struct opening { int a, b; vec3 n, across; label patchi; };
        std::vector<opening> openings;
        const size_t nWallFaces = s.faces.size();
        for (size_t fi = 0; fi < nWallFaces; ++fi)
        {
            const immersedDEM::triFace& f = s.faces[fi];
            const vec3 n =
                (s.points[f[1]] - s.points[f[0]]).cross(s.points[f[2]] - s.points[f[0]]).normalized();
            for (int k = 0; k < 3; ++k)
            {
                const int a = f[k], b = f[(k + 1)%3];
                if (uses[{std::min(a, b), std::max(a, b)}] != 1) continue;
                const vec3& pa = s.points[a];
                const vec3& pb = s.points[b];
                const auto it = restAt.find
                (
                    edgeKey(point(pa.x(), pa.y(), pa.z()), point(pb.x(), pb.y(), pb.z()))
                );
                if (it == restAt.end()) continue;   // inside the fluid: a baffle
                // Every face there turns to the fluid's side, clearly
                // (1e-6 of its size: an outlet in the wall's own plane,
                // or a baffle's other side, is not)
                bool turns = true;
                // An open patch's face in the wall's plane, beyond the edge
                bool inPlane = false;
                const vec3 e = (pb - pa).normalized();
                const vec3 w = s.points[f[(k + 2)%3]] - pa;
                const vec3 across = -(w - w.dot(e)*e).normalized();
                for (const auto& [c, open] : it->second)
                {
                    const vec3 q = vec3(c.x(), c.y(), c.z()) - pa;
                    turns = turns && n.dot(q) > 1e-6*q.norm();
                    inPlane = inPlane
                     || (open && std::abs(n.dot(q)) <= 1e-6*q.norm() && q.dot(across) > 0);
                }
                if (turns)
                {
                    continued->push_back({a, b});
                }
                else if (inPlane)
                {
                    openings.push_back
                    (
                        {a, b, n, across, patchOfFace ? (*patchOfFace)[fi] : label(-1)}
                    );
                }
            }
        }
        // The wall has a hole there (a floor's outlet): its solid ends at
        // the hole's sides, a skirt of faces from each such edge down
        // through the wall's thickness, facing into the hole. Without it
        // the solid went on under the hole: a body falling through it was
        // pushed back, or stopped the run
        std::map<int, int> lowered;
        const auto below = [&](const int a, const vec3& n)
        {
            const auto it = lowered.find(a);
            if (it != lowered.end()) return it->second;
            const int k = int(s.points.size());
            s.points.push_back(s.points[a] - skirtDepth*n);
            lowered.emplace(a, k);
            return k;
        };
        for (const opening& o : openings)
        {
            const int la = below(o.a, o.n), lb = below(o.b, o.n);
            for (immersedDEM::triFace t : {immersedDEM::triFace{o.a, o.b, lb}, immersedDEM::triFace{o.a, lb, la}})
            {
                const vec3 tn =
                    (s.points[t[1]] - s.points[t[0]]).cross(s.points[t[2]] - s.points[t[0]]);
                if (tn.dot(o.across) < 0) std::swap(t[1], t[2]);
                s.faces.push_back(t);
                if (patchOfFace) patchOfFace->push_back(o.patchi);
            }
        }
        if (openingEdges) *openingEdges = label(openings.size());
    }
    return s;
}
