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

#include <algorithm>
#include <map>

using namespace immersedDEM;

namespace
{

using namespace Foam;

std::vector<contactMaterial> readMaterials(const dictionary& all)
{
    std::vector<contactMaterial> materials;
    for (const entry& e : all)
    {
        const dictionary& d = immersedDEMChecks::subDictEntry(all, e, "material properties");
        immersedDEMChecks::allowOnly
        (
            d, {"youngsModulus", "poissonsRatio", "restitution", "friction"}
        );
        contactMaterial m;
        m.name = e.keyword();
        // From soft gels (1e3 Pa) to above diamond (1.2e12 Pa): outside,
        // a contact cannot hold a body up against its weight at any
        // usable step (below), or the step becomes vanishingly small
        // (above)
        m.youngsModulus = immersedDEMChecks::inRange(d, "youngsModulus", 1e3, 1e13);
        m.poissonsRatio = immersedDEMChecks::inRange(d, "poissonsRatio", 0, 0.5);
        m.restitution = immersedDEMChecks::inRangeOrDefault(d, "restitution", 1e-6, 1, 1);
        m.friction = immersedDEMChecks::inRangeOrDefault(d, "friction", 0, 100, 0);
        materials.push_back(m);
    }
    if (materials.empty())
    {
        FatalIOErrorInFunction(all)
            << "No material in " << all.name() << exit(FatalIOError);
    }
    return materials;
}


int materialIndex
(
    const dictionary& d,
    const std::vector<contactMaterial>& materials,
    const word& owner
)
{
    const word name = d.get<word>("material");
    wordList names;
    for (size_t i = 0; i < materials.size(); ++i)
    {
        names.append(materials[i].name);
        if (materials[i].name == name) return int(i);
    }
    FatalIOErrorInFunction(d)
        << "Unknown material '" << name << "' for '" << owner << "' in "
        << d.name() << nl << "Valid materials: " << names << nl
        << exit(FatalIOError);
    return -1;
}


demSettings readSettings(const dictionary& top)
{
    demSettings s;
    if (const dictionary* c = top.findDict("contact"))
    {
        immersedDEMChecks::allowOnly
        (
            *c,
            {
                "method", "level", "cellSize", "law", "characteristicLength", "normal",
                "initialOverlaps", "reuse", "convexExact", "volumeTolerance"
            }
        );
        wordList methods;
        for (const std::string& m : overlapEngine::types()) methods.append(word(m));
        s.overlapMethod = immersedDEMChecks::oneOfOrDefault(*c, "method", methods, "virtualMesh");
        s.overlap.level = label
        (
            immersedDEMChecks::inRangeOrDefault
            (
                *c, "level", 0, overlapSettings::maxLevel, overlapSettings::defaultLevel
            )
        );
        s.overlap.h = immersedDEMChecks::positiveOrDefault(*c, "cellSize", 0);
        // The resolution of each pair type from a tolerance on the
        // overlap volume, unless cellSize or level fix it for all
        const bool fixed = c->found("cellSize") || c->found("level");
        if (fixed && c->found("volumeTolerance"))
        {
            FatalIOErrorInFunction(*c)
                << "Keywords 'volumeTolerance' and '"
                << (c->found("cellSize") ? "cellSize" : "level") << "' in "
                << c->name() << " exclude each other: volumeTolerance chooses"
                << " the cell size and level of each pair type; cellSize and"
                << " level fix them for all pairs" << nl << exit(FatalIOError);
        }
        s.volumeTolerance =
            fixed
          ? 0
          : immersedDEMChecks::inRangeOrDefault
            (
                *c, "volumeTolerance", 1e-4, 0.2, contactResolution::defaultTolerance
            );
        wordList laws;
        for (const std::string& l : contactLaw::types()) laws.append(word(l));
        s.contactLaw = immersedDEMChecks::oneOfOrDefault(*c, "law", laws, demSettings().contactLaw);
        s.characteristicLength =
            immersedDEMChecks::positiveOrDefault(*c, "characteristicLength", 0);
        wordList normals;
        normals.append(word("fittedPlane"));
        normals.append(word("areaVector"));
        s.overlap.areaVectorNormal =
            immersedDEMChecks::oneOfOrDefault(*c, "normal", normals, "fittedPlane")
         == "areaVector";
        wordList overlapActions;
        overlapActions.append(word("keep"));
        overlapActions.append(word("separate"));
        s.separateInitialOverlaps =
            immersedDEMChecks::oneOfOrDefault(*c, "initialOverlaps", overlapActions, "separate")
         == "separate";
        s.reuseContacts = c->getOrDefault<bool>("reuse", true);
        s.overlap.convexExact = c->getOrDefault<bool>("convexExact", true);
    }
    if (const dictionary* l = top.findDict("lubrication"))
    {
        immersedDEMChecks::allowOnly(*l, {"active", "activation", "roughness"});
        s.lubrication.active = l->getOrDefault<bool>("active", s.lubrication.active);
        s.lubrication.activation =
            immersedDEMChecks::inRangeOrDefault(*l, "activation", 0.1, 10, s.lubrication.activation);
        s.lubrication.roughness =
            immersedDEMChecks::inRangeOrDefault(*l, "roughness", 1e-6, 0.1, s.lubrication.roughness);
    }
    else if (top.found("lubrication"))
    {
        FatalIOErrorInFunction(top)
            << "Keyword 'lubrication' in " << top.name()
            << " must be a dictionary: lubrication { active yes; activation 1;"
            << " roughness 1e-3; }" << nl << exit(FatalIOError);
    }
    if (const dictionary* t = top.findDict("time"))
    {
        immersedDEMChecks::allowOnly(*t, {"deltaT", "stepsPerContact", "referenceSpeed"});
        s.deltaT = immersedDEMChecks::positiveOrDefault(*t, "deltaT", 0);
        s.stepsPerContact =
            label(immersedDEMChecks::inRangeOrDefault(*t, "stepsPerContact", 10, 1e6, 30));
        s.referenceSpeed = immersedDEMChecks::positiveOrDefault(*t, "referenceSpeed", 0.1);
    }
    return s;
}


Eigen::Vector3i readLocks(const dictionary& d, const word& key)
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


//- The surfaces read so far, by file, scale and self-intersection check:
//  bodies of one surface share it (one search structure, curvature and
//  set of mass properties; each body holds only its pose)
using surfaceCache =
    std::map<std::tuple<std::string, double, bool>, std::shared_ptr<const triangleMeshShape>>;


rigidBody readBody
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
        allowed.append(wordList{"file", "scale", "checkSelfIntersection"});
        immersedDEMChecks::allowOnly(d, allowed);
        const fileName file = surfaceDir/d.get<fileName>("file");
        const scalar scale = immersedDEMChecks::positiveOrDefault(d, "scale", 1);
        const bool selfCheck = d.getOrDefault<bool>("checkSelfIntersection", true);
        std::shared_ptr<const triangleMeshShape>& shared =
            surfaces[std::make_tuple(std::string(file), double(scale), selfCheck)];
        try
        {
            if (!shared)
            {
                shared = triangleMeshShape::fromFile(file, scale, selfCheck);
                for (const std::string& w : shared->warnings())
                {
                    WarningInFunction << "Body " << name << ": " << w.c_str() << endl;
                }
            }
            geometry = shared;
        }
        catch (const coreError& err)
        {
            FatalIOErrorInFunction(d)
                << "Body '" << name << "', keyword 'file' in " << d.name()
                << ":" << nl << "    " << err.what() << nl
                << exit(FatalIOError);
        }
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
    return b;
}


rigidBody readWall
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
    std::shared_ptr<const shape> geometry;
    bodyPose pose;
    if (type == "plane")
    {
        immersedDEMChecks::allowOnly
        (
            d, {"type", "point", "normal", "material", "velocity"}
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
        immersedDEMChecks::allowOnly(d, {"type", "patches", "material"});
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
            geometry = std::make_shared<wallMeshShape>
            (
                immersedDEMPatchSurface::of(*mesh, d, name), name, thickness
            );
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
            d, {"type", "file", "scale", "flipNormals", "material", "velocity"}
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
    return w;
}


} // End anonymous namespace


std::unique_ptr<immersedDEM::demSolver> Foam::immersedDEMReader::read
(
    const dictionary& dict,
    const fileName& surfaceDir,
    const vector& gravity,
    const polyMesh* mesh,
    std::vector<immersedDEM::bodyStream>* streams
)
{
    // Before the dictionary's own reading merged them away: two bodies of
    // one name, a keyword given twice
    const std::map<std::string, label> lines = immersedDEMChecks::noDuplicateKeywords
    (
        dict.name(),
        {
            {"bodies", "bodies"}, {"materials", "materials"}, {"walls", "walls"},
            {"templates", "templates"}, {"insertion", "insertion"}
        }
    );
    immersedDEMChecks::allowOnly
    (
        dict,
        {
            "materials", "contact", "time", "bodies", "walls", "restart",
            "templates", "insertion", "removal", "lubrication"
        }
    );
    // restart (yes/no) is used by immersedDEMState: checked here
    (void)dict.getOrDefault<bool>("restart", true);

    const std::vector<contactMaterial> materials = readMaterials(dict.subDict("materials"));
    demSettings settings = readSettings(dict);
    settings.gravity = toCore(gravity);

    std::unique_ptr<demSolver> dem;
    try
    {
        dem.reset(new demSolver(materials, settings));
    }
    catch (const coreError& err)
    {
        FatalIOErrorInFunction(dict)
            << "In " << dict.name() << ": " << err.what() << nl << exit(FatalIOError);
    }

    // Listed bodies; with an insertion the list may be absent
    const dictionary emptyBodies;
    const dictionary& bodies =
        dict.found("insertion") && !dict.found("bodies")
      ? emptyBodies : dict.subDict("bodies");
    double largest = 0;
    auto lineOf = [&lines](const std::string& path)
    {
        const auto it = lines.find(path);
        return it == lines.end() ? label(-1) : it->second;
    };
    surfaceCache surfaces;
    for (const entry& e : bodies)
    {
        const dictionary& d = immersedDEMChecks::subDictEntry(bodies, e, "a body's description");
        rigidBody b = readBody(e.keyword(), d, surfaceDir, materials, surfaces);
        largest = std::max(largest, 2*b.geometry->boundingRadius());
        try
        {
            dem->addBody(std::move(b));
        }
        catch (const coreError& err)
        {
            FatalIOErrorInFunction(d)
                << "In " << d.name() << ": " << err.what() << nl << exit(FatalIOError);
        }
    }

    const auto templates = immersedDEMInsertion::readTemplates(dict, surfaceDir, materials);
    largest = std::max(largest, immersedDEMInsertion::largestDiameter(dict, templates));

    if (const dictionary* walls = dict.findDict("walls"))
    {
        for (const entry& e : *walls)
        {
            const dictionary& d = immersedDEMChecks::subDictEntry(*walls, e, "a wall's description");
            if (bodies.found(e.keyword(), keyType::LITERAL))
            {
                // Contacts, outputs and the restart state name bodies and
                // walls alike
                FatalIOErrorInFunction(d)
                    << "Wall '" << e.keyword() << "' (line "
                    << lineOf("walls/" + e.keyword()) << ") has the name of body '"
                    << e.keyword() << "' (line " << lineOf("bodies/" + e.keyword())
                    << ") in " << dict.name()
                    << ": bodies and walls need distinct names" << nl
                    << exit(FatalIOError);
            }
            dem->addBody
            (
                readWall(e.keyword(), d, surfaceDir, materials, std::max(largest, SMALL), mesh),
                true
            );
        }
    }

    // After the walls: inserted bodies are placed apart from them
    immersedDEMInsertion::insert(dict, surfaceDir, templates, *dem);

    // 2D: the bodies are their part in the slab
    if (mesh)
    {
        immersedDEMSlabs::toSlab(*dem, *mesh, dict);
    }

    // Insertions over time: the virtual mesh's cell size from the smallest
    // body that can ever be present (the same at a restart, whatever is
    // present then)
    std::vector<bodyStream> newStreams =
        immersedDEMInsertion::readStreams(dict, surfaceDir, templates);
    if (!newStreams.empty() && !(dem->cellSize() > 0))
    {
        double dMin = std::numeric_limits<double>::max();
        for (size_t i = 0; i < dem->bodies().size(); ++i)
        {
            if (!dem->isWall(i)) dMin = std::min(dMin, 2*dem->bodies()[i].equivalentRadius());
        }
        for (const bodyStream& st : newStreams)
        {
            dMin = std::min(dMin, st.smallestDiameter());
        }
        dem->setCellSize(overlapSettings::defaultCellSize(dMin));
    }
    if (streams)
    {
        *streams = std::move(newStreams);
    }

    // The step at the start, and why (it follows the speeds in the run)
    Info<< "    " << timeStepExplanation::of(*dem).text(*dem).c_str() << endl;
    return dem;
}


void Foam::immersedDEMReader::reportMessages(immersedDEM::demSolver& dem)
{
    for (const std::string& m : dem.takeMessages())
    {
        Info<< "    " << m.c_str() << endl;
    }
}


void Foam::immersedDEMReader::initialOverlaps
(
    immersedDEM::demSolver& dem,
    const fileName& dictName
)
{
    namespace io = immersedDEM::initialOverlaps;
    // (the overlap engine's errors name the contact settings)
    try
    {
        const std::vector<immersedDEM::initialOverlap> found = io::find(dem);
        if (found.empty())
        {
            Info<< "    No overlaps at the start" << endl;
            return;
        }
        if (!dem.settings().separateInitialOverlaps)
        {
            WarningInFunction
                << found.size() << " pairs overlap at the start (" << dictName
                << "); the contacts push them apart in the first steps:" << nl
                << io::text(dem, found).c_str()
                << "    (contact/initialOverlaps keep; 'separate', the default,"
                << " moves them apart before the first step)" << endl;
            return;
        }
        Info<< "    " << found.size() << " pairs overlap at the start:" << nl
            << io::text(dem, found).c_str();
        const immersedDEM::overlapSeparation s = io::separate(dem);
        Info<< "    initialOverlaps separate: " << s.bodiesMoved << " bodies moved apart"
            << " in " << s.iterations << " iterations, the farthest by "
            << s.largestMove << " m" << endl;
        if (!s.remaining.empty())
        {
            WarningInFunction
                << s.remaining.size() << " pairs of " << dictName
                << " still overlap after " << s.iterations
                << " separation iterations (walls or fixed bodies into each"
                << " other, or a body held between two walls):" << nl
                << io::text(dem, s.remaining).c_str() << endl;
        }
    }
    catch (const coreError& err)
    {
        FatalErrorInFunction
            << "Overlaps at the start of " << dictName << ": " << err.what()
            << " (sub-dictionary contact)" << exit(FatalError);
    }
}
