#include "immersedDEMInsertion.H"
#include "immersedDEMReader.H"
#include "immersedDEMDictionaryReaders.H"
#include "dictionaryChecks.H"
#include "sphereShape.H"
#include "triangleMeshShape.H"
#include "coreError.H"
#include "unitConversion.H"
#include "IOstreams.H"

using namespace immersedDEM;

namespace
{

using namespace Foam;

// The template of 'key' in d: one of templates, with the list in the error
const bodyTemplate& findTemplate
(
    const dictionary& d,
    const std::map<word, bodyTemplate>& templates
)
{
    const word name = d.get<word>("template");
    const auto it = templates.find(name);
    if (it == templates.end())
    {
        wordList names;
        for (const auto& t : templates) names.append(t.first);
        FatalIOErrorInFunction(d)
            << "Unknown template '" << name << "', keyword 'template' in "
            << d.name() << nl << "Templates (in 'templates'): " << names << nl
            << exit(FatalIOError);
    }
    return it->second;
}


sizeDistribution readSize(const dictionary& d)
{
    const word type = immersedDEMChecks::oneOf
    (
        d, "distribution", {"fixed", "uniform", "normal", "table"}
    );
    try
    {
        if (type == "fixed")
        {
            immersedDEMChecks::allowOnly(d, {"distribution", "value"});
            return sizeDistribution::fixed(immersedDEMChecks::positive(d, "value"));
        }
        if (type == "uniform")
        {
            immersedDEMChecks::allowOnly(d, {"distribution", "min", "max"});
            const scalar lo = immersedDEMChecks::positive(d, "min");
            const scalar hi = immersedDEMChecks::positive(d, "max");
            if (lo > hi)
            {
                FatalIOErrorInFunction(d)
                    << "Keywords 'min' " << lo << " > 'max' " << hi << " in "
                    << d.name() << exit(FatalIOError);
            }
            return sizeDistribution::uniform(lo, hi);
        }
        if (type == "normal")
        {
            immersedDEMChecks::allowOnly
            (
                d, {"distribution", "mean", "standardDeviation", "min", "max"}
            );
            const scalar m = immersedDEMChecks::positive(d, "mean");
            const scalar sd = immersedDEMChecks::positive(d, "standardDeviation", true);
            const scalar lo =
                immersedDEMChecks::positiveOrDefault(d, "min", std::max(m - 3*sd, 1e-3*m));
            const scalar hi = immersedDEMChecks::positiveOrDefault(d, "max", m + 3*sd);
            if (!(lo <= m && m <= hi))
            {
                FatalIOErrorInFunction(d)
                    << "Keywords 'min' " << lo << ", 'mean' " << m << ", 'max' "
                    << hi << " in " << d.name() << ": min <= mean <= max is needed"
                    << exit(FatalIOError);
            }
            return sizeDistribution::normal(m, sd, lo, hi);
        }
        immersedDEMChecks::allowOnly(d, {"distribution", "values"});
        const List<Tuple2<scalar, scalar>> rows(d.get<List<Tuple2<scalar, scalar>>>("values"));
        std::vector<std::pair<double, double>> table;
        scalar sum = 0;
        for (const auto& r : rows)
        {
            if (!(r.first() > 0) || !(r.second() >= 0))
            {
                FatalIOErrorInFunction(d)
                    << "Keyword 'values' in " << d.name() << ": row (" << r.first()
                    << ' ' << r.second() << ") needs a factor > 0 and a weight >= 0"
                    << exit(FatalIOError);
            }
            sum += r.second();
            table.emplace_back(r.first(), r.second());
        }
        if (!(sum > 0))
        {
            FatalIOErrorInFunction(d)
                << "Keyword 'values' in " << d.name()
                << ": give rows (factor weight) with weights summing to more than 0"
                << exit(FatalIOError);
        }
        return sizeDistribution::table(table);
    }
    catch (const coreError& err)
    {
        FatalIOErrorInFunction(d)
            << "In " << d.name() << ": " << err.what() << exit(FatalIOError);
    }
    return sizeDistribution();
}


vec3 vectorOrZero(const dictionary& d, const word& key)
{
    return immersedDEMReader::toCore(d.getOrDefault<vector>(key, Zero));
}


bodyTemplate readTemplate
(
    const word& name,
    const dictionary& d,
    const fileName& surfaceDir,
    const std::vector<contactMaterial>& materials
)
{
    const word shapeType = immersedDEMChecks::oneOf(d, "shape", {"sphere", "triangleMesh"});
    wordList allowed
    {
        "shape", "material", "density", "size", "orientation", "rotationAxis",
        "rotationAngle", "velocity", "velocitySpread", "angularVelocity"
    };
    bodyTemplate t;
    t.name = name;
    if (shapeType == "sphere")
    {
        allowed.append("radius");
        immersedDEMChecks::allowOnly(d, allowed);
        t.geometry = std::make_shared<sphereShape>(immersedDEMChecks::positive(d, "radius"));
    }
    else
    {
        allowed.append(immersedDEMReaders::surfaceKeywords);
        immersedDEMChecks::allowOnly(d, allowed);
        immersedDEMReaders::surfaceCache own;
        const auto s = immersedDEMReaders::readSurfaceShape
        (
            d, surfaceDir, "Template '" + name + "'", own
        );
        Info<< "    template " << name << " contacts: "
            << immersedDEMReaders::contactPathOf(*s).c_str() << endl;
        t.geometry = s;
    }

    const word material = d.get<word>("material");
    t.material = -1;
    wordList names;
    for (size_t i = 0; i < materials.size(); ++i)
    {
        names.append(materials[i].name);
        if (materials[i].name == material) t.material = int(i);
    }
    if (t.material < 0)
    {
        FatalIOErrorInFunction(d)
            << "Unknown material '" << material << "' for template '" << name
            << "' in " << d.name() << nl << "Valid materials: " << names << nl
            << exit(FatalIOError);
    }
    t.density = immersedDEMChecks::positive(d, "density");

    if (const dictionary* s = d.findDict("size"))
    {
        t.size = readSize(*s);
    }
    else if (d.found("size"))
    {
        FatalIOErrorInFunction(d)
            << "Keyword 'size' in " << d.name() << " must be a dictionary"
            << " { distribution fixed|uniform|normal|table; ... }" << exit(FatalIOError);
    }

    t.randomOrientation =
        immersedDEMChecks::oneOfOrDefault(d, "orientation", {"fixed", "random"}, "fixed")
     == "random";
    if (t.randomOrientation && (d.found("rotationAxis") || d.found("rotationAngle")))
    {
        FatalIOErrorInFunction(d)
            << "Keywords 'rotationAxis' and 'rotationAngle' in " << d.name()
            << " need 'orientation fixed' (the orientation is random)"
            << exit(FatalIOError);
    }
    const vector axis = d.getOrDefault<vector>("rotationAxis", vector(0, 0, 1));
    if (mag(axis) == 0)
    {
        FatalIOErrorInFunction(d)
            << "Keyword 'rotationAxis' in " << d.name() << " is a zero vector"
            << exit(FatalIOError);
    }
    t.orientation = bodyPose::axisAngle
    (
        immersedDEMReader::toCore(axis), degToRad(d.getOrDefault<scalar>("rotationAngle", 0))
    );
    t.velocity = vectorOrZero(d, "velocity");
    t.velocitySpread = vectorOrZero(d, "velocitySpread");
    if (t.velocitySpread.minCoeff() < 0)
    {
        FatalIOErrorInFunction(d)
            << "Keyword 'velocitySpread' in " << d.name() << " must be >= 0 per component"
            << exit(FatalIOError);
    }
    t.angularVelocity = vectorOrZero(d, "angularVelocity");

    const scalar V = t.geometry->volume();
    Info<< "    template " << name << ": " << shapeType << ", volume " << V
        << " m3 at size factor 1, size factor in [" << t.size.minimum() << ", "
        << t.size.maximum() << "]" << endl;
    return t;
}


insertionRegion readRegionDict(const dictionary& d, const fileName& surfaceDir)
{
    const word type = immersedDEMChecks::oneOf(d, "type", {"box", "cylinder", "surface"});
    if (type == "surface")
    {
        immersedDEMChecks::allowOnly(d, {"type", "file", "scale"});
        const fileName file = surfaceDir/d.get<fileName>("file");
        try
        {
            // (a region: inside tests only, no convex pieces)
            std::shared_ptr<const shape> s = triangleMeshShape::fromFile
            (
                file, immersedDEMChecks::positiveOrDefault(d, "scale", 1), true, 0
            );
            return insertionRegion::surface(s);
        }
        catch (const coreError& err)
        {
            FatalIOErrorInFunction(d)
                << "Region, keyword 'file' in " << d.name() << ":" << nl
                << "    " << err.what() << nl << exit(FatalIOError);
        }
    }
    try
    {
        if (type == "box")
        {
            immersedDEMChecks::allowOnly(d, {"type", "min", "max"});
            const vector lo = d.get<vector>("min"), hi = d.get<vector>("max");
            if (!(cmptMin(hi - lo) > 0))
            {
                FatalIOErrorInFunction(d)
                    << "Keywords 'min' " << lo << " and 'max' " << hi << " in "
                    << d.name() << ": min < max is needed on every axis"
                    << exit(FatalIOError);
            }
            return insertionRegion::box(immersedDEMReader::toCore(lo), immersedDEMReader::toCore(hi));
        }
        immersedDEMChecks::allowOnly(d, {"type", "point1", "point2", "radius"});
        const vector p1 = d.get<vector>("point1"), p2 = d.get<vector>("point2");
        if (mag(p2 - p1) == 0)
        {
            FatalIOErrorInFunction(d)
                << "Keywords 'point1' and 'point2' in " << d.name()
                << " are the same point" << exit(FatalIOError);
        }
        return insertionRegion::cylinder
        (
            immersedDEMReader::toCore(p1), immersedDEMReader::toCore(p2),
            immersedDEMChecks::positive(d, "radius")
        );
    }
    catch (const coreError& err)
    {
        FatalIOErrorInFunction(d)
            << "In " << d.name() << ": " << err.what() << exit(FatalIOError);
    }
    return insertionRegion();
}


//- The keywords an insertion at start and a stream share: region, seed,
//  clearance, maxAttempts
template<class Settings>
void readPlacement(const dictionary& d, const fileName& surfaceDir, Settings& s)
{
    const dictionary* rd = d.findDict("region");
    if (!rd)
    {
        FatalIOErrorInFunction(d)
            << "Keyword 'region' in " << d.name() << " is missing or not a"
            << " dictionary { type box|cylinder|surface; ... }" << exit(FatalIOError);
    }
    s.region = readRegionDict(*rd, surfaceDir);
    s.seed = label(immersedDEMChecks::inRangeOrDefault(d, "seed", 0, 2147483647, 1));
    s.clearance = d.found("clearance")
        ? immersedDEMChecks::positive(d, "clearance", true) : 0;
    s.maxAttempts =
        label(immersedDEMChecks::inRangeOrDefault(d, "maxAttempts", 1, 1e8, 1000));
}

} // End anonymous namespace


std::map<Foam::word, immersedDEM::bodyTemplate> Foam::immersedDEMInsertion::readTemplates
(
    const dictionary& dict,
    const fileName& surfaceDir,
    const std::vector<contactMaterial>& materials
)
{
    std::map<word, bodyTemplate> templates;
    if (const dictionary* td = dict.findDict("templates"))
    {
        for (const entry& e : *td)
        {
            const dictionary& d =
                immersedDEMChecks::subDictEntry(*td, e, "a body template's description");
            templates.emplace(e.keyword(), readTemplate(e.keyword(), d, surfaceDir, materials));
        }
    }
    return templates;
}


Foam::scalar Foam::immersedDEMInsertion::largestDiameter
(
    const dictionary& dict,
    const std::map<word, bodyTemplate>& templates
)
{
    scalar largest = 0;
    if (const dictionary* id = dict.findDict("insertion"))
    {
        for (const entry& e : *id)
        {
            const dictionary& d =
                immersedDEMChecks::subDictEntry(*id, e, "an insertion's description");
            largest = max(largest, 2*findTemplate(d, templates).maxBoundingRadius());
        }
    }
    return largest;
}


void Foam::immersedDEMInsertion::insert
(
    const dictionary& dict,
    const fileName& surfaceDir,
    const std::map<word, bodyTemplate>& templates,
    demSolver& dem
)
{
    const dictionary* id = dict.findDict("insertion");
    if (!id) return;
    for (const entry& e : *id)
    {
        const dictionary& d = immersedDEMChecks::subDictEntry(*id, e, "an insertion's description");
        if (d.found("rate"))
        {
            // Insertion over time: readStreams
            continue;
        }
        immersedDEMChecks::allowOnly
        (
            d,
            {
                "template", "region", "number", "volumeFraction", "seed",
                "clearance", "maxAttempts", "rate"
            }
        );
        const bodyTemplate& t = findTemplate(d, templates);
        insertionSettings s;
        s.name = e.keyword();
        const bool byNumber = d.found("number"), byFraction = d.found("volumeFraction");
        if (byNumber == byFraction)
        {
            FatalIOErrorInFunction(d)
                << "Insertion '" << s.name << "' in " << d.name()
                << ": give one of the keywords 'number' (of bodies) or"
                << " 'volumeFraction' (of the region)" << exit(FatalIOError);
        }
        if (byNumber)
        {
            s.number = label(immersedDEMChecks::inRange(d, "number", 1, 1e7));
            if (d.get<scalar>("number") != s.number)
            {
                FatalIOErrorInFunction(d)
                    << "Keyword 'number' in " << d.name() << " must be a whole number"
                    << exit(FatalIOError);
            }
        }
        else
        {
            s.volumeFraction = immersedDEMChecks::inRange(d, "volumeFraction", 1e-6, 0.74);
        }
        readPlacement(d, surfaceDir, s);

        insertionReport r;
        try
        {
            r = bodyInsertion::insert(dem, t, s);
        }
        catch (const coreError& err)
        {
            FatalIOErrorInFunction(d)
                << "Insertion '" << s.name << "' in " << d.name() << ": " << err.what()
                << exit(FatalIOError);
        }
        Info<< "    " << r.summary().c_str() << endl;
        if (!r.complete)
        {
            // What was missed: bodies of a number, the fraction of a
            // volume fraction
            OStringStream missed;
            if (r.requested > 0)
            {
                missed
                    << r.requested - r.placed << " of " << r.requested
                    << " could not be placed";
            }
            else
            {
                missed
                    << "they fill a volume fraction of " << r.volumeFraction()
                    << " of the requested " << r.targetFraction;
            }
            WarningInFunction
                << "Insertion '" << s.name << "' in " << d.name() << " placed "
                << r.placed << " bodies only: " << missed.str().c_str()
                << " (enlarge the region, lower the number"
                << " or volumeFraction, or raise maxAttempts)" << endl;
        }
    }
}


immersedDEM::insertionRegion Foam::immersedDEMInsertion::readRegion
(
    const dictionary& d,
    const fileName& surfaceDir
)
{
    return readRegionDict(d, surfaceDir);
}


std::vector<immersedDEM::bodyStream> Foam::immersedDEMInsertion::readStreams
(
    const dictionary& dict,
    const fileName& surfaceDir,
    const std::map<word, bodyTemplate>& templates
)
{
    std::vector<bodyStream> streams;
    const dictionary* id = dict.findDict("insertion");
    if (!id) return streams;
    for (const entry& e : *id)
    {
        const dictionary& d = immersedDEMChecks::subDictEntry(*id, e, "an insertion's description");
        if (!d.found("rate")) continue;
        immersedDEMChecks::allowOnly
        (
            d,
            {
                "template", "region", "rate", "start", "end", "number",
                "volumeFraction", "seed", "clearance", "maxAttempts"
            }
        );
        const bodyTemplate& t = findTemplate(d, templates);
        streamSettings s;
        s.name = e.keyword();
        s.rate = immersedDEMChecks::inRange(d, "rate", 1e-9, 1e9);
        s.start = d.getOrDefault<scalar>("start", 0);
        if (d.found("end"))
        {
            s.end = d.get<scalar>("end");
            if (!(s.end > s.start))
            {
                FatalIOErrorInFunction(d)
                    << "Keyword 'end' " << s.end << " in " << d.name()
                    << " must be after 'start' " << s.start << exit(FatalIOError);
            }
        }
        if (d.found("number"))
        {
            s.number = label(immersedDEMChecks::inRange(d, "number", 1, 1e9));
            if (d.get<scalar>("number") != s.number)
            {
                FatalIOErrorInFunction(d)
                    << "Keyword 'number' in " << d.name() << " must be a whole number"
                    << exit(FatalIOError);
            }
        }
        if (d.found("volumeFraction"))
        {
            s.volumeFraction = immersedDEMChecks::inRange(d, "volumeFraction", 1e-6, 0.74);
        }
        readPlacement(d, surfaceDir, s);
        try
        {
            streams.emplace_back(t, s);
        }
        catch (const coreError& err)
        {
            FatalIOErrorInFunction(d)
                << "Insertion '" << s.name << "' in " << d.name() << ": " << err.what()
                << exit(FatalIOError);
        }
        Info<< "    insertion " << s.name.c_str() << ": " << s.rate << " bodies/s of template "
            << t.name.c_str() << " from t = " << s.start;
        if (std::isfinite(s.end)) Info<< " to " << s.end;
        if (s.number > 0) Info<< ", at most " << s.number << " bodies";
        if (s.volumeFraction > 0) Info<< ", until volume fraction " << s.volumeFraction;
        Info<< " (region volume " << s.region.volume() << " m3)" << endl;
    }
    return streams;
}
