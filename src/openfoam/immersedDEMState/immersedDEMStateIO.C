// Restart I/O of immersedDEMState: one file per written time,
// <time>/uniform/immersedDEM/state, an OpenFOAM dictionary with 17
// significant digits (a continued run is bit-identical to an
// uninterrupted one)

#include "immersedDEMState.H"
#include "dictionaryChecks.H"
#include "coreConversion.H"
#include "restartEntries.H"
#include "coreError.H"
#include "OFstream.H"
#include "IFstream.H"
#include "OSspecific.H"

using namespace immersedDEM;


namespace
{

constexpr auto v = &Foam::coreConversion::toFoam;
constexpr auto c = &Foam::coreConversion::toCore;

} // End anonymous namespace


Foam::fileName Foam::immersedDEMState::restartFile(const fileName& timePath) const
{
    return timePath/"uniform"/"immersedDEM"/"state";
}


void Foam::immersedDEMState::writeRestart(const fileName& timePath) const
{
    const fileName file = restartFile(timePath);
    mkDir(file.path());
    const fileName tmp = file + ".tmp";
    {
        OFstream os(tmp);
        os.precision(17);
        os  << "// immersedDEM restart state: body states, fluid momenta inside"
            << " the bodies and contact histories" << nl << nl;
        os.writeEntry("time", dem_->time());
        // Whether the next DEM step kicks with the loads below, as written
        // (no: bodies entered or left in the step, and it computes them)
        os.writeEntry("loadsCurrent", Switch(dem_->loadsCurrent()));
        // The identity the next body added gets (demSolver::identity)
        os.writeEntry("nextIdentity", label(dem_->nextIdentity()));
        os  << nl << "bodies" << nl << token::BEGIN_BLOCK << incrIndent << nl;
        forAll(dem_->bodies(), i)
        {
            const rigidBody& b = dem_->bodies()[i];
            const quat& q = b.pose.orientation();
            os.beginBlock(word(b.name));
            // Its number in the output (VTK's body field)
            os.writeEntry("identity", label(dem_->identity(i)));
            os.writeEntry("position", v(b.pose.position()));
            if (dem_->periodic().active())
            {
                // The periods it was moved back by (bodies.dat's unwrapped
                // position continues)
                os.writeEntry("periodicOffset", v(b.periodicOffset));
            }
            os.writeEntry("orientation", List<scalar>({q.w(), q.x(), q.y(), q.z()}));
            os.writeEntry("velocity", v(b.velocity));
            os.writeEntry("angularVelocity", v(b.angularVelocity));
            if (projection_.hasProjectedPose(i))
            {
                // The pose its cells were projected at (a body at rest
                // keeps it while it stays within restDistance)
                const bodyPose& pp = projection_.projectedPose(i);
                const quat& pq = pp.orientation();
                os.writeEntry("projectedPosition", v(pp.position()));
                os.writeEntry
                (
                    "projectedOrientation",
                    List<scalar>({pq.w(), pq.x(), pq.y(), pq.z()})
                );
            }
            fluidLoad::fields(b.fluid, restartEntries::writer{os});
            coupling_->writeBody(os, i);
            // The loads of the last step, for the first output row of a
            // continued run (the DEM computes them again before its step)
            os.writeEntry("contactForce", v(b.contactForce));
            os.writeEntry("contactTorque", v(b.contactTorque));
            os.writeEntry("lubricationForce", v(b.lubricationForce));
            os.writeEntry("lubricationTorque", v(b.lubricationTorque));
            os.writeEntry("externalForce", v(b.externalForce));
            os.writeEntry("externalTorque", v(b.externalTorque));
            os.endBlock();
        }
        os  << decrIndent << token::END_BLOCK << nl << nl;
        os  << "contacts" << nl << token::BEGIN_BLOCK << incrIndent << nl;
        label k = 0;
        for (const auto& pair : dem_->histories())
        {
            for (const contactHistory& h : pair.second)
            {
                os.beginBlock(word("contact" + Foam::name(k++)));
                os.writeEntry("bodyA", word(dem_->bodies()[pair.first.first].name));
                os.writeEntry("bodyB", word(dem_->bodies()[pair.first.second].name));
                os.writeEntry("tangentialSpring", v(h.tangentialSpring));
                os.writeEntry("normal", v(h.normal));
                os.writeEntry("point", v(h.point));
                os.writeEntry("approach", h.approach);
                os.writeEntry("maxNormalForce", h.maxNormalForce);
                os.writeEntry("twist", h.twist);
                os.writeEntry("rolling", v(h.rolling));
                os.endBlock();
            }
        }
        os  << decrIndent << token::END_BLOCK << nl << nl;
        streams_->write(os);
        if (!os.good())
        {
            FatalErrorInFunction
                << "Could not write " << tmp << exit(FatalError);
        }
    }
    if (!Foam::mv(tmp, file))
    {
        FatalErrorInFunction
            << "Could not rename " << tmp << " to " << file << exit(FatalError);
    }
}


bool Foam::immersedDEMState::readRestart()
{
    const Time& runTime = mesh_.time();
    const fileName timePath = runTime.timePath();
    const fileName file = restartFile(timePath);
    const bool found = isFile(file);

    if (!properties_.getOrDefault<bool>("restart", true))
    {
        Info<< "immersedDEM: restart no in " << immersedDEMChecks::caseFile(properties_)
            << ": the bodies start afresh from it at time " << runTime.timeName();
        if (returnReduce(found, orOp<bool>()))
        {
            Info<< " (the state in " << file << " is not read)";
        }
        Info<< endl;
        return false;
    }

    if (!returnReduce(found, andOp<bool>()))
    {
        // A folder a run wrote (OpenFOAM's uniform/time is there) without
        // the bodies' state: the run stopped between the field writes and
        // the state's (the function object writes it after the solver's
        // fields), or the state was removed. Starting the bodies from
        // constant/immersedDEMProperties there would put them back where
        // they were at the start while the fluid goes on.
        const bool some = returnReduce(found, orOp<bool>());
        const bool written = returnReduce(isFile(timePath/"uniform"/"time"), orOp<bool>());
        if (some || written)
        {
            FatalIOErrorInFunction(properties_)
                << "Restart from the time folder " << timePath
                << ": uniform/immersedDEM/state is missing"
                << (some ? " on some processors" : "")
                << " (the bodies' poses, velocities, fluid loads and contact"
                << " histories)." << nl
                << "The run that wrote this folder stopped before the"
                << " immersedDEM state was written (it is written after the"
                << " fields), or the file was removed." << nl
                << "Restart from an earlier time that has it (remove "
                << timePath.name() << " or set startTime), or put 'restart no;'"
                << " in " << immersedDEMChecks::caseFile(properties_) << " to start the bodies"
                << " afresh from that file at time " << runTime.timeName() << nl
                << exit(FatalIOError);
        }
        // A first start (no state, a folder no run wrote)
        return false;
    }
    Info<< "immersedDEM: restarting from " << file << endl;
    IFstream is(file);
    dictionary dict(is);
    dict.name() = file;

    // Bodies inserted over time and removed: as the run that wrote it had
    // them, then the fluid coupling for those bodies
    streams_->restore(dict, *dem_);
    coupling_.reset(new immersedFluidCoupling(*dem_));

    auto& bodies = dem_->bodies();
    std::map<std::string, int> index;
    forAll(bodies, i)
    {
        index[bodies[i].name] = i;
    }
    auto bodyIndex = [&](const dictionary& d, const word& key)
    {
        const word name = d.get<word>(key);
        const auto it = index.find(name);
        if (it == index.end())
        {
            FatalIOErrorInFunction(d)
                << "Keyword '" << key << "' in " << d.name() << ": no body or wall '"
                << name << "' in " << immersedDEMChecks::caseFile(properties_) << nl
                << exit(FatalIOError);
        }
        return it->second;
    };

    const dictionary& bd = dict.subDict("bodies");
    // (states written before it have none: the DEM computes the loads)
    loadsRestored_ = dict.getOrDefault<Switch>("loadsCurrent", false);
    // The bodies' numbers in the output (states written before them have
    // none: numbered in the order the bodies were added again)
    std::vector<std::uint64_t> identities;
    const bool numbered = dict.found("nextIdentity");
    forAll(bodies, i)
    {
        rigidBody& b = bodies[i];
        const dictionary* dp = bd.findDict(b.name);
        if (!dp)
        {
            FatalIOErrorInFunction(bd)
                << "No state for body '" << b.name << "' in " << file
                << ": the bodies of " << immersedDEMChecks::caseFile(properties_)
                << " must be those of the run that wrote it" << nl
                << exit(FatalIOError);
        }
        const dictionary& d = *dp;
        if (numbered) identities.push_back(d.get<label>("identity"));
        const List<scalar> q(d.get<List<scalar>>("orientation"));
        if (q.size() != 4)
        {
            FatalIOErrorInFunction(d)
                << "Keyword 'orientation' in " << d.name()
                << " must be a quaternion (w x y z)" << nl << exit(FatalIOError);
        }
        b.pose = bodyPose(c(d.get<vector>("position")), quat(q[0], q[1], q[2], q[3]));
        b.velocity = c(d.get<vector>("velocity"));
        b.angularVelocity = c(d.get<vector>("angularVelocity"));
        b.periodicOffset = c(d.getOrDefault<vector>("periodicOffset", Zero));
        // The pose its cells were projected at (states written before it
        // have none: the body is projected where it is)
        if (d.found("projectedPosition"))
        {
            const List<scalar> pq(d.get<List<scalar>>("projectedOrientation"));
            if (pq.size() != 4)
            {
                FatalIOErrorInFunction(d)
                    << "Keyword 'projectedOrientation' in " << d.name()
                    << " must be a quaternion (w x y z)" << nl
                    << exit(FatalIOError);
            }
            projection_.restoreProjectedPose
            (
                *dem_, i,
                bodyPose
                (
                    c(d.get<vector>("projectedPosition")),
                    quat(pq[0], pq[1], pq[2], pq[3])
                )
            );
        }
        // (restart files written before the implicit coupling have no
        // added moment of inertia and no course flags: none, as they were
        // written)
        fluidLoad::fields
        (
            b.fluid,
            restartEntries::reader
            {
                d,
                [](const word& name)
                {
                    return
                        name == "fluidAddedInertia"
                     || name == "fluidCourseExtrapolated"
                     || name == "fluidImpactRestartsCourse";
                }
            }
        );
        coupling_->readBody(d, i);
        // The loads of the step before (absent from older states): the
        // first output row carries them, and the first DEM step kicks with
        // them (resumeLoads) where the run that wrote them would have
        // (loadsCurrent); otherwise the DEM computes them again, as that
        // run did
        vector F;
        label loads = 0;
        if (d.readIfPresent("contactForce", F)) { b.contactForce = c(F); ++loads; }
        if (d.readIfPresent("contactTorque", F)) { b.contactTorque = c(F); ++loads; }
        if (d.readIfPresent("lubricationForce", F)) { b.lubricationForce = c(F); ++loads; }
        if (d.readIfPresent("lubricationTorque", F)) { b.lubricationTorque = c(F); ++loads; }
        loadsRestored_ = loadsRestored_ && loads == 4;
        if (d.readIfPresent("externalForce", F)) b.externalForce = c(F);
        if (d.readIfPresent("externalTorque", F)) b.externalTorque = c(F);
    }
    if (numbered)
    {
        try
        {
            dem_->restoreIdentities(identities, dict.get<label>("nextIdentity"));
        }
        catch (const coreError& err)
        {
            FatalIOErrorInFunction(bd)
                << "The bodies' keyword 'identity' in " << file << ": " << err.what()
                << " (the file was edited, or written by another run): remove"
                << " 'nextIdentity' to number the bodies afresh" << nl
                << exit(FatalIOError);
        }
    }

    std::map<std::pair<int, int>, std::vector<contactHistory>> histories;
    const dictionary& cd = dict.subDict("contacts");
    for (const entry& e : cd)
    {
        const dictionary& d = e.dict();
        contactHistory h;
        h.tangentialSpring = c(d.get<vector>("tangentialSpring"));
        h.normal = c(d.get<vector>("normal"));
        h.point = c(d.get<vector>("point"));
        h.approach = d.get<scalar>("approach");
        h.maxNormalForce = d.get<scalar>("maxNormalForce");
        // (restart files written before twisting friction: none)
        h.twist = d.getOrDefault<scalar>("twist", 0);
        // (and before rolling friction: none)
        h.rolling = c(d.getOrDefault<vector>("rolling", Zero));
        histories[{bodyIndex(d, "bodyA"), bodyIndex(d, "bodyB")}].push_back(h);
    }
    dem_->setHistories(std::move(histories));
    dem_->setTime(dict.get<scalar>("time"));
    return true;
}
