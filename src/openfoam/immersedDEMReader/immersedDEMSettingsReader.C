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

#include <algorithm>
#include <cstdio>
#include <map>


using namespace immersedDEM;
using namespace Foam;


std::vector<contactMaterial> Foam::immersedDEMReaders::readMaterials(const dictionary& all)
{
    std::vector<contactMaterial> materials;
    for (const entry& e : all)
    {
        const dictionary& d = immersedDEMChecks::subDictEntry(all, e, "material properties");
        immersedDEMChecks::allowOnly
        (
            d,
            {
                "youngsModulus", "poissonsRatio", "restitution", "friction",
                "rollingFriction"
            }
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
        // Defaults that give a pile and a bed their shape
        // (caseTemplates/README.md, materials); a material made
        // frictionless (friction 0) gets no rolling friction either
        m.friction =
            immersedDEMChecks::inRangeOrDefault(d, "friction", 0, 100, defaultFriction);
        m.rollingFriction = immersedDEMChecks::inRangeOrDefault
        (
            d, "rollingFriction", 0, 1, m.friction > 0 ? defaultRollingFriction : 0
        );
        // Logged with what was defaulted: friction and rolling friction
        // change a pile's shape
        auto given = [&d](const char* key)
        {
            return d.found(key) ? "" : " (default)";
        };
        // (6 digits whatever the case's writePrecision)
        char line[256];
        std::snprintf
        (
            line, sizeof(line),
            "youngsModulus %g Pa, poissonsRatio %g, restitution %g%s, friction %g%s,"
            " rollingFriction %g%s",
            m.youngsModulus, m.poissonsRatio, m.restitution, given("restitution"),
            m.friction, given("friction"), m.rollingFriction, given("rollingFriction")
        );
        Info<< "    material " << e.keyword() << ": " << line << endl;
        materials.push_back(m);
    }
    if (materials.empty())
    {
        FatalIOErrorInFunction(all)
            << "No material in " << all.name() << exit(FatalIOError);
    }
    return materials;
}


int Foam::immersedDEMReaders::materialIndex
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


demSettings Foam::immersedDEMReaders::readSettings(const dictionary& top)
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
        immersedDEMChecks::allowOnly(*l, {"active", "activation", "pairActivation", "roughness"});
        s.lubrication.active = l->getOrDefault<bool>("active", s.lubrication.active);
        s.lubrication.activation =
            immersedDEMChecks::inRangeOrDefault(*l, "activation", 0.1, 10, s.lubrication.activation);
        s.lubrication.pairActivation =
            immersedDEMChecks::inRangeOrDefault(*l, "pairActivation", 0.1, 10, s.lubrication.pairActivation);
        s.lubrication.roughness =
            immersedDEMChecks::inRangeOrDefault(*l, "roughness", 1e-6, 0.1, s.lubrication.roughness);
    }
    else if (top.found("lubrication"))
    {
        FatalIOErrorInFunction(top)
            << "Keyword 'lubrication' in " << top.name()
            << " must be a dictionary: lubrication { active yes; activation 1.7;"
            << " pairActivation 2.5; roughness 1e-3; }" << nl << exit(FatalIOError);
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
