#include "immersedDEMSlabs.H"
#include "triangleMeshShape.H"
#include "boxFraction.H"
#include "coreError.H"
#include "surfaceFileIO.H"
#include <algorithm>
#include <cmath>

using namespace immersedDEM;
using namespace Foam;


// 2D: on a mesh one cell thick with empty patches (OpenFOAM's nSolutionD 2)
// the fluid acts on the slab between the empty patches only. Each body must
// pierce both empty patches and be a prism along the empty direction (a
// cylinder's STL along it); it is replaced by its part in the slab (the
// surface mapped onto the slab along that direction), so that mass,
// inertia, buoyancy, added mass and contact volumes are per slab like the
// fluid force, and its motion is kept in the plane (no translation along
// the empty direction, rotation about it only).
void Foam::immersedDEMSlabs::toSlab
(
    demSolver& dem,
    const polyMesh& mesh,
    const dictionary& dict
)
{
    if (mesh.nSolutionD() == 3) return;
    const Vector<label>& sol = mesh.solutionD();
    if (mesh.nSolutionD() != 2)
    {
        FatalIOErrorInFunction(dict)
            << "The mesh has " << mesh.nSolutionD() << " solution direction(s)"
            << " (empty patches " << sol << "): the bodies of " << dict.name()
            << " need a 3D mesh or a 2D one (one cell thick, empty patches on"
            << " both sides)" << nl << exit(FatalIOError);
    }
    direction n = 0;
    for (direction k = 0; k < 3; ++k)
    {
        if (sol[k] < 0) n = k;
    }
    const char axis = "xyz"[n];
    const boundBox& bb = mesh.bounds();
    const scalar z0 = bb.min()[n];
    const scalar z1 = bb.max()[n];
    const scalar t = z1 - z0;
    Info<< "    2D mesh: empty direction " << axis << ", slab " << axis << " from "
        << z0 << " to " << z1 << " m: the bodies are their part in the slab"
        << " (mass, buoyancy, added mass and forces per slab depth " << t
        << " m)" << endl;

    auto& bodies = dem.bodies();
    for (size_t i = 0; i < bodies.size(); ++i)
    {
        if (dem.isWall(int(i))) continue;
        rigidBody& b = bodies[i];
        const word name(b.name);
        if (b.geometry->type() != "triangleMesh" && !b.dynamic())
        {
            // A fixed or prescribed sphere: the fluid sees its section (a
            // disk at the slab's cells); its mass plays no part
            Info<< "    body " << name << ": a " << b.geometry->type().c_str()
                << ", " << motionTypeName(b.motion).c_str() << ": kept as it"
                << " is (the fluid sees its section in the slab)" << endl;
            continue;
        }
        if (b.geometry->type() != "triangleMesh")
        {
            FatalIOErrorInFunction(dict)
                << "Body '" << name << "' of " << dict.name() << " is a "
                << b.geometry->type().c_str() << " in a 2D run (the mesh is one"
                << " cell thick along " << axis << ", with empty patches): the"
                << " fluid sees its section in the slab as an infinite prism;"
                << " give it as a triangleMesh prism along " << axis
                << " (a cylinder's STL) longer than the slab" << nl
                << exit(FatalIOError);
        }
        const axisAlignedBox wb = b.geometry->worldBox(b.pose);
        const scalar L = wb.max[n] - wb.min[n];
        if (wb.min[n] > z0 || wb.max[n] < z1)
        {
            FatalIOErrorInFunction(dict)
                << "Body '" << name << "' of " << dict.name() << " spans " << axis
                << " from " << wb.min[n] << " to " << wb.max[n] << " m; in a 2D"
                << " run (the mesh is one cell thick along " << axis << ", from "
                << z0 << " to " << z1 << " m) a body must pierce both empty"
                << " patches: make its STL longer than the slab" << nl
                << exit(FatalIOError);
        }
        if (b.velocity[n] != 0)
        {
            FatalIOErrorInFunction(dict)
                << "Body '" << name << "' of " << dict.name() << " has a velocity"
                << " along " << axis << ", the empty direction of the 2D mesh:"
                << " bodies move in the plane" << nl << exit(FatalIOError);
        }
        for (direction k = 0; k < 3; ++k)
        {
            if (k != n && b.angularVelocity[k] != 0)
            {
                FatalIOErrorInFunction(dict)
                    << "Body '" << name << "' of " << dict.name() << " has an"
                    << " angular velocity about " << "xyz"[k] << " in a 2D run"
                    << " (empty direction " << axis << "): bodies turn about "
                    << axis << " only" << nl << exit(FatalIOError);
            }
        }

        // The part in the slab, measured, against the prism's: the volume
        // times slab over length
        vec3 lo = wb.min, hi = wb.max;
        lo[n] = z0;
        hi[n] = z1;
        const scalar inSlab =
            boxFraction::of(*b.geometry, b.pose, lo, hi, 4)*(hi - lo).prod();
        const scalar prism = b.geometry->volume()*t/L;
        if (mag(inSlab - prism) > 0.01*prism)
        {
            FatalIOErrorInFunction(dict)
                << "Body '" << name << "' of " << dict.name() << " is not a"
                << " prism along " << axis << ", the empty direction of the 2D"
                << " mesh: its part in the slab has the volume " << inSlab
                << " m3, its volume times slab over length " << prism << " m3."
                << " Give a cylinder's (a prism's) STL along " << axis
                << nl << exit(FatalIOError);
        }

        // The surface in the world, mapped along n onto the slab
        triangleSoup s = b.geometry->surface();
        for (vec3& p : s.points)
        {
            p = b.pose.toWorld(p);
            p[n] = z0 + (p[n] - wb.min[n])*(t/L);
        }
        std::shared_ptr<const triangleMeshShape> slab;
        try
        {
            // (decomposed into convex pieces where the body was)
            const auto* m = shapeAs<triangleMeshShape>(*b.geometry);
            slab = std::make_shared<triangleMeshShape>
            (
                std::move(s), name + " (slab part)", false,
                m && !m->pieces().empty() ? convexDecomposition::defaultMaxPieces : 0
            );
        }
        catch (const coreError& err)
        {
            FatalIOErrorInFunction(dict)
                << "Body '" << name << "' of " << dict.name() << ": its part in"
                << " the slab: " << err.what() << nl << exit(FatalIOError);
        }
        b.geometry = slab;
        b.pose = slab->bodyInFile();
        b.lockTranslation[n] = 1;
        for (direction k = 0; k < 3; ++k)
        {
            if (k != n) b.lockRotation[k] = 1;
        }
        const vec3 J = b.inertia();
        Info<< "    body " << name << " in the slab: volume " << slab->volume()
            << " m3 (of " << L << " m along " << axis << ": "
            << b.geometry->volume()/inSlab << " of the measured slab part),"
            << " mass " << b.mass() << " kg, principal moments ("
            << J.x() << ' ' << J.y() << ' ' << J.z() << ") kg m2" << endl;
    }
}
