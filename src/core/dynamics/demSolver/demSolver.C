#include "demSolver.H"
#include "demSolverRegion.H"
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
    //- Spheres and planes among themselves: their contact and gap are
    //  analytic and cheap, never worth carrying
    bool analyticPair(const shape& a, const shape& b)
    {
        auto analytic = [](const shape& s)
        {
            return s.type() == "sphere" || s.type() == "plane";
        };
        return analytic(a) && analytic(b);
    }
}


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
    )
{
    if (materials_.empty())
    {
        throw coreError("The DEM needs at least one material");
    }
    for (const contactMaterial& m : materials_)
    {
        m.check();
    }
    for (const contactMaterial& a : materials_)
    {
        for (const contactMaterial& b : materials_)
        {
            pairMaterials_.push_back(pairMaterial::of(a, b));
        }
    }
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
    bodies_.push_back(std::move(b));
    isWall_.push_back(wall);
    identity_.push_back(nextIdentity_++);
    loadsCurrent_ = false;
    return int(bodies_.size()) - 1;
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

    // Pairs keep their order (wall or lower index first): renumbering
    // keeps the order of the indices
    history_.renumber(newIndex);
    // Reuse records are keyed by the old indices: the next contacts are
    // evaluated in full
    reuse_.clear();
    films_.clear();
    std::vector<contactRecord> contacts;
    for (contactRecord c : contacts_)
    {
        if (newIndex[c.a] >= 0 && newIndex[c.b] >= 0)
        {
            c.a = newIndex[c.a];
            c.b = newIndex[c.b];
            contacts.push_back(c);
        }
    }
    contacts_.swap(contacts);
    std::set<size_t> warned;
    for (const size_t i : warnedTravel_)
    {
        if (newIndex[i] >= 0) warned.insert(size_t(newIndex[i]));
    }
    warnedTravel_.swap(warned);

    // The broad phase starts afresh
    boxes_.clear();
    listBox_.clear();
    neighbours_.clear();
    loadsCurrent_ = false;
    return kept;
}


void demSolver::addPairLoad(const pairLoad& l)
{
    addContactLoad(l);
    rigidBody& A = bodies_[l.a];
    rigidBody& B = bodies_[l.b];
    A.lubricationForce += l.filmForceA;
    A.lubricationTorque += l.filmTorqueA;
    B.lubricationForce += l.filmForceB;
    B.lubricationTorque += l.filmTorqueB;
}


std::vector<std::pair<int, int>> demSolver::pairsInContact() const
{
    std::vector<std::pair<int, int>> pairs(history_.size());
    for (size_t k = 0; k < pairs.size(); ++k) pairs[k] = history_.key(k);
    return pairs;
}


double demSolver::effectiveRadius(int a, int b) const
{
    const double Rb = bodies_[b].equivalentRadius();
    if (isWall_[a])
    {
        return Rb;
    }
    const double Ra = bodies_[a].equivalentRadius();
    return Ra*Rb/(Ra + Rb);
}


std::vector<std::pair<int, int>> demSolver::gridPairs
(
    const std::vector<axisAlignedBox>& box, const std::vector<int>& others
)
{
    double cell = 0;
    for (const int i : others)
    {
        cell = std::max(cell, box[i].span().maxCoeff());
    }
    std::vector<std::pair<int, int>> pairs;
    if (!(cell > 0))
    {
        return pairs;
    }
    // A uniform grid of cells as large as the largest box, so a box spans
    // at most 2 cells per axis. A pair is tested in the cell holding the
    // lower corner of the two boxes' intersection only, so it is found once.
    using key = std::array<long, 3>;
    auto index = [cell](const vec3& p)
    {
        return key
        {
            long(std::floor(p.x()/cell)), long(std::floor(p.y()/cell)),
            long(std::floor(p.z()/cell))
        };
    };
    // (cell, body) entries sorted by cell: the bodies of a cell are a run
    std::vector<std::pair<key, int>> entries;
    entries.reserve(8*others.size());
    for (const int i : others)
    {
        const key lo = index(box[i].min), hi = index(box[i].max);
        for (long x = lo[0]; x <= hi[0]; ++x)
            for (long y = lo[1]; y <= hi[1]; ++y)
                for (long z = lo[2]; z <= hi[2]; ++z)
                    entries.emplace_back(key{x, y, z}, i);
    }
    std::sort(entries.begin(), entries.end());
    for (size_t first = 0; first < entries.size();)
    {
        size_t last = first;
        while (last < entries.size() && entries[last].first == entries[first].first) ++last;
        for (size_t s = first; s < last; ++s)
        {
            for (size_t t = s + 1; t < last; ++t)
            {
                const int i = entries[s].second, j = entries[t].second;
                if (!box[i].overlaps(box[j])) continue;
                if (index(box[i].min.cwiseMax(box[j].min)) != entries[first].first) continue;
                pairs.emplace_back(std::min(i, j), std::max(i, j));
            }
        }
        first = last;
    }
    std::sort(pairs.begin(), pairs.end());
    return pairs;
}


void demSolver::refreshNeighbours
(
    const std::vector<axisAlignedBox>& box, const std::vector<int>& others, double cell
)
{
    // The neighbour list: pairs of bodies whose boxes, grown by a skin,
    // overlap. Kept while every box stays inside its grown box of the last
    // build, so that any two boxes that overlap now are in it
    const size_t n = box.size();
    bool valid = listBox_.size() == n;
    for (size_t k = 0; valid && k < others.size(); ++k)
    {
        const int i = others[k];
        valid =
            (box[i].min.array() >= listBox_[i].min.array()).all()
         && (box[i].max.array() <= listBox_[i].max.array()).all();
    }
    if (!valid)
    {
        const double skin = 0.1*cell;
        listBox_.assign(n, axisAlignedBox());
        for (const int i : others)
        {
            listBox_[i] = box[i].inflated(skin);
        }
        neighbours_ = gridPairs(listBox_, others);
        ++counters_.broadPhaseBuilds;
    }
}


std::vector<std::pair<int, int>> demSolver::candidatePairs()
{
    const int n = int(bodies_.size());
    std::vector<axisAlignedBox>& box = boxes_;
    box.resize(n);
    std::vector<int> walls, others;
    double cell = 0;
    // Lubrication reaches beyond the contact: boxes grown by half its
    // activation distance meet where the gap may be below it
    const double margin = 0.5*lubricationReach();
    const bool lub = margin > 0;
    // Each body's centre, bounding radius and whether it moves, compact:
    // the pair loops below read these, not the bodies
    balls_.resize(n);
    for (int i = 0; i < n; ++i)
    {
        const rigidBody& b = bodies_[i];
        box[i] = b.geometry->worldBox(b.pose);
        if (margin > 0) box[i] = box[i].inflated(margin);
        balls_[i].centre = b.pose.position();
        balls_[i].radius = b.geometry->boundingRadius();
        // (a prescribed one too when lubricating: its film is output)
        balls_[i].moves = b.dynamic() || (lub && b.motion != motionType::fixed);
        if (isWall_[i])
        {
            walls.push_back(i);
        }
        else
        {
            others.push_back(i);
            cell = std::max(cell, box[i].span().maxCoeff());
        }
    }

    refreshNeighbours(box, others, cell);

    std::vector<std::pair<int, int>> pairs;
    pairs.reserve(neighbours_.size() + walls.size()*others.size());

    // With the pair filter on, a pair whose bounding spheres are farther
    // apart than both the engine's and the lubrication's reach is one both
    // filters would reject first (pairFilter's test 1): dropped here,
    // unless a contact of it is being carried (reuse_ asks no filter). A
    // plane wall's box holds everything: its pairs are dropped so by the
    // height of the body's centre above it
    const double dropBeyond = settings_.rejectSeparated
        ? std::max(engineReach(), 2*margin)
        : std::numeric_limits<double>::infinity();

    // Walls (few, large) against every body that can move
    for (const int w : walls)
    {
        const bool plane = shapeAs<halfSpaceShape>(*bodies_[w].geometry) != nullptr;
        const vec3 n = bodies_[w].pose.vectorToWorld(vec3::UnitZ());
        const vec3& p0 = bodies_[w].pose.position();
        for (const int i : others)
        {
            if (!balls_[i].moves || !box[w].overlaps(box[i])) continue;
            if
            (
                plane
             && n.dot(balls_[i].centre - p0) - balls_[i].radius > dropBeyond
             && (reuse_.empty() || reuse_.find(std::make_pair(w, i)) == reuse_.end())
            )
            {
                ++counters_.droppedBySpheres;
                continue;
            }
            pairs.emplace_back(w, i);
        }
    }
    // Both parts are sorted: merge them
    const size_t nWallPairs = pairs.size();
    for (const auto& p : neighbours_)
    {
        const int i = p.first, j = p.second;
        if (!balls_[i].moves && !balls_[j].moves) continue;
        if (!box[i].overlaps(box[j])) continue;
        const double spheres =
            (balls_[i].centre - balls_[j].centre).norm() - balls_[i].radius - balls_[j].radius;
        if (spheres > dropBeyond && (reuse_.empty() || reuse_.find(p) == reuse_.end()))
        {
            ++counters_.droppedBySpheres;
            continue;
        }
        pairs.push_back(p);
    }
    std::inplace_merge(pairs.begin(), pairs.begin() + nWallPairs, pairs.end());
    return pairs;
}


bool demSolver::reusable(int ia, int ib) const
{
    // The potential law reused: F = w'(V0 - S.u - M.dtheta) S, the gradient
    // of w of the first-order volume, is conservative between two full
    // evaluations (the error is that of the volume, within reuseTolerance)
    if
    (
        !settings_.reuseContacts || law_->needsSpheres() || engine_->type() == "sphere"
    )
    {
        return false;
    }
    // Pairs measured exactly by the convex path (convexOverlap): a few
    // microseconds per sub-step, exact; carried, they would cost about 2
    // to 3 times less but take the first-order error of S, M and the
    // normal (contactScaleBenchmark --reuse-only, src/README.md)
    const shape& A = *bodies_[ia].geometry;
    const shape& B = *bodies_[ib].geometry;
    if
    (
        engine_->type() == "convex"
     || (engine_->type() == "virtualMesh" && settings_.overlap.convexExact && convexOverlap::handles(A, B))
    )
    {
        return false;
    }
    // Spheres and planes among themselves: analytic and cheap already
    return !analyticPair(A, B);
}


bool demSolver::carryRecord
(
    const reuseRecord& rec, int ia, int ib, contactGeometry& g,
    bool anyMotion, double& moved, vec3* u0
) const
{
    if (!anyMotion && rec.count >= settings_.reuseMaxSteps)
    {
        return false;
    }
    const rigidBody& A = bodies_[ia];
    const rigidBody& B = bodies_[ib];
    const bodyPose& A0 = rec.poseA;
    const bodyPose& B0 = rec.poseB;
    const bodyPose& A1 = A.pose;

    // B's pose now, seen from A's frame at the full evaluation: the
    // relative motion since is the move from B0 to Bs (world frame of then)
    const bodyPose Bs
    (
        A0.toWorld(A1.toBody(B.pose.position())),
        A0.orientation()*A1.orientation().conjugate()*B.pose.orientation()
    );
    quat dq = Bs.orientation()*B0.orientation().conjugate();
    if (dq.w() < 0) dq.coeffs() = -dq.coeffs();
    const double sinHalf = dq.vec().norm();
    const double angle = 2*std::atan2(sinHalf, dq.w());
    const vec3 dtheta = sinHalf > 0 ? vec3(angle/sinHalf*dq.vec()) : vec3::Zero();

    // The relative displacement of B's material points at x
    auto move = [&](const vec3& x) { return vec3(Bs.toWorld(B0.toBody(x)) - x); };

    // The most any point of either body has moved relative to the other
    // (over B's bounding ball, and over A's: a new region can only appear
    // where both are)
    const double chord = 2*sinHalf;
    const double dB = move(B0.position()).norm() + chord*B.geometry->boundingRadius();
    const double dA = move(A0.position()).norm() + chord*A.geometry->boundingRadius();
    moved = std::min(dA, dB);
    if (!anyMotion && !(moved <= rec.fraction*rec.depth))
    {
        return false;
    }

    // The contact point moves with B in the share R_A/(R_A + R_B) (as the
    // point between two spheres; with B against a wall)
    const double RB = B.equivalentRadius();
    const double w = isWall_[ia] ? 1.0 : A.equivalentRadius()/(A.equivalentRadius() + RB);
    const mat3 RT = A1.rotation()*A0.rotation().transpose();
    g.regions.clear();
    for (const contactRegion& r0 : rec.regions)
    {
        const vec3 u = move(r0.point);
        vec3 S = r0.areaVector.squaredNorm() > 0 ? r0.areaVector : vec3(r0.area*r0.normal);
        if (rec.regions.size() == 1)
        {
            S += A0.vectorToWorld(rec.slope);
            if (u0) *u0 = u;
        }
        // dV/du_B = -S, dV/dtheta_B = -M about the point (S the integral
        // of A's outward normal over A's surface inside B)
        const double V = r0.volume - S.dot(u) - r0.areaMoment.dot(dtheta);
        if (!(V > 0))
        {
            return false;
        }
        contactRegion r = r0;
        const vec3 p = r0.point + w*u;
        r.volume = V;
        r.point = A1.toWorld(A0.toBody(p));
        r.normal = RT*r0.normal;
        if (r0.areaVector.squaredNorm() > 0)
        {
            r.areaVector = RT*r0.areaVector;
            // The moment about the moved point
            r.areaMoment = RT*(r0.areaMoment - (p - r0.point).cross(r0.areaVector));
        }
        g.regions.push_back(r);
    }
    return true;
}


bool demSolver::applyContacts
(
    int ia, int ib, const contactGeometry& g, contactHistoryTable& next
)
{
    const rigidBody& A = bodies_[ia];
    const rigidBody& B = bodies_[ib];
    if (g.regions.empty())
    {
        return false;
    }

    const double mA = A.mass(), mB = B.mass();
    const double Reff = effectiveRadius(ia, ib);

    contactInput in;
    in.material = pairMaterialOf(A.material, B.material);
    in.effectiveMass = effectiveMass(mA, A.dynamic(), mB, B.dynamic());
    in.characteristicLength =
        settings_.characteristicLength > 0 ? settings_.characteristicLength : Reff;

    // Overlap depth for laws on spheres: B is a sphere (walls are A)
    in.overlapDepth = 0;
    in.effectiveRadius = Reff;
    if (law_->needsSpheres())
    {
        const auto* sb = shapeAs<sphereShape>(*B.geometry);
        if (const auto* sa = shapeAs<sphereShape>(*A.geometry))
        {
            in.overlapDepth =
                sphereDepth(A.pose.position(), sa->radius(), B.pose.position(), sb->radius());
            in.effectiveRadius = sa->radius()*sb->radius()/(sa->radius() + sb->radius());
        }
        else
        {
            in.overlapDepth = sb->radius() - A.geometry->signedDistance(A.pose, B.pose.position());
            in.effectiveRadius = sb->radius();
        }
    }
    in.flatFaceArea =
        std::min(A.geometry->largestFlatFace(), B.geometry->largestFlatFace());
    in.pairVolume = g.volume();
    in.dt = lastDt_;

    const bodyState a{A.pose.position(), A.velocity, A.angularVelocity};
    const bodyState b{B.pose.position(), B.velocity, B.angularVelocity};
    applyRegions(ia, a, ib, b, g.regions.data(), g.regions.size(), in, next);
    return true;
}


void demSolver::applyRegions
(
    int ia, const bodyState& A, int ib, const bodyState& B,
    const contactRegion* regions, size_t nRegions, contactInput& in,
    contactHistoryTable& next
)
{
    // The pair's histories of the last step (pairs come in increasing
    // order: found by the table's cursor), and its entry in the next
    const auto key = std::make_pair(ia, ib);
    const contactHistoryTable::range oldHistory = history_.find(key);
    next.beginPair(key);
    taken_.assign(oldHistory.size(), 0);
    for (size_t k = 0; k < nRegions; ++k)
    {
        const int best = nearestHistory(oldHistory, regions[k], taken_.data());
        if (best >= 0)
        {
            taken_[best] = 1;
        }
        applyRegion
        (
            ia, A, ib, B, regions[k], in, best >= 0 ? oldHistory.first + best : nullptr, next
        );
    }
}


void demSolver::applyRegion
(
    int ia, const bodyState& A, int ib, const bodyState& B,
    const contactRegion& r, contactInput& in, const contactHistory* old,
    contactHistoryTable& next
)
{
    // Twisting friction (contactLaw::twistingCouple) for the laws on
    // overlap regions: a flat face resting on another stops spinning
    // about its normal (a point's friction has no couple about it). The
    // law on spheres keeps its point contact (as LIGGGHTS's)
    const contactLaw& law = *law_;
    applyRegionWith
    (
        ia, A, ib, B, r, in, old, next,
        [&law](const contactInput& i, contactHistory& h) { return law.evaluate(i, h); },
        !law.needsSpheres(), false
    );
}


double demSolver::lubricationReach() const
{
    if (!lubricating())
    {
        return 0;
    }
    double h = 0;
    for (size_t i = 0; i < bodies_.size(); ++i)
    {
        if (!isWall_[i]) h = std::max(h, bodies_[i].fluidCellSize);
    }
    return settings_.lubrication.activation*h;
}


double demSolver::inverseMassAlong
(
    const rigidBody& b, const vec3& x, const vec3& n, double addedMass
) const
{
    if (!b.dynamic())
    {
        return 0;
    }
    const vec3 rn = (x - b.pose.position()).cross(n);
    return 1/(b.mass() + addedMass) + b.inverseInertiaAlong(rn);
}


void demSolver::lubricatePair(int ia, int ib, size_t contactsFrom)
{
    rigidBody& A = bodies_[ia];
    rigidBody& B = bodies_[ib];
    // The activation distance: in the finer fluid cells of the two
    double cell = 0;
    for (const rigidBody* b : {&A, &B})
    {
        if (b->fluidCellSize > 0 && !isWall_[b == &A ? ia : ib])
        {
            cell = cell > 0 ? std::min(cell, b->fluidCellSize) : b->fluidCellSize;
        }
    }
    const lubricationSettings& ls = settings_.lubrication;
    const double hAct = ls.activation*cell;
    if (!(hAct > 0))
    {
        return;
    }
    // A film measured earlier in this advance, carried while the bodies
    // have moved, relative to each other, by less than a small fraction
    // of its gap: the gap and the normal follow the material points that
    // were closest (first order in the motion)
    const std::pair<int, int> key(ia, ib);
    const auto carried = films_.find(key);
    if
    (
        carried != films_.end()
     && carried->second.count < settings_.reuseMaxSteps
     && pairFilter::motionBound(carried->second.poseA, A.pose, A.geometry->boundingRadius())
      + pairFilter::motionBound(carried->second.poseB, B.pose, B.geometry->boundingRadius())
      < filmCarryFraction*carried->second.gap
    )
    {
        filmRecord& f = carried->second;
        ++f.count;
        // The filter's record lives on as near: when the film is measured
        // again, no new proof (a body near a wall mesh: milliseconds)
        lubricationFilter_.stillTouching(ia, ib);
        const vec3 pa = A.pose.toWorld(f.pointA);
        const vec3 pb = B.pose.toWorld(f.pointB);
        const vec3 n = A.pose.vectorToWorld(f.normal);
        const double gap = (pb - pa).dot(n);
        ++counters_.reusedFilms;
        if (gap < hAct)
        {
            const mat3& RA = A.pose.rotation();
            applyFilm
            (
                A, B, 0.5*(pa + pb), n, gap, f.radius, hAct,
                ls.roughness*effectiveRadius(ia, ib), f.footprintArea,
                RA*f.footprintSpread*RA.transpose(), f.footprintHeight,
                A.pose.toWorld(f.footprintCentre)
            );
        }
        return;
    }
    if (carried != films_.end())
    {
        films_.erase(carried);
    }
    // In contact now: the film is the contact's (its largest region's
    // point and normal, at no gap), so no search for the closest approach
    const contactRecord* best = nullptr;
    for (size_t k = contactsFrom; k < contacts_.size(); ++k)
    {
        if (!best || contacts_[k].region.volume > best->region.volume)
        {
            best = &contacts_[k];
        }
    }
    if (best)
    {
        const double Rcap = effectiveRadius(ia, ib);
        const vec3& x = best->region.point;
        const vec3& n = best->region.normal;
        const double R = lubrication::gapRadius
        (
            lubrication::curvatureNear(*A.geometry, A.pose, x),
            lubrication::curvatureNear(*B.geometry, B.pose, x),
            n, Rcap
        );
        applyFilm(A, B, x, n, 0, R, hAct, ls.roughness*Rcap);
        return;
    }
    lubricationFilter_.setReach(hAct);
    if (lubricationFilter_.separated(ia, ib, *A.geometry, A.pose, *B.geometry, B.pose))
    {
        return;
    }
    const closestApproach c =
        lubrication::approach(*A.geometry, A.pose, *B.geometry, B.pose, hAct);
    lubricationFilter_.engineResult(ia, ib, c.found);
    if (!c.found || !(c.gap < hAct))
    {
        return;
    }
    if (!(c.gap > 0))
    {
        // Touching with no contact region (an overlap below the engine's
        // threshold): no film to speak of
        return;
    }
    const vec3& n = c.normal;
    const vec3 x = 0.5*(c.pointA + c.pointB);
    const double Rcap = effectiveRadius(ia, ib);
    const double R = lubrication::gapRadius
    (
        lubrication::curvatureNear(*A.geometry, A.pose, x),
        lubrication::curvatureNear(*B.geometry, B.pose, x),
        n, Rcap
    );
    // (spheres and planes are measured exactly and cheaply every time)
    if (settings_.reuseContacts && !analyticPair(*A.geometry, *B.geometry))
    {
        filmRecord& f = films_[key];
        f.poseA = A.pose;
        f.poseB = B.pose;
        f.pointA = A.pose.toBody(c.pointA);
        f.pointB = B.pose.toBody(c.pointB);
        f.normal = A.pose.vectorToBody(n);
        f.gap = c.gap;
        f.radius = R;
        f.footprintArea = c.footprintArea;
        f.footprintSpread =
            A.pose.rotation().transpose()*c.footprintSpread*A.pose.rotation();
        f.footprintHeight = c.footprintHeight;
        f.footprintCentre = A.pose.toBody(c.footprintCentre);
        f.count = 0;
    }
    applyFilm
    (
        A, B, x, n, c.gap, R, hAct, ls.roughness*Rcap, c.footprintArea,
        c.footprintSpread, c.footprintHeight, c.footprintCentre
    );
}


double demSolver::filmShare(const rigidBody& A, const rigidBody& B) const
{
    int n = 1;
    for (const rigidBody* b : {&A, &B})
    {
        const size_t i = size_t(b - bodies_.data());
        if (b->dynamic() && i < filmNeighbours_.size())
        {
            n = std::max(n, filmNeighbours_[i]);
        }
    }
    return 1.0/n;
}


void demSolver::applyFilm
(
    const rigidBody& A, const rigidBody& B, const vec3& x, const vec3& n,
    double gap, double R, double hAct, double hRough,
    double footprintArea, const mat3& footprintSpread,
    double footprintHeight, const vec3& footprintCentre
)
{
    double coeff = lubrication::coefficient
    (
        settings_.lubrication.viscosity, R, gap, hAct, hRough
    );
    // Nearly parallel flat faces: the squeeze film of their footprint
    // when stronger than the curvature's (the 1/h^3 of parallel plates),
    // at their mean gap; tilted against each other, a wedge from the
    // closest gap to twice the mean's excess over it: its factors, and
    // the force at its pressure centre, from the footprint's centre
    // towards the closest points (x, at about half the footprint's length
    // from it)
    lubrication::tangentAxes axes;
    lubrication::flatFilm flat;
    vec3 at = x;
    if (footprintArea > 0)
    {
        axes = lubrication::principalInPlane(footprintSpread, n);
        const double hMin = std::max(gap, std::min(hRough, hAct));
        const double height = std::max(footprintHeight, 0.0);
        flat = lubrication::flatCoefficients
        (
            settings_.lubrication.viscosity, footprintArea, axes.s[0],
            axes.s[1], gap + height, hAct, hRough
        );
        const lubrication::wedgeFactors w = lubrication::wedge(1 + 2*height/hMin);
        // The centre on the film's mid-plane, and the direction of the
        // closest gap from it
        const vec3 centre = footprintCentre + n.dot(x - footprintCentre)*n;
        vec3 thin = x - centre;
        thin -= n.dot(thin)*n;
        const double thinLength = thin.norm();
        const vec3 g = thinLength > 0 ? vec3(thin/thinLength) : vec3::Zero();
        flat.normal *= w.normal;
        // The tilt across the gradient takes the wedge's factor, about it
        // the normal film's
        const double across1 = n.cross(axes.e[0]).dot(g);
        const double across2 = n.cross(axes.e[1]).dot(g);
        flat.tilt1 *= w.normal + (w.tilt - w.normal)*across1*across1;
        flat.tilt2 *= w.normal + (w.tilt - w.normal)*across2*across2;
        if (flat.normal > coeff)
        {
            coeff = flat.normal;
            at = centre + 2*w.offset*thinLength*g;
        }
    }
    // Bodies carrying their added mass m_a as inertia (fluidLoad.H;
    // rigidBodyIntegrator): the film's force is scaled so that it slows
    // the approach as it would bodies carrying only their nominal added
    // mass Ca rho V (m_a may be the forcing's larger one, needed for the
    // coupling's stability; the film is below the mesh). With the damper
    // both are 0: no scaling
    const double invMass =
        inverseMassAlong(A, at, n, A.fluid.addedMass)
      + inverseMassAlong(B, at, n, B.fluid.addedMass);
    const double invNominal =
        inverseMassAlong(A, at, n, A.fluid.nominalAddedMass)
      + inverseMassAlong(B, at, n, B.fluid.nominalAddedMass);
    if (invMass > 0)
    {
        coeff *= invNominal/invMass;
    }
    // The film's dampers (the normal one at its point, the tilt about the
    // footprint's axes) together remove at most the whole relative motion
    // in one step, and a body's films together at most its whole
    // velocity: each film a share 1/n of it, n the most films either body
    // may have (films limited each to the whole made a body between three
    // faces overshoot, and grow: bodies of a pile spun up to 1.7 rad/s).
    // Together: the normal force at the wedge's pressure centre, off the
    // bodies' centres, also turns them, so dampers limited each alone to
    // the whole of their own motion take out more than the whole of a
    // coupled one (up to 1 + the coupling) and reverse it. The rates
    // dt c_k K_kk (K_kk the pair's inverse mass or moment of inertia
    // along damper k) are scaled so that their sum is at most the share:
    // the sum bounds the largest rate of the coupled dampers (the trace
    // of D^1/2 K D^1/2, K = J M^-1 J^T), so no motion is reversed
    const double dt = lastDt_ > 0 ? lastDt_ : timeStep();
    const double share = filmShare(A, B);
    double tilt[2] = {flat.tilt1, flat.tilt2};
    if (dt > 0 && dt < std::numeric_limits<double>::max())
    {
        double rate = std::max(invMass, 0.0)*coeff*dt;
        for (int k = 0; k < 2; ++k)
        {
            rate +=
                (A.inverseInertiaAlong(axes.e[k]) + B.inverseInertiaAlong(axes.e[k]))
               *tilt[k]*dt;
        }
        if (rate > share)
        {
            const double f = share/rate;
            coeff *= f;
            tilt[0] *= f;
            tilt[1] *= f;
        }
    }
    const double un = (B.pointVelocity(at) - A.pointVelocity(at)).dot(n);
    const vec3 F = -coeff*un*n;
    load_.filmForceB += F;
    load_.filmTorqueB += (at - B.pose.position()).cross(F);
    load_.filmForceA -= F;
    load_.filmTorqueA -= (at - A.pose.position()).cross(F);
    // The tilting film's torque on B (its opposite on A)
    const vec3 w = B.angularVelocity - A.angularVelocity;
    vec3 T = vec3::Zero();
    for (int k = 0; k < 2; ++k)
    {
        T -= tilt[k]*w.dot(axes.e[k])*axes.e[k];
    }
    load_.filmTorqueB += T;
    load_.filmTorqueA -= T;
    load_.film = true;
    ++counters_.lubricatedPairs;
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
            effectiveMass(A.mass(), A.dynamic() && !isWall_[a], B.mass(), B.dynamic() && !isWall_[b]);
        const double tc =
            law_->contactTime(pairMaterialOf(A.material, B.material), m, Reff, lc, v);
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
    contacts_.clear();
    contactHistoryTable& next = nextHistory_;
    next.clear();
    const bool filter = settings_.rejectSeparated;
    if (filter)
    {
        filter_.setReach(engineReach());
        filter_.rejectProvenGaps(true);
        filter_.beginSweep();
    }
    const bool full = fullNext_ || !settings_.reuseContacts;
    ++contactPass_;
    contactGeometry g;
    const bool lub = lubricating();
    if (lub)
    {
        lubricationFilter_.beginSweep();
    }
    // The contact of one candidate pair: carried from its last full
    // evaluation while within the bound, else evaluated
    auto contactOf = [&](const std::pair<int, int>& p)
    {
        const rigidBody& A = bodies_[p.first];
        const rigidBody& B = bodies_[p.second];

        // A lasting contact within its bound: carried, not evaluated (and
        // not asked of the filter: the filter only ever rejects pairs the
        // engine would find apart, so the reuse decisions, and so the
        // trajectories, do not depend on the filter)
        if (!full)
        {
            const auto it = reuse_.find(p);
            double moved = 0;
            if (it != reuse_.end() && carryRecord(it->second, p.first, p.second, g, false, moved))
            {
                ++it->second.count;
                it->second.lastPass = contactPass_;
                ++counters_.reusedEvaluations;
                applyContacts(p.first, p.second, g, next);
                if (filter) filter_.stillTouching(p.first, p.second);
                return;
            }
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
        const bool touching = applyContacts(p.first, p.second, g, next);
        if (touching && reusable(p.first, p.second))
        {
            // The bound: a fraction of the shallowest region's equivalent
            // depth V/area
            double depth = std::numeric_limits<double>::max();
            for (const contactRegion& r : g.regions)
            {
                depth = std::min(depth, r.area > 0 ? r.volume/r.area : 0.0);
            }
            const auto it = reuse_.find(p);
            const double reuseTol =
                law_->type() == "potential"
              ? settings_.reuseTolerancePotential : settings_.reuseTolerance;
            double fraction = settings_.reuseFraction;
            vec3 slope = vec3::Zero();
            // (a full evaluation forced at the end of an advance starts
            // the pair afresh, as a restart from there does)
            if (it != reuse_.end() && !full)
            {
                // The error of the last record carried to here, where it
                // was given up, sets the fraction of the next: the error
                // taken as growing linearly with the motion (the error of
                // S and M), the motion that keeps it within the tolerance
                fraction = it->second.fraction;
                contactGeometry carried;
                double moved = 0;
                vec3 u = vec3::Zero();
                if
                (
                    it->second.regions.size() == g.regions.size()
                 && carryRecord(it->second, p.first, p.second, carried, true, moved, &u)
                 && moved > 0 && it->second.depth > 0
                )
                {
                    const double V = g.volume();
                    // The secant update of a single region's slope along
                    // the motion u (A's body frame), when the motion is
                    // well above round-off; at most half of |S|
                    if (g.regions.size() == 1 && moved > 0.25*it->second.fraction*it->second.depth && u.squaredNorm() > 0)
                    {
                        const contactRegion& r0 = it->second.regions[0];
                        const double e = V - carried.volume();
                        vec3 c = it->second.slope - e*it->second.poseA.vectorToBody(u)/u.squaredNorm();
                        const double Sn = r0.areaVector.squaredNorm() > 0 ? r0.areaVector.norm() : r0.area;
                        if (c.norm() > 0.5*Sn) c *= 0.5*Sn/c.norm();
                        slope = c;
                    }
                    else if (g.regions.size() == 1)
                    {
                        slope = it->second.slope;
                    }
                    const double error = std::abs(carried.volume() - V)/V;
                    const double perDepth = error/(moved/it->second.depth);
                    // (an error far below the tolerance says nothing of
                    // its growth: the fraction may double)
                    fraction =
                        error <= 0.1*reuseTol
                      ? 2*fraction
                      : std::min(2*fraction, reuseTol/perDepth);
                }
                // The engine's S is known off by |c| along one direction:
                // it may be so along any, and the motion is bounded so
                // that such an error stays within the tolerance too
                if (g.regions.size() == 1 && slope.squaredNorm() > 0)
                {
                    const contactRegion& r = g.regions[0];
                    const double Sn = r.areaVector.squaredNorm() > 0 ? r.areaVector.norm() : r.area;
                    fraction = std::min(fraction, reuseTol*Sn/slope.norm());
                }
                fraction = std::max
                (
                    settings_.reuseFractionMin, std::min(settings_.reuseFractionMax, fraction)
                );
            }
            reuseRecord& rec = it != reuse_.end() ? it->second : reuse_[p];
            rec.poseA = A.pose;
            rec.poseB = B.pose;
            rec.regions = g.regions;
            rec.depth = depth;
            rec.fraction = fraction;
            rec.slope = slope;
            rec.count = 0;
            rec.lastPass = contactPass_;
        }
        if (filter)
        {
            filter_.engineResult(p.first, p.second, touching);
        }
    };
    using clock = std::chrono::steady_clock;
    auto since = [](clock::time_point a)
    {
        return std::chrono::duration<double>(clock::now() - a).count();
    };
    // This process's pairs (all of them, alone): their loads, summed per
    // pair, are added to the bodies in the order of the pairs once every
    // process's are gathered, so the sums do not depend on who made them
    loads_.clear();
    if (sphereSweepApplies())
    {
        sphereSweep(next);
    }
    else
    {
        const auto searchStart = clock::now();
        const auto candidates = candidatePairs();
        counters_.searchSeconds += since(searchStart);
        if (lub)
        {
            // Each body's pairs that may carry a film this step (an upper
            // bound on its films: every process counts all pairs alike)
            filmNeighbours_.assign(bodies_.size(), 0);
            for (const auto& p : candidates)
            {
                ++filmNeighbours_[p.first];
                ++filmNeighbours_[p.second];
            }
        }
        for (const auto& p : candidates)
        {
            if (!owns(p.first, p.second))
            {
                continue;
            }
            load_ = pairLoad();
            load_.a = p.first;
            load_.b = p.second;
            load_.contactsFrom = contacts_.size();
            if (bodies_[p.first].dynamic() || bodies_[p.second].dynamic())
            {
                contactOf(p);
            }
            if (lub)
            {
                const auto lubStart = clock::now();
                lubricatePair(p.first, p.second, load_.contactsFrom);
                counters_.lubricationSeconds += since(lubStart);
            }
            load_.contactsTo = contacts_.size();
            if (load_.film || load_.contactsTo > load_.contactsFrom)
            {
                loads_.push_back(load_);
            }
        }
    }
    if (comm_)
    {
        gatherLoads(next);
    }
    for (const pairLoad& l : loads_)
    {
        addPairLoad(l);
    }
    if (lub)
    {
        lubricationFilter_.endSweep();
    }
    // Records of pairs not in contact (or not reusable) now are dropped
    for (auto it = reuse_.begin(); it != reuse_.end();)
    {
        it = it->second.lastPass == contactPass_ ? std::next(it) : reuse_.erase(it);
    }
    if (filter)
    {
        filter_.endSweep();
    }
    next.finish();
    history_.swap(next);
    touched_.resize(bodies_.size(), 0);
    for (size_t k = 0; k < history_.size(); ++k)
    {
        const auto p = history_.key(k);
        touched_[p.first] = 1;
        touched_[p.second] = 1;
    }
    loadsCurrent_ = true;
    counters_.contactSeconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}


void demSolver::gatherLoads(contactHistoryTable& next)
{
    // This process's pairs, flat: per pair a, b, film, its region count,
    // its eight load vectors, then per region the contact record and the
    // history the law left
    std::vector<double> mine;
    auto put3 = [&mine](const vec3& v) { mine.insert(mine.end(), {v.x(), v.y(), v.z()}); };
    mine.push_back(double(loads_.size()));
    for (const pairLoad& l : loads_)
    {
        const size_t nr = l.contactsTo - l.contactsFrom;
        mine.insert(mine.end(), {double(l.a), double(l.b), double(l.film), double(nr)});
        for (const vec3* v : {&l.forceA, &l.torqueA, &l.forceB, &l.torqueB,
            &l.filmForceA, &l.filmTorqueA, &l.filmForceB, &l.filmTorqueB})
        {
            put3(*v);
        }
        contactHistoryTable::range hs;
        if (nr > 0)
        {
            hs = next.find(std::make_pair(l.a, l.b));
            if (hs.size() != nr)
            {
                throw coreError("demSolver: a pair's contact histories do not match its contacts");
            }
        }
        for (size_t k = 0; k < nr; ++k)
        {
            const contactRecord& c = contacts_[l.contactsFrom + k];
            const contactRegion& r = c.region;
            mine.push_back(r.volume);
            put3(r.point);
            put3(r.normal);
            mine.push_back(r.area);
            put3(r.areaVector);
            put3(r.areaMoment);
            const contactOutput& f = c.force;
            put3(f.force);
            mine.push_back(f.normalForce);
            put3(f.tangentialForce);
            put3(f.couple);
            mine.push_back(double(f.sliding));
            const contactHistory& h = hs.first[k];
            put3(h.tangentialSpring);
            put3(h.normal);
            put3(h.point);
            mine.push_back(h.approach);
            mine.push_back(h.maxNormalForce);
            mine.push_back(h.twist);
        }
    }

    const std::vector<std::vector<double>> all = comm_->allGather(mine);

    // Every process's pairs, read back, in the order of the pairs (each
    // process's are in that order already; a pair has one owner)
    struct gathered
    {
        pairLoad load;
        std::vector<contactRecord> contacts;
        std::vector<contactHistory> histories;
    };
    std::vector<gathered> pairs;
    for (const std::vector<double>& buf : all)
    {
        size_t at = 0;
        auto get = [&buf, &at]() { return buf.at(at++); };
        auto get3 = [&get]() { const double x = get(), y = get(), z = get(); return vec3(x, y, z); };
        const size_t nPairs = size_t(get());
        for (size_t k = 0; k < nPairs; ++k)
        {
            gathered g;
            pairLoad& l = g.load;
            l.a = int(get());
            l.b = int(get());
            l.film = get() != 0;
            const size_t nr = size_t(get());
            for (vec3* v : {&l.forceA, &l.torqueA, &l.forceB, &l.torqueB,
                &l.filmForceA, &l.filmTorqueA, &l.filmForceB, &l.filmTorqueB})
            {
                *v = get3();
            }
            for (size_t j = 0; j < nr; ++j)
            {
                contactRecord c;
                c.a = l.a;
                c.b = l.b;
                contactRegion& r = c.region;
                r.volume = get();
                r.point = get3();
                r.normal = get3();
                r.area = get();
                r.areaVector = get3();
                r.areaMoment = get3();
                contactOutput& f = c.force;
                f.force = get3();
                f.normalForce = get();
                f.tangentialForce = get3();
                f.couple = get3();
                f.sliding = get() != 0;
                contactHistory h;
                h.tangentialSpring = get3();
                h.normal = get3();
                h.point = get3();
                h.approach = get();
                h.maxNormalForce = get();
                h.twist = get();
                g.contacts.push_back(c);
                g.histories.push_back(h);
            }
            pairs.push_back(std::move(g));
        }
        if (at != buf.size())
        {
            throw coreError("demSolver: a process's contact loads were not read whole");
        }
    }
    std::sort
    (
        pairs.begin(), pairs.end(),
        [](const gathered& x, const gathered& y)
        {
            return std::make_pair(x.load.a, x.load.b) < std::make_pair(y.load.a, y.load.b);
        }
    );
    loads_.clear();
    contacts_.clear();
    next.clear();
    for (gathered& g : pairs)
    {
        g.load.contactsFrom = contacts_.size();
        contacts_.insert(contacts_.end(), g.contacts.begin(), g.contacts.end());
        g.load.contactsTo = contacts_.size();
        if (!g.histories.empty())
        {
            next.beginPair(std::make_pair(g.load.a, g.load.b));
            for (const contactHistory& h : g.histories) next.add(h);
        }
        loads_.push_back(g.load);
    }
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


double demSolver::contactTimeOf(int i, int k, double f, double v) const
{
    const rigidBody& b = bodies_[i];
    const double m = b.mass();
    const double R = b.equivalentRadius();
    const pairMaterial& pm = pairMaterialOf(b.material, k);
    const double Reff = f*R;
    const double lc =
        settings_.characteristicLength > 0 ? settings_.characteristicLength : Reff;
    double tc = law_->contactTime(pm, f*m, Reff, lc, v);

    // A mesh may touch with a flat face: a linear spring of stiffness
    // Y* A/l_c over its cross-section A ~ pi R^2, whose half period does
    // not depend on the speed
    if (!shapeAs<sphereShape>(*b.geometry))
    {
        const double kf = law_->faceStiffness(pm, M_PI*R*R, Reff, lc);
        tc = std::min(tc, M_PI*std::sqrt(f*m/kf));
    }
    return tc;
}


namespace
{
    // The largest speed of any body, and the smallest volume-equivalent
    // diameter of a body that is not a wall
    void speedAndSize
    (
        const std::vector<rigidBody>& bodies, const std::vector<char>& isWall,
        double& vMax, double& dMin
    )
    {
        vMax = 0;
        dMin = std::numeric_limits<double>::max();
        for (size_t i = 0; i < bodies.size(); ++i)
        {
            vMax = std::max(vMax, bodies[i].velocity.norm());
            if (!isWall[i]) dMin = std::min(dMin, 2*bodies[i].equivalentRadius());
        }
    }
}


double demSolver::timeStep() const
{
    if (settings_.deltaT > 0)
    {
        return settings_.deltaT;
    }
    double vMax, dMin;
    speedAndSize(bodies_, isWall_, vMax, dMin);
    const double v = std::max(settings_.referenceSpeed, 2*vMax);

    // Materials present
    std::vector<char> present(materials_.size(), 0);
    for (const rigidBody& b : bodies_) present[b.material] = 1;

    double tc = std::numeric_limits<double>::max();
    for (size_t i = 0; i < bodies_.size(); ++i)
    {
        if (!bodies_[i].dynamic()) continue;
        for (size_t k = 0; k < materials_.size(); ++k)
        {
            if (!present[k]) continue;
            // Against a like body (m*/2, R/2), and against a wall (m, R)
            for (const double f : {0.5, 1.0})
            {
                tc = std::min(tc, contactTimeOf(int(i), int(k), f, v));
            }
        }
    }
    if (tc == std::numeric_limits<double>::max())
    {
        return std::numeric_limits<double>::max();
    }
    // No body moves more than maxTravel of the smallest body's size
    // relative to another in a step, whatever the contact law says: the
    // fastest relative approach (at most 2 max|v|) cannot carry a body
    // through a wall or another body between two contact evaluations
    double dt = tc/settings_.stepsPerContact;
    if (vMax > 0 && dMin < std::numeric_limits<double>::max())
    {
        dt = std::min(dt, maxTravel*dMin/(2*vMax));
    }
    return dt;
}


demSolver::stepChoice demSolver::stepFor(double T) const
{
    stepChoice c;
    if (settings_.deltaT > 0)
    {
        c.deltaT = settings_.deltaT;
        c.userStep = true;
        return c;
    }
    const int n = int(bodies_.size());
    double vMax, dMin;
    speedAndSize(bodies_, isWall_, vMax, dMin);
    const double v = std::max(settings_.referenceSpeed, 2*vMax);

    // How far each body can go in T: its speed now and its acceleration
    // under the loads and forces now (fluid, weight, contacts, films), the
    // damper's pull to its reference course included; twice that, for
    // what a collision within the step may add
    const double g = settings_.gravity.norm();
    std::vector<double> travel(n, 0.0);
    for (int i = 0; i < n; ++i)
    {
        const rigidBody& b = bodies_[i];
        double a = 0;
        if (b.dynamic())
        {
            const double m = b.mass();
            const fluidLoad& fl = b.fluid;
            a = g
              + (
                    b.appliedFluidForce(time_).norm()
                  + fl.damping*fl.referenceAcceleration.norm()*T
                  + b.contactForce.norm() + b.lubricationForce.norm()
                )/m;
        }
        travel[i] = 2*(b.velocity.norm()*T + 0.5*a*T*T);
    }
    const double reach = std::max
    (
        engineReach(),
        lubricationReach()
    );

    double tc = std::numeric_limits<double>::max();
    auto consider = [&](int a, int b)
    {
        ++c.pairs;
        for (const int i : {a, b})
        {
            const int j = i == a ? b : a;
            if (!bodies_[i].dynamic()) continue;
            const double f = bodies_[j].dynamic() ? 0.5 : 1.0;
            const double t = contactTimeOf(i, bodies_[j].material, f, v);
            if (t < tc)
            {
                tc = t;
                c.a = a;
                c.b = b;
            }
        }
    };

    // Bodies: boxes grown by their travel and half the reach, then their
    // bounding spheres
    std::vector<int> others;
    std::vector<axisAlignedBox> grown(n);
    for (int i = 0; i < n; ++i)
    {
        grown[i] = bodies_[i].geometry->worldBox(bodies_[i].pose)
            .inflated(travel[i] + 0.5*reach);
        if (!isWall_[i]) others.push_back(i);
    }
    for (const auto& p : gridPairs(grown, others))
    {
        const int i = p.first, j = p.second;
        if (!bodies_[i].dynamic() && !bodies_[j].dynamic()) continue;
        const double gap =
            (bodies_[i].pose.position() - bodies_[j].pose.position()).norm()
          - bodies_[i].geometry->boundingRadius() - bodies_[j].geometry->boundingRadius();
        if (gap <= travel[i] + travel[j] + reach) consider(i, j);
    }
    // Walls: the distance from the body's centre to the wall's surface. A
    // turning wall (prescribed) moves near the body at most at
    // |v| + |w| |x - c|: no box test for it
    for (int w = 0; w < n; ++w)
    {
        if (!isWall_[w]) continue;
        const rigidBody& W = bodies_[w];
        const double spin = W.angularVelocity.norm();
        for (const int i : others)
        {
            if (!bodies_[i].dynamic() || (spin == 0 && !grown[w].overlaps(grown[i])))
            {
                continue;
            }
            const vec3& x = bodies_[i].pose.position();
            const double d = std::abs(W.geometry->closest(W.pose, x).distance);
            const double gap = d - bodies_[i].geometry->boundingRadius();
            const double wallTravel =
                travel[w] + 2*spin*((x - W.pose.position()).norm() + d)*T;
            if (gap <= travel[i] + wallTravel + reach) consider(w, i);
        }
    }

    double dt = T;
    if (tc < std::numeric_limits<double>::max())
    {
        dt = tc/settings_.stepsPerContact;
        if (vMax > 0 && dMin < std::numeric_limits<double>::max())
        {
            dt = std::min(dt, maxTravel*dMin/(2*vMax));
        }
    }
    else
    {
        // Free flight. The damper relaxes a body to its reference course
        // over m/c; the step's kicks integrate it to first order (the
        // second half kick sees the half-step velocity): 1/500 of m/c keeps
        // its error within 1e-3 of the relaxation. Never shorter than the
        // softest-case step, though (a measured added mass far above
        // Ca rho V makes m/c tiny)
        for (const rigidBody& b : bodies_)
        {
            if (!b.dynamic()) continue;
            const double relax = std::min
            (
                b.fluid.damping > 0
              ? b.mass()/b.fluid.damping : std::numeric_limits<double>::max(),
                b.fluid.angularDamping > 0
              ? b.inertia().minCoeff()/b.fluid.angularDamping
              : std::numeric_limits<double>::max()
            );
            if (0.002*relax < dt)
            {
                dt = 0.002*relax;
                c.nameA = b.name;
                c.relaxation = relax;
            }
        }
        if (dt < timeStep())
        {
            dt = timeStep();
            c.nameA.clear();
            c.floor = true;
        }
    }
    if (c.a >= 0)
    {
        c.nameA = bodies_[c.a].name;
        c.nameB = bodies_[c.b].name;
    }
    c.deltaT = std::min(dt, T);
    return c;
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
    // Velocity-dependent loads see the half-step velocity: evaluate them
    // at the half step
    loadTime_ = time_ + 0.5*dt;
    computeContacts();
    fullNext_ = false;
    loadTime_ = time_ + dt;
    for (rigidBody& b : bodies_)
    {
        rigidBodyIntegrator::kick(b, 0.5*dt);
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
    lastStep_ = stepFor(T);
    const double dtMax = lastStep_.deltaT;
    const double steps = std::ceil(T/dtMax - 1e-9);
    if (!(dtMax > 0) || !(steps <= maxStepsPerAdvance))
    {
        // The step must be representable and its count an int: a stiff or
        // light material (youngsModulus, density) makes it vanish
        std::ostringstream msg;
        msg.precision(3);
        msg << "The DEM time step " << dtMax << " s would take " << steps
            << " steps to cover " << T << " s (at most " << maxStepsPerAdvance
            << " are allowed): the contact time of the bodies is too short."
            << " Check youngsModulus of the materials (";
        for (size_t k = 0; k < materials_.size(); ++k)
        {
            msg << (k ? ", " : "") << materials_[k].name << ": "
                << materials_[k].youngsModulus << " Pa";
        }
        msg << ") and density of the bodies (";
        bool first = true;
        for (size_t i = 0; i < bodies_.size(); ++i)
        {
            if (!bodies_[i].dynamic()) continue;
            msg << (first ? "" : ", ") << bodies_[i].name << ": "
                << bodies_[i].density << " kg/m3";
            first = false;
        }
        msg << "), or deltaT";
        throw coreError(msg.str());
    }
    const int n = std::max(1, int(steps));
    const double dt = T/n;
    // Films are carried within an advance only: each starts measured, as
    // after a restart
    films_.clear();
    // A step of the user's (deltaT) may let a fast body travel far
    for (size_t i = 0; i < bodies_.size(); ++i)
    {
        const rigidBody& b = bodies_[i];
        if (!lastStep_.userStep || isWall_[i] || warnedTravel_.count(i)) continue;
        const double d = 2*b.equivalentRadius();
        if (b.velocity.norm()*dt > maxTravel*d)
        {
            std::cerr
                << "\n--> immersedDEM warning: body '" << b.name << "' moves "
                << b.velocity.norm()*dt/d << " of its size (" << d << " m) in one DEM"
                << " step of " << dt << " s (more than " << maxTravel << "):"
                << " contacts may be missed or too deep. Reduce deltaT\n";
            warnedTravel_.insert(i);
        }
    }
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
    for (const contactRecord& c : contacts_)
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
