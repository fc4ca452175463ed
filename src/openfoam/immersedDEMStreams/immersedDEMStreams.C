#include "immersedDEMStreams.H"
#include "immersedDEMInsertion.H"
#include "dictionaryChecks.H"
#include "coreConversion.H"
#include "bodyRemoval.H"
#include "coreError.H"
#include "Pstream.H"
#include "ListOps.H"
#include "wallPolyPatch.H"
#include "processorPolyPatch.H"

#include <sstream>

using namespace immersedDEM;

namespace
{

//- A time in the log: ten digits (writePrecision 17 would show the step
//  sums' round-off, 0.17600000000000013)
std::string tenDigits(const Foam::scalar t)
{
    std::ostringstream os;
    os.precision(10);
    os << t;
    return os.str();
}

} // End anonymous namespace

Foam::immersedDEMStreams::immersedDEMStreams
(
    const dictionary& dict,
    const fileName& surfaceDir,
    std::vector<bodyStream>&& streams,
    const polyMesh* mesh,
    const demSolver& dem
)
:
    streams_(std::move(streams)),
    mesh_(mesh),
    dictName_(dict.name()),
    warnedWaiting_(streams_.size(), false)
{
    for (const bodyStream& st : streams_)
    {
        const std::string prefix = st.settings().name + "_";
        for (const rigidBody& b : dem.bodies())
        {
            if (b.name.rfind(prefix, 0) == 0)
            {
                FatalIOErrorInFunction(dict)
                    << "Insertion '" << st.settings().name.c_str() << "' in " << dict.name()
                    << ": the name of body or wall '" << b.name.c_str()
                    << "' is taken by the names of its bodies ("
                    << st.settings().name.c_str() << "_<n>)" << nl << exit(FatalIOError);
            }
        }
    }
    // The open patches: where a body carried out of the mesh leaves it
    if (mesh_)
    {
        DynamicList<label> open;
        DynamicList<word> names;
        forAll(mesh_->boundaryMesh(), patchi)
        {
            const polyPatch& pp = mesh_->boundaryMesh()[patchi];
            if (!isA<wallPolyPatch>(pp) && !polyPatch::constraintType(pp.type()))
            {
                open.append(patchi);
                names.append(pp.name());
            }
        }
        openPatches_.transfer(open);
        if (openPatches_.size())
        {
            leavingMesh_ = leaving::throughOpenPatches;
        }
        openPatchNames_.transfer(names);
    }
    const dictionary* rd = dict.findDict("removal");
    if (!rd)
    {
        if (dict.found("removal"))
        {
            FatalIOErrorInFunction(dict)
                << "Keyword 'removal' in " << dict.name() << " must be a dictionary"
                << " { outlet { type box|cylinder|surface; ... } leavingMesh yes|no; }"
                << nl << exit(FatalIOError);
        }
        reportRemoval();
        return;
    }
    immersedDEMChecks::allowOnly(*rd, {"outlet", "leavingMesh"});
    if (rd->found("outlet"))
    {
        const dictionary* od = rd->findDict("outlet");
        if (!od)
        {
            FatalIOErrorInFunction(*rd)
                << "Keyword 'outlet' in " << rd->name() << " must be a region"
                << " dictionary { type box|cylinder|surface; ... }" << nl
                << exit(FatalIOError);
        }
        outlets_.push_back(immersedDEMInsertion::readRegion(*od, surfaceDir));
    }
    if (rd->found("leavingMesh"))
    {
        const bool all = rd->get<bool>("leavingMesh");
        if (all && !mesh_)
        {
            FatalIOErrorInFunction(*rd)
                << "Keyword 'leavingMesh' in " << rd->name() << ": the case has no"
                << " mesh (constant/polyMesh) to leave; remove the keyword or give"
                << " an 'outlet' region" << nl << exit(FatalIOError);
        }
        leavingMesh_ = all ? leaving::all : leaving::none;
    }
    reportRemoval();
}


void Foam::immersedDEMStreams::reportRemoval() const
{
    if (outlets_.empty() && leavingMesh_ == leaving::none)
    {
        return;
    }
    Info<< "    removal: bodies whose centre";
    if (!outlets_.empty())
    {
        const axisAlignedBox b = outlets_[0].bounds();
        Info<< " enters the outlet (bounds " << coreConversion::toFoam(b.min) << ' '
            << coreConversion::toFoam(b.max) << ")";
    }
    if (leavingMesh_ == leaving::all)
    {
        Info<< (outlets_.empty() ? "" : " or") << " is in no cell of the mesh";
    }
    else if (leavingMesh_ == leaving::throughOpenPatches)
    {
        Info<< (outlets_.empty() ? "" : " or") << " leaves the mesh through an open patch (";
        forAll(openPatchNames_, k)
        {
            Info<< (k ? " " : "") << openPatchNames_[k];
        }
        Info<< "; the default: leavingMesh no makes it an error, yes removes"
            << " bodies leaving anywhere)";
    }
    Info<< " are removed" << endl;
}


Foam::boolList Foam::immersedDEMStreams::nearestFaceOnPatches
(
    const polyMesh& mesh,
    const labelList& patches,
    const List<point>& points
)
{
    // Each processor's nearest boundary face, then the nearest over all:
    // the processor holding it says whether it is on one of the patches
    // (brute force over the faces: only for the few bodies just outside)
    const polyBoundaryMesh& bm = mesh.boundaryMesh();
    boolList on(bm.size(), false);
    for (const label patchi : patches) on[patchi] = true;
    scalarList nearest(points.size(), GREAT);
    labelList nearestPatch(points.size(), -1);
    forAll(bm, patchi)
    {
        const polyPatch& pp = bm[patchi];
        if (isA<processorPolyPatch>(pp)) continue;
        forAll(pp, facei)
        {
            forAll(points, k)
            {
                const scalar d =
                    pp[facei].nearestPoint(points[k], mesh.points()).distance();
                if (d < nearest[k])
                {
                    nearest[k] = d;
                    nearestPatch[k] = patchi;
                }
            }
        }
    }
    scalarList globalNearest(nearest);
    Pstream::listCombineGather(globalNearest, minEqOp<scalar>());
    Pstream::listCombineScatter(globalNearest);
    labelList onIt(points.size(), 0);
    forAll(points, k)
    {
        if (nearestPatch[k] >= 0 && nearest[k] == globalNearest[k] && on[nearestPatch[k]])
        {
            onIt[k] = 1;
        }
    }
    Pstream::listCombineGather(onIt, maxEqOp<label>());
    Pstream::listCombineScatter(onIt);
    boolList result(points.size());
    forAll(result, k) result[k] = onIt[k] > 0;
    return result;
}


Foam::labelList Foam::immersedDEMStreams::inMesh
(
    const polyMesh& mesh,
    const demSolver& dem,
    const std::vector<char>& skip
)
{
    const auto& bodies = dem.bodies();
    labelList in(bodies.size(), 0);
    forAll(in, i)
    {
        if
        (
            dem.isWall(i)
         || (size_t(i) < skip.size() && skip[i])
         || mesh.findCell(coreConversion::toFoam(bodies[i].pose.position())) >= 0
        )
        {
            in[i] = 1;
        }
    }
    Pstream::listCombineGather(in, maxEqOp<label>());
    Pstream::listCombineScatter(in);
    return in;
}


Foam::immersedDEMStreams::change Foam::immersedDEMStreams::update
(
    demSolver& dem,
    const scalar t
)
{
    change c;
    auto& bodies = dem.bodies();

    // Removal: outlets, then the mesh (decided over all processors)
    std::vector<int> gone = bodyRemoval::bodiesIn(dem, outlets_);
    std::vector<char> why(bodies.size(), 0);
    for (const int i : gone) why[i] = 1;
    if (leavingMesh_ != leaving::none)
    {
        const labelList in = inMesh(*mesh_, dem, why);
        DynamicList<label> out;
        DynamicList<point> centres;
        forAll(in, i)
        {
            if (!in[i])
            {
                out.append(i);
                centres.append(coreConversion::toFoam(bodies[i].pose.position()));
            }
        }
        // By default only those carried out through an open patch (one
        // leaving through a wall stays the function object's error)
        const boolList open =
            leavingMesh_ == leaving::all || out.empty()
          ? boolList(out.size(), true)
          : nearestFaceOnPatches(*mesh_, openPatches_, centres);
        forAll(out, k)
        {
            if (open[k])
            {
                why[out[k]] = 2;
                gone.push_back(out[k]);
            }
        }
        std::sort(gone.begin(), gone.end());
    }
    if (!gone.empty())
    {
        for (const int i : gone)
        {
            Info<< "immersedDEM: removed body " << bodies[i].name.c_str() << " at t "
                << tenDigits(t).c_str() << ": its centre " << coreConversion::toFoam(bodies[i].pose.position())
                << (why[i] == 1 ? " entered the outlet" : " left the mesh")
                << endl;
            removed_.append(word(bodies[i].name));
        }
        c.kept = dem.removeBodies(gone);
        c.nRemoved = label(gone.size());
    }

    // Insertion
    c.firstNew = label(bodies.size());
    for (size_t k = 0; k < streams_.size(); ++k)
    {
        streamStepReport r;
        try
        {
            r = streams_[k].insert(dem, t);
        }
        catch (const coreError& err)
        {
            FatalErrorInFunction
                << "Insertion '" << streams_[k].settings().name.c_str() << "' of "
                << dictName_ << " at t " << t << ": " << err.what() << exit(FatalError);
        }
        c.nNew += r.placed;
        for (const int i : r.indices)
        {
            const rigidBody& b = dem.bodies()[i];
            Info<< "immersedDEM: inserted body " << b.name.c_str() << " at t " << tenDigits(t).c_str()
                << ": centre " << coreConversion::toFoam(b.pose.position())
                << ", volume " << b.geometry->volume() << " m3, mass " << b.mass()
                << " kg" << endl;
        }
        if (r.placed > 0 || r.waiting > 0 || r.finishedNow)
        {
            Info<< "immersedDEM: " << r.summary().c_str() << endl;
        }
        if (r.waiting > 0 && !warnedWaiting_[k])
        {
            WarningInFunction
                << "Insertion '" << streams_[k].settings().name.c_str() << "' of "
                << dictName_ << " at t " << t << ": " << r.waiting << " bodies due"
                << " could not be placed (no free position in maxAttempts "
                << streams_[k].settings().maxAttempts << "); they wait and are"
                << " tried at every step. Enlarge the region, lower the rate or"
                << " raise maxAttempts (warned once)" << endl;
            warnedWaiting_[k] = true;
        }
    }
    return c;
}


void Foam::immersedDEMStreams::write(Ostream& os) const
{
    os  << "insertionState" << nl << token::BEGIN_BLOCK << incrIndent << nl;
    for (const bodyStream& st : streams_)
    {
        const streamState& s = st.state();
        os.beginBlock(word(st.settings().name));
        os.writeEntry("placed", label(s.placed));
        os.writeEntry("round", label(s.round));
        os.writeEntry("attempts", label(s.attempts));
        os.writeEntry("placedVolume", s.placedVolume);
        os.writeEntry("finished", Switch(s.finished));
        os.endBlock();
    }
    os  << decrIndent << token::END_BLOCK << nl << nl;
    os.writeEntry("removed", removed_);
    os  << nl;
}


void Foam::immersedDEMStreams::restore(const dictionary& state, demSolver& dem)
{
    // Older states and runs without streams or removal have neither entry
    if (const dictionary* sd = state.findDict("insertionState"))
    {
        for (bodyStream& st : streams_)
        {
            const word name(st.settings().name);
            const dictionary* d = sd->findDict(name);
            if (!d)
            {
                FatalIOErrorInFunction(*sd)
                    << "No state for the insertion '" << name << "' in "
                    << sd->name() << ": the insertions of " << dictName_
                    << " must be those of the run that wrote it" << nl
                    << exit(FatalIOError);
            }
            streamState s;
            s.placed = d->get<label>("placed");
            s.round = d->get<label>("round");
            s.attempts = d->get<label>("attempts");
            s.placedVolume = d->get<scalar>("placedVolume");
            s.finished = d->get<bool>("finished");
            st.setState(s);
        }
    }
    else if (!streams_.empty())
    {
        FatalIOErrorInFunction(state)
            << "No 'insertionState' in " << state.name() << " for the insertions"
            << " over time of " << dictName_ << ": the state was written by a run"
            << " without them" << nl << exit(FatalIOError);
    }
    removed_ = state.getOrDefault<wordList>("removed", wordList());

    // Bodies of the start that were removed
    std::map<std::string, int> index;
    forAll(dem.bodies(), i) index[dem.bodies()[i].name] = i;
    std::vector<int> gone;
    for (const word& n : removed_)
    {
        const auto it = index.find(n);
        if (it != index.end()) gone.push_back(it->second);
    }
    std::sort(gone.begin(), gone.end());
    dem.removeBodies(gone);

    // The stream bodies present, in the order of the saved bodies
    const dictionary& bd = state.subDict("bodies");
    for (const entry& e : bd)
    {
        const std::string name = e.keyword();
        for (const bodyStream& st : streams_)
        {
            const std::string prefix = st.settings().name + "_";
            if (name.rfind(prefix, 0) != 0) continue;
            const std::string rest = name.substr(prefix.size());
            if (rest.empty() || rest.find_first_not_of("0123456789") != std::string::npos)
            {
                continue;
            }
            const long n = std::stol(rest);
            if (n >= st.state().placed)
            {
                FatalIOErrorInFunction(bd)
                    << "Body '" << name.c_str() << "' in " << bd.name() << ": the"
                    << " insertion '" << st.settings().name.c_str() << "' placed "
                    << label(st.state().placed) << " bodies only" << nl
                    << exit(FatalIOError);
            }
            dem.addBody(st.body(n));
        }
    }
    dem.bodiesChanged();
    Info<< "immersedDEM: restart with " << removed_.size() << " bodies removed so far";
    for (const bodyStream& st : streams_)
    {
        Info<< ", insertion " << st.settings().name.c_str() << ' '
            << label(st.state().placed) << " placed";
    }
    Info<< endl;
}
