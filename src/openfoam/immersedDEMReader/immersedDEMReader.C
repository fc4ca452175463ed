#include "immersedDEMReader.H"
#include "immersedDEMDictionaryReaders.H"
#include "immersedDEMPatchSurface.H"
#include "immersedDEMSlabs.H"
#include "immersedDEMPeriodic.H"
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
using namespace Foam::immersedDEMReaders;


std::unique_ptr<immersedDEM::demSolver> Foam::immersedDEMReader::read
(
    const dictionary& dict,
    const fileName& surfaceDir,
    const vector& gravity,
    const polyMesh* mesh,
    std::vector<immersedDEM::bodyStream>* streams,
    immersedDEM::demSettings* settingsRead
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
    if (settingsRead)
    {
        *settingsRead = settings;
    }

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

    // Periodic directions (cyclic patches), before the insertion: the
    // bodies' sizes are checked against the periods
    if (mesh)
    {
        const periodicBox periodic = immersedDEMPeriodic::fromMesh(*mesh, dict);
        if (periodic.active())
        {
            try
            {
                dem->setPeriodic(periodic);
            }
            catch (const coreError& err)
            {
                FatalIOErrorInFunction(dict)
                    << "In " << dict.name() << ": " << err.what() << nl
                    << exit(FatalIOError);
            }
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
