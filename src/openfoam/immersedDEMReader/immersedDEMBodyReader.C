#include "immersedDEMDictionaryReaders.H"
#include "immersedDEMReader.H"
#include "immersedDEMPatchSurface.H"
#include "immersedDEMSlabs.H"
#include "dictionaryChecks.H"
#include "immersedDEMInsertion.H"
#include "timeStepExplanation.H"
#include "initialOverlaps.H"
#include "sphereShape.H"
#include "triangleMeshShape.H"
#include "halfSpaceShape.H"
#include "wallMeshShape.H"
#include "surfaceFileIO.H"
#include "coreError.H"
#include "unitConversion.H"
#include "IOstreams.H"
#include "polyMesh.H"
#include "volFields.H"
#include "basicSymmetryFvPatchFields.H"

#include <algorithm>
#include <map>


using namespace immersedDEM;
using namespace Foam;


Eigen::Vector3i Foam::immersedDEMReaders::readLocks(const dictionary& d, const word& key)
{
    const vector v = d.getOrDefault<vector>(key, Zero);
    Eigen::Vector3i lock;
    for (direction i = 0; i < 3; ++i)
    {
        if (v[i] != 0 && v[i] != 1)
        {
            FatalIOErrorInFunction(d)
                << "Keyword '" << key << "' in " << d.name()
                << " takes 0 (free) or 1 (locked) per axis, not " << v << nl
                << exit(FatalIOError);
        }
        lock[i] = int(v[i]);
    }
    return lock;
}




const Foam::wordList Foam::immersedDEMReaders::surfaceKeywords
{
    "file", "parts", "scale", "checkSelfIntersection", "maxConvexPieces"
};


std::shared_ptr<const triangleMeshShape> Foam::immersedDEMReaders::readSurfaceShape
(
    const dictionary& d,
    const fileName& surfaceDir,
    const std::string& what,
    surfaceCache& surfaces
)
{
    const bool hasFile = d.found("file", keyType::LITERAL);
    const bool hasParts = d.found("parts", keyType::LITERAL);
    if (hasFile == hasParts)
    {
        FatalIOErrorInFunction(d)
            << what.c_str() << " in " << d.name() << ": give either 'file' (one"
            << " closed surface) or 'parts' (a list of convex closed surfaces"
            << " whose union is the body), not " << (hasFile ? "both" : "neither")
            << exit(FatalIOError);
    }
    const word key = hasFile ? "file" : "parts";
    const fileNameList files =
        hasFile ? fileNameList{d.get<fileName>("file")} : d.get<fileNameList>("parts");
    if (files.empty())
    {
        FatalIOErrorInFunction(d)
            << "Keyword 'parts' in " << d.name() << " is an empty list"
            << exit(FatalIOError);
    }
    const scalar scale = immersedDEMChecks::positiveOrDefault(d, "scale", 1);
    const bool selfCheck = d.getOrDefault<bool>("checkSelfIntersection", true);
    const int maxPieces = readMaxConvexPieces(d);
    std::string names = key + ":";
    for (const fileName& f : files) names += std::string(surfaceDir/f) + ";";
    std::shared_ptr<const triangleMeshShape>& shared =
        surfaces[std::make_tuple(names, double(scale), selfCheck, maxPieces)];
    try
    {
        if (!shared)
        {
            if (hasFile)
            {
                shared = triangleMeshShape::fromFile(surfaceDir/files[0], scale, selfCheck, maxPieces);
            }
            else
            {
                std::vector<triangleSoup> parts;
                for (const fileName& f : files)
                {
                    parts.push_back(surfaceFileIO::read(surfaceDir/f));
                    for (vec3& p : parts.back().points) p *= scale;
                }
                std::string shown;
                for (const fileName& f : files) shown += (shown.empty() ? "" : "+") + std::string(f);
                shared = triangleMeshShape::fromParts(std::move(parts), shown, selfCheck);
            }
            for (const std::string& w : shared->warnings())
            {
                WarningInFunction << what.c_str() << ": " << w.c_str() << endl;
            }
        }
    }
    catch (const coreError& err)
    {
        FatalIOErrorInFunction(d)
            << what.c_str() << ", keyword '" << key << "' in " << d.name()
            << ":" << nl << "    " << err.what() << nl
            << exit(FatalIOError);
    }
    return shared;
}


int Foam::immersedDEMReaders::readMaxConvexPieces(const dictionary& d)
{
    const scalar n = immersedDEMChecks::inRangeOrDefault
    (
        d, "maxConvexPieces", 0, 1000, convexDecomposition::defaultMaxPieces
    );
    if (n != std::floor(n))
    {
        FatalIOErrorInFunction(d)
            << "Keyword 'maxConvexPieces' in " << d.name() << " is " << n
            << "; it must be a whole number (0: keep the octree virtual mesh)"
            << exit(FatalIOError);
    }
    return int(n);
}


std::string Foam::immersedDEMReaders::contactPathOf(const triangleMeshShape& s)
{
    if (s.convex())
    {
        return "convex: exact intersection";
    }
    if (!s.pieces().empty())
    {
        return s.piecesNote() + ": exact intersection of the pieces";
    }
    return s.piecesNote() + "; octree virtual mesh (set maxConvexPieces to change)";
}


rigidBody Foam::immersedDEMReaders::readBody
(
    const word& name,
    const dictionary& d,
    const fileName& surfaceDir,
    const std::vector<contactMaterial>& materials,
    surfaceCache& surfaces
)
{
    const word shapeType = immersedDEMChecks::oneOf(d, "shape", {"sphere", "triangleMesh"});
    wordList allowed
    {
        "shape", "density", "material", "position", "rotationAxis",
        "rotationAngle", "velocity", "angularVelocity", "motion",
        "lockTranslation", "lockRotation"
    };
    std::shared_ptr<const shape> geometry;
    if (shapeType == "sphere")
    {
        allowed.append("radius");
        immersedDEMChecks::allowOnly(d, allowed);
        geometry = std::make_shared<sphereShape>(immersedDEMChecks::positive(d, "radius"));
    }
    else
    {
        allowed.append(surfaceKeywords);
        immersedDEMChecks::allowOnly(d, allowed);
        geometry = readSurfaceShape(d, surfaceDir, "Body '" + name + "'", surfaces);
    }

    rigidBody b
    (
        name, geometry, immersedDEMChecks::positive(d, "density"),
        materialIndex(d, materials, name)
    );

    const vector axis = d.getOrDefault<vector>("rotationAxis", vector(0, 0, 1));
    if (mag(axis) == 0)
    {
        FatalIOErrorInFunction(d)
            << "Keyword 'rotationAxis' in " << d.name() << " is a zero vector"
            << exit(FatalIOError);
    }
    const scalar angle = degToRad(d.getOrDefault<scalar>("rotationAngle", 0));
    // The rotation turns the shape as given in its file about its centroid
    const quat R = bodyPose::axisAngle(immersedDEMReader::toCore(axis), angle);
    b.pose = bodyPose
    (
        immersedDEMReader::toCore(d.get<vector>("position")),
        R*geometry->bodyInFile().orientation()
    );
    b.velocity = immersedDEMReader::toCore(d.getOrDefault<vector>("velocity", Zero));
    b.angularVelocity =
        immersedDEMReader::toCore(d.getOrDefault<vector>("angularVelocity", Zero));
    b.motion = motionTypeFromName
    (
        immersedDEMChecks::oneOfOrDefault(d, "motion", {"free", "fixed", "prescribed"}, "free")
    );
    b.lockTranslation = readLocks(d, "lockTranslation");
    b.lockRotation = readLocks(d, "lockRotation");

    const scalar V = geometry->volume();
    const vec3 J = b.inertia();
    Info<< "    body " << name << ": " << shapeType
        << ", volume " << V << " m3, mass " << b.mass()
        << " kg, principal moments (" << J.x() << ' ' << J.y() << ' ' << J.z()
        << ") kg m2" << endl;
    if (const auto* m = shapeAs<triangleMeshShape>(*geometry))
    {
        Info<< "        contacts: " << contactPathOf(*m).c_str() << endl;
    }
    return b;
}


// The squeeze film a wall takes (lubrication.H), from its fluid side: a
// quarter of a no-slip wall's where the fluid slips along it, none where
// the fluid passes through it (film none: a distributor or a screen given
// as a wall for the bodies only). Given by 'film', or for a patch wall by
// the velocity's condition on each of its patches
namespace
{
    double filmFactorOf(const word& kind)
    {
        return kind == "slip" ? 0.25 : kind == "none" ? 0 : 1;
    }
}


void Foam::immersedDEMReaders::readWallFilm
(
    const word& name,
    const dictionary& d,
    const std::vector<label>& patchOfFace,
    const polyMesh* mesh,
    rigidBody& w
)
{
    if (d.found("film"))
    {
        const word kind =
            immersedDEMChecks::oneOf(d, "film", {"noSlip", "slip", "none"});
        w.filmFactor = filmFactorOf(kind);
        Info<< "        its lubrication film: " << kind << " (keyword film)"
            << endl;
        return;
    }
    if (patchOfFace.empty() || !mesh)
    {
        return;
    }
    // A patch wall: each patch's velocity condition (slip, symmetry and
    // symmetryPlane, the basic symmetry conditions: the fluid slips; any
    // other: the wall's film as for a no-slip wall)
    const word UName("U");
    const volVectorField* U = mesh->findObject<volVectorField>(UName);
    if (!U)
    {
        Info<< "        its lubrication film: no-slip (no field " << UName
            << " to read the patches' conditions from; keyword film sets it)"
            << endl;
        return;
    }
    std::map<label, double> factorOfPatch;
    for (const label patchi : patchOfFace)
    {
        if (factorOfPatch.count(patchi)) continue;
        const fvPatchVectorField& Ub = U->boundaryField()[patchi];
        const word t = Ub.type();
        const bool slips = isA<basicSymmetryFvPatchVectorField>(Ub);
        factorOfPatch[patchi] = filmFactorOf(slips ? "slip" : "noSlip");
        Info<< "        its lubrication film on patch "
            << mesh->boundaryMesh()[patchi].name() << ": "
            << (slips ? "slip" : "noSlip") << " (" << UName << " is " << t
            << " there)" << endl;
    }
    const double first = factorOfPatch.begin()->second;
    bool uniform = true;
    for (const auto& [patchi, f] : factorOfPatch) uniform = uniform && f == first;
    w.filmFactor = first;
    if (!uniform)
    {
        auto perFace = std::make_shared<std::vector<double>>(patchOfFace.size());
        for (size_t i = 0; i < patchOfFace.size(); ++i)
        {
            (*perFace)[i] = factorOfPatch[patchOfFace[i]];
        }
        w.faceFilm = perFace;
    }
}


rigidBody Foam::immersedDEMReaders::readWall
(
    const word& name,
    const dictionary& d,
    const fileName& surfaceDir,
    const std::vector<contactMaterial>& materials,
    double thickness,
    const polyMesh* mesh
)
{
    const word type = immersedDEMChecks::oneOf(d, "type", {"plane", "triSurface", "patch"});
    std::vector<label> patchOfFace;
    std::shared_ptr<const shape> geometry;
    bodyPose pose;
    if (type == "plane")
    {
        immersedDEMChecks::allowOnly
        (
            d, {"type", "point", "normal", "material", "velocity", "film"}
        );
        const vector n = d.get<vector>("normal");
        if (mag(n) == 0)
        {
            FatalIOErrorInFunction(d)
                << "Keyword 'normal' in " << d.name() << " is a zero vector"
                << exit(FatalIOError);
        }
        geometry = std::make_shared<halfSpaceShape>();
        pose = halfSpaceShape::poseOf
        (
            immersedDEMReader::toCore(d.get<vector>("point")), immersedDEMReader::toCore(n)
        );
    }
    else if (type == "patch")
    {
        immersedDEMChecks::allowOnly(d, {"type", "patches", "material", "film"});
        if (!mesh)
        {
            FatalIOErrorInFunction(d)
                << "Wall '" << name << "' in " << d.name() << " is of type patch,"
                << " which needs the CFD mesh: use it with the immersedDEM"
                << " function object, or type plane or triSurface here" << nl
                << exit(FatalIOError);
        }
        try
        {
            std::vector<wallMeshShape::edge> continued;
            label openingEdges = 0;
            triangleSoup s = immersedDEMPatchSurface::of
            (
                *mesh, d, name, &patchOfFace, &continued, thickness, &openingEdges
            );
            const auto wall =
                std::make_shared<wallMeshShape>(std::move(s), name, thickness, continued);
            geometry = wall;
            // (the openings' sides end in rim edges of their own)
            const label ends = label(wall->rimEdges()) - openingEdges;
            if (!continued.empty() || openingEdges > 0 || ends > 0)
            {
                Info<< "    wall " << name << ": continued across " << continued.size()
                    << " edges, where it meets the rest of the boundary at an angle"
                    << " (exact flat contacts up to them)";
                if (openingEdges > 0)
                {
                    Info<< "; " << openingEdges << " edges of an opening in its own"
                        << " plane (an outlet in a floor) given sides " << thickness
                        << " m deep";
                }
                if (ends > 0)
                {
                    Info<< "; it ends at " << ends << " other edges (a baffle's)";
                }
                Info<< endl;
            }
        }
        catch (const coreError& err)
        {
            FatalIOErrorInFunction(d)
                << "Wall '" << name << "', keyword 'patches' in " << d.name()
                << ":" << nl << "    " << err.what() << nl
                << exit(FatalIOError);
        }
    }
    else
    {
        immersedDEMChecks::allowOnly
        (
            d, {"type", "file", "scale", "flipNormals", "material", "velocity", "film"}
        );
        const fileName file = surfaceDir/d.get<fileName>("file");
        try
        {
            triangleSoup s = surfaceFileIO::read(file);
            const scalar scale = immersedDEMChecks::positiveOrDefault(d, "scale", 1);
            for (vec3& p : s.points) p *= scale;
            if (d.getOrDefault<bool>("flipNormals", false))
            {
                for (immersedDEM::triFace& f : s.faces) std::swap(f[1], f[2]);
            }
            geometry = std::make_shared<wallMeshShape>(std::move(s), file, thickness);
        }
        catch (const coreError& err)
        {
            FatalIOErrorInFunction(d)
                << "Wall '" << name << "', keyword 'file' in " << d.name()
                << ":" << nl << "    " << err.what() << nl
                << exit(FatalIOError);
        }
    }
    rigidBody w(name, geometry, 1, materialIndex(d, materials, name));
    w.pose = pose;
    w.velocity = immersedDEMReader::toCore(d.getOrDefault<vector>("velocity", Zero));
    w.motion = w.velocity.norm() > 0 ? motionType::prescribed : motionType::fixed;
    Info<< "    wall " << name << ": " << type << endl;
    readWallFilm(name, d, patchOfFace, mesh, w);
    return w;
}
