#include "demSolver.H"
#include "rigidBodyIntegrator.H"
#include "sphereShape.H"
#include "halfSpaceShape.H"
#include "convexOverlap.H"
#include "coreError.H"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <sstream>

namespace immersedDEM
{

namespace
{

//- For one pair's evaluation in a periodic domain: A (unless a wall) at
//  its unwrapped position, so that the pair's contact points and
//  histories continue when A is wrapped, and B at its image nearest to A
//  (periodicBox::nearestShift); both poses back as they were after
class pairImage
{
    std::vector<rigidBody>& bodies_;
    int a_ = -1, b_ = -1;
    bodyPose poseA_, poseB_;

public:

    pairImage
    (
        const periodicBox& box, std::vector<rigidBody>& bodies,
        const std::vector<char>& isWall, const std::pair<int, int>& p
    )
    :
        bodies_(bodies)
    {
        if (!box.active() || isWall[p.first] || isWall[p.second]) return;
        rigidBody& A = bodies[p.first];
        rigidBody& B = bodies[p.second];
        a_ = p.first;
        b_ = p.second;
        poseA_ = A.pose;
        poseB_ = B.pose;
        const vec3 xA = A.pose.position() + A.periodicOffset;
        A.pose.setPosition(xA);
        B.pose.setPosition(B.pose.position() + box.nearestShift(xA, B.pose.position()));
    }

    ~pairImage()
    {
        if (a_ < 0) return;
        bodies_[a_].pose = poseA_;
        bodies_[b_].pose = poseB_;
    }

    pairImage(const pairImage&) = delete;
    pairImage& operator=(const pairImage&) = delete;
};

} // End anonymous namespace


demSolver::demSolver(std::vector<contactMaterial> materials, const demSettings& settings)
:
    materials_(std::move(materials)),
    settings_(settings),
    engine_(overlapEngine::New(settings.overlapMethod)),
    law_(contactLaw::New(settings.contactLaw)),
    resolutions_
    (
        settings.overlapMethod == "virtualMesh" && !(settings.overlap.h > 0)
      ? settings.volumeTolerance : 0.0
    ),
    reuse_(settings, engine_->type(), *law_),
    films_(settings)
{
    if (settings_.stepsPerContact < 10)
    {
        throw coreError
        (
            "stepsPerContact is " + std::to_string(settings_.stepsPerContact)
          + "; it must be at least 10 (30 or more resolves a collision)"
        );
    }
    if (settings_.overlap.level < 0 || settings_.overlap.level > overlapSettings::maxLevel)
    {
        throw coreError
        (
            "level must be in [0, " + std::to_string(overlapSettings::maxLevel) + "]"
        );
    }
}


int demSolver::addBody(rigidBody b, bool wall)
{
    if (b.material < 0 || b.material >= int(materials_.size()))
    {
        throw coreError("Body '" + b.name + "': material index out of range");
    }
    if (wall && b.motion == motionType::free)
    {
        throw coreError("Wall '" + b.name + "' must be fixed or prescribed");
    }
    if (law_->needsSpheres() && !wall && !shapeAs<sphereShape>(*b.geometry))
    {
        throw coreError
        (
            "Body '" + b.name + "': contact law " + law_->type()
          + " needs spheres; use the volume law for other shapes"
        );
    }
    if (!wall)
    {
        checkPeriodicSize(b);
    }
    bodies_.push_back(std::move(b));
    isWall_.push_back(wall);
    identity_.push_back(nextIdentity_++);
    loadsCurrent_ = false;
    return int(bodies_.size()) - 1;
}


void demSolver::restoreIdentities
(
    const std::vector<std::uint64_t>& identities, std::uint64_t next
)
{
    if (identities.size() != bodies_.size())
    {
        throw coreError
        (
            "restoreIdentities: " + std::to_string(identities.size()) + " identities for "
          + std::to_string(bodies_.size()) + " bodies"
        );
    }
    std::vector<std::uint64_t> sorted(identities);
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
    {
        throw coreError("restoreIdentities: two bodies have the same identity");
    }
    if (!sorted.empty() && sorted.back() >= next)
    {
        throw coreError
        (
            "restoreIdentities: identity " + std::to_string(sorted.back())
          + " is not below the next one, " + std::to_string(next)
        );
    }
    identity_ = identities;
    nextIdentity_ = next;
}


std::vector<int> demSolver::removeBodies(const std::vector<int>& indices)
{
    const int n = int(bodies_.size());
    std::vector<char> gone(n, 0);
    for (const int i : indices)
    {
        if (i < 0 || i >= n)
        {
            throw coreError("removeBodies: index " + std::to_string(i) + " out of range");
        }
        if (isWall_[i])
        {
            throw coreError("Wall '" + bodies_[i].name + "' cannot be removed");
        }
        gone[i] = 1;
    }
    std::vector<int> kept, newIndex(n, -1);
    if (indices.empty())
    {
        for (int i = 0; i < n; ++i) kept.push_back(i);
        return kept;
    }
    std::vector<rigidBody> bodies;
    std::vector<char> isWall;
    std::vector<std::uint64_t> identity;
    for (int i = 0; i < n; ++i)
    {
        if (gone[i]) continue;
        newIndex[i] = int(kept.size());
        kept.push_back(i);
        bodies.push_back(std::move(bodies_[i]));
        isWall.push_back(isWall_[i]);
        identity.push_back(identity_[i]);
    }
    bodies_.swap(bodies);
    isWall_.swap(isWall);
    identity_.swap(identity);

    contacts_.renumber(newIndex);
    // Reuse records are keyed by the old indices: the next contacts are
    // evaluated in full
    reuse_.clear();
    films_.clear();
    stepSize_.renumber(newIndex);

    // The broad phase starts afresh
    broad_.clear();
    loadsCurrent_ = false;
    return kept;
}


std::vector<std::pair<int, int>> demSolver::candidatePairs()
{
    // Lubrication reaches beyond the contact: boxes grown by half its
    // activation distance meet where the gap may be below it
    const double margin = 0.5*lubricationReach();
    // With the pair filter on, a pair whose bounding spheres are farther
    // apart than both the engine's and the lubrication's reach is one both
    // filters would reject first (pairFilter's test 1): dropped by the
    // broad phase, unless a contact of it is being carried (reuse asks no
    // filter). A plane wall's box holds everything: its pairs are dropped
    // so by the height of the body's centre above it
    const double dropBeyond = settings_.rejectSeparated
        ? std::max(engineReach(), 2*margin)
        : std::numeric_limits<double>::infinity();
    return broad_.candidates
    (
        bodies_, isWall_, settings_.periodic, margin, dropBeyond,
        [this](const std::pair<int, int>& p) { return reuse_.carries(p); },
        counters_
    );
}


void demSolver::updateResolutions()
{
    if
    (
        !resolutions_.active()
     || (resolvedCount_ == bodies_.size() && resolvedIdentity_ == nextIdentity_)
    )
    {
        return;
    }
    // The deepest a pair goes: the peak of a head-on collision at the
    // reference speed, v t_c/pi (a linear spring's; Hertz's is 1.07 times
    // that)
    const double v = settings_.referenceSpeed;
    auto depthOf = [&](size_t a, size_t b)
    {
        const rigidBody& A = bodies_[a];
        const rigidBody& B = bodies_[b];
        const double Reff = effectiveRadius(int(a), int(b));
        const double lc =
            settings_.characteristicLength > 0 ? settings_.characteristicLength : Reff;
        const double m =
            demPair::effectiveMass(A.mass(), A.dynamic() && !isWall_[a], B.mass(), B.dynamic() && !isWall_[b]);
        const double tc =
            law_->contactTime(materials_.of(A.material, B.material), m, Reff, lc, v);
        return v*tc/M_PI;
    };
    resolutions_.update(bodies_, isWall_, settings_.overlap, depthOf);
    resolvedCount_ = bodies_.size();
    resolvedIdentity_ = nextIdentity_;
    double dMax = 0;
    for (size_t i = 0; i < bodies_.size(); ++i)
    {
        if (!isWall_[i]) dMax = std::max(dMax, 2*bodies_[i].equivalentRadius());
    }
    resolvedLeaf_ = resolutions_.largestLeaf(dMax);
}


double demSolver::engineReach() const
{
    const double reach = pairFilter::engineReach(engine_->type(), settings_.overlap);
    return
        resolvedLeaf_ > 0
      ? std::max(reach, 1.01*std::sqrt(3.0)*resolvedLeaf_)
      : reach;
}


void demSolver::contactOf
(
    const pairContacts::context& c, const std::pair<int, int>& p,
    contactGeometry& g, bool full
)
{
    const rigidBody& A = bodies_[p.first];
    const rigidBody& B = bodies_[p.second];
    const bool filter = settings_.rejectSeparated;

    // A lasting contact within its bound: carried, not evaluated (and not
    // asked of the filter: the filter only ever rejects pairs the engine
    // would find apart, so the reuse decisions, and so the trajectories,
    // do not depend on the filter)
    if (!full && reuse_.carry(p, bodies_, isWall_, g, counters_))
    {
        contacts_.apply(c, p.first, p.second, g);
        if (filter) filter_.stillTouching(p.first, p.second);
        return;
    }
    if
    (
        filter
     && filter_.separated(p.first, p.second, *A.geometry, A.pose, *B.geometry, B.pose)
    )
    {
        return;
    }
    g = engine_->evaluate(*A.geometry, A.pose, *B.geometry, B.pose, pairSettings(p.first, p.second));
    ++counters_.pairEvaluations;
    counters_.queries += g.queries;
    const bool touching = contacts_.apply(c, p.first, p.second, g);
    if (touching && reuse_.reusable(*A.geometry, *B.geometry))
    {
        reuse_.record(p, bodies_, isWall_, g, full);
    }
    if (filter)
    {
        filter_.engineResult(p.first, p.second, touching);
    }
}


void demSolver::computeContacts()
{
    if (settings_.overlap.h <= 0)
    {
        double dMin = std::numeric_limits<double>::max();
        for (size_t i = 0; i < bodies_.size(); ++i)
        {
            if (!isWall_[i]) dMin = std::min(dMin, 2*bodies_[i].equivalentRadius());
        }
        if (dMin < std::numeric_limits<double>::max())
        {
            settings_.overlap.h = overlapSettings::defaultCellSize(dMin);
        }
    }
    updateResolutions();

    const auto t0 = std::chrono::steady_clock::now();
    for (rigidBody& b : bodies_)
    {
        b.clearContactForces();
        updateExternalLoad(b, loadTime_);
    }
    contacts_.beginPass();
    const pairContacts::context c = contactContext();
    const bool filter = settings_.rejectSeparated;
    if (filter)
    {
        filter_.setReach(engineReach());
        filter_.rejectProvenGaps(true);
        filter_.beginSweep();
    }
    const bool full = fullNext_ || !settings_.reuseContacts;
    reuse_.beginPass();
    contactGeometry g;
    const bool lub = lubricating();
    // The films' step: the one that led here (the first of an advance:
    // the softest-case estimate)
    const double filmStep = lub ? (lastDt_ > 0 ? lastDt_ : timeStep()) : 0;
    using clock = std::chrono::steady_clock;
    auto since = [](clock::time_point a)
    {
        return std::chrono::duration<double>(clock::now() - a).count();
    };
    // This process's pairs (all of them, alone): their loads, summed per
    // pair, are added to the bodies in the order of the pairs once every
    // process's are gathered, so the sums do not depend on who made them
    if (sphereSweepApplies())
    {
        spheres_.sweep(c, contacts_, broad_, comm_.get(), identity_, counters_);
    }
    else
    {
        const auto searchStart = clock::now();
        const auto candidates = candidatePairs();
        counters_.searchSeconds += since(searchStart);
        if (lub)
        {
            films_.beginPass(candidates, bodies_.size());
        }
        for (const auto& p : candidates)
        {
            if (!owns(p.first, p.second))
            {
                continue;
            }
            contacts_.beginPair(p.first, p.second);
            // (periodic: A at its unwrapped position, B at its image
            // nearest A, for this pair only)
            const pairImage image(settings_.periodic, bodies_, isWall_, p);
            if (bodies_[p.first].dynamic() || bodies_[p.second].dynamic())
            {
                contactOf(c, p, g, full);
            }
            if (lub)
            {
                const auto lubStart = clock::now();
                films_.lubricate
                (
                    p.first, p.second, bodies_, isWall_, contacts_.records(),
                    contacts_.load().contactsFrom, filmStep, contacts_.load(), counters_
                );
                counters_.lubricationSeconds += since(lubStart);
            }
            contacts_.endPair();
        }
    }
    if (comm_)
    {
        contacts_.gather(*comm_);
    }
    contacts_.addLoads(bodies_);
    if (lub)
    {
        films_.endPass();
    }
    // Records of pairs not in contact (or not reusable) now are dropped
    reuse_.endPass();
    if (filter)
    {
        filter_.endSweep();
    }
    contacts_.endPass(bodies_.size());
    loadsCurrent_ = true;
    counters_.contactSeconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}


void demSolver::wrapPeriodic()
{
    if (!settings_.periodic.active()) return;
    for (size_t i = 0; i < bodies_.size(); ++i)
    {
        rigidBody& b = bodies_[i];
        if (isWall_[i] || !b.dynamic()) continue;
        vec3 x = b.pose.position();
        const periodicBox::periods n = settings_.periodic.wrap(x);
        if (n[0] != 0 || n[1] != 0 || n[2] != 0)
        {
            const vec3 t = settings_.periodic.translation(n);
            b.pose.setPosition(x);
            b.periodicOffset += t;
            // Its contacts with the walls, which stay, are where it is now
            contacts_.translateWallHistories(int(i), -t, isWall_);
        }
    }
}


void demSolver::checkPeriodicSize(const rigidBody& b) const
{
    settings_.periodic.check
    (
        b.name, 2*b.geometry->boundingRadius(),
        std::max(engineReach(), lubricationReach())
    );
}


void demSolver::setPeriodic(const periodicBox& box)
{
    settings_.periodic = box;
    for (size_t i = 0; i < bodies_.size(); ++i)
    {
        if (!isWall_[i]) checkPeriodicSize(bodies_[i]);
    }
    wrapPeriodic();
    broad_.clear();
    bodiesChanged();
}


void demSolver::updateExternalLoad(rigidBody& b, double t) const
{
    // Walls have infinite mass: no weight (and no inf*0 either)
    b.externalForce = b.fluid.force;
    if (b.dynamic())
    {
        b.externalForce = b.appliedFluidForce(t) + b.mass()*settings_.gravity;
    }
    b.externalTorque = b.dynamic() ? b.appliedFluidTorque(t) : b.fluid.torque;
}


double demSolver::timeStep() const
{
    return demStepSize::timeStep(stepInputs());
}


demSolver::stepChoice demSolver::stepFor(double T) const
{
    return demStepSize::stepFor
    (
        stepInputs(), T, std::max(engineReach(), lubricationReach()), time_
    );
}


void demSolver::step(double dt)
{
    if (!loadsCurrent_)
    {
        lastDt_ = 0;
        loadTime_ = time_;
        computeContacts();
    }
    lastDt_ = dt;
    for (rigidBody& b : bodies_)
    {
        // The fluid loads may have changed since the contacts were
        // computed
        updateExternalLoad(b, time_);
        rigidBodyIntegrator::kick(b, 0.5*dt);
        rigidBodyIntegrator::drift(b, dt);
    }
    wrapPeriodic();
    // Velocity-dependent loads see the half-step velocity: evaluate them
    // at the half step
    loadTime_ = time_ + 0.5*dt;
    computeContacts();
    fullNext_ = false;
    loadTime_ = time_ + dt;
    for (rigidBody& b : bodies_)
    {
        rigidBodyIntegrator::kick(b, 0.5*dt);
        // An impact of a body free at the CFD step's start: the fluid's
        // dampers go on from the velocity it leaves with (fluidLoad.H)
        if (b.fluid.impactRestartsCourse != 0 && !b.contactForce.isZero())
        {
            b.fluid.restartCourse(b.velocity, b.angularVelocity, time_ + dt);
        }
    }
    time_ += dt;
    ++counters_.steps;
}


int demSolver::advance(double T, const std::function<void()>& afterStep)
{
    if (!(T > 0))
    {
        return 0;
    }
    // (the pairs' resolutions first: their reach enters the step)
    updateResolutions();
    const int n = stepSize_.plan
    (
        stepInputs(), T, std::max(engineReach(), lubricationReach()), time_
    );
    const double dt = T/n;
    // Films are carried within an advance only: each starts measured, as
    // after a restart
    films_.clear();
    for (int i = 0; i < n; ++i)
    {
        // The contacts at the end of an advance (where a run writes and
        // restarts) come from full evaluations, and so do those of its
        // first step, as after a restart (which has no reuse records):
        // a restarted run continues the written one exactly
        if (i == 0 || i == n - 1) fullNext_ = true;
        step(dt);
        checkDepths();
        if (afterStep) afterStep();
    }
    return n;
}


double demSolver::smallerVolume(const contactRecord& c) const
{
    const double VA = bodies_[c.a].geometry->volume();
    const double VB = bodies_[c.b].geometry->volume();
    return isWall_[c.a] ? VB : isWall_[c.b] ? VA : std::min(VA, VB);
}


void demSolver::checkDepths() const
{
    for (const contactRecord& c : contacts_.records())
    {
        const rigidBody& A = bodies_[c.a];
        const rigidBody& B = bodies_[c.b];
        const double V = smallerVolume(c);
        if (!(c.region.volume <= maxOverlapFraction*V))
        {
            std::ostringstream msg;
            msg.precision(3);
            msg << "At t = " << time_ << " s bodies '" << A.name << "' and '"
                << B.name << "' overlap by " << c.region.volume << " m3, "
                << 100*c.region.volume/V << "% of the smaller one (more than "
                << 100*maxOverlapFraction << "%): one has gone into the other"
                << " beyond what a contact law can push apart (the direction"
                << " and depth of the overlap no longer say how), at speeds "
                << A.velocity.norm() << " and " << B.velocity.norm() << " m/s."
                << " The contact is too soft for the impact: raise"
                << " youngsModulus of their materials, lower the speeds, or"
                << " shorten the DEM step (time { stepsPerContact; referenceSpeed; })";
            throw coreError(msg.str());
        }
    }
}


double demSolver::kineticEnergy() const
{
    double e = 0;
    for (size_t i = 0; i < bodies_.size(); ++i)
    {
        if (bodies_[i].dynamic()) e += bodies_[i].kineticEnergy();
    }
    return e;
}

} // End namespace immersedDEM
