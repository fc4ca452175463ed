/*---------------------------------------------------------------------------*\
Description
    demSolver's sphere sweep: the contacts of spheres among themselves and
    with plane walls under a law on spheres (hertzMindlin), without the
    lubrication film. The general loop (computeContacts) asks the pair
    filter, calls the overlap engine through its interface (a vector of
    regions per pair), and reads each body's mass, radius and state through
    the shape's virtual functions and the whole 640-byte body; for a pour of
    1,000 spheres that was about 80% of the run. Here every body's position,
    velocities, radius, mass and plane normal are copied once per sweep into
    one compact array, and each pair's lens or cap is computed in place.
    The law, the histories, the loads and the records are those of the
    general loop (applyRegions), so the results are the same bit for bit
    (test demProcesses.sphereSweepIsTheGeneralLoopBitForBit).
\*---------------------------------------------------------------------------*/

#include "demSolver.H"
#include "sphereOverlap.H"
#include "sphereShape.H"
#include "halfSpaceShape.H"

#include <algorithm>
#include <chrono>

namespace immersedDEM
{

bool demSolver::sphereSweepApplies() const
{
    if
    (
        !settings_.sphereSweep
     || engine_->type() != "sphere"
     || !law_->needsSpheres()
     || lubricating()
    )
    {
        return false;
    }
    for (size_t i = 0; i < bodies_.size(); ++i)
    {
        const shape& s = *bodies_[i].geometry;
        const bool sphere = shapeAs<sphereShape>(s) != nullptr;
        const bool plane = shapeAs<halfSpaceShape>(s) != nullptr;
        // Bodies are spheres; walls are spheres or planes (the engine's
        // own range; a plane is always the pair's first body, A)
        if (!(sphere || (isWall_[i] && plane)))
        {
            return false;
        }
    }
    return true;
}


void demSolver::sphereCandidates()
{
    const size_t n = bodies_.size();
    sphereBodies_.resize(n);
    boxes_.resize(n);
    sphereWalls_.clear();
    sphereOthers_.clear();
    double cell = 0;
    for (size_t i = 0; i < n; ++i)
    {
        const rigidBody& b = bodies_[i];
        sphereBody& s = sphereBodies_[i];
        s.state = bodyState{b.pose.position(), b.velocity, b.angularVelocity};
        const auto* sp = shapeAs<sphereShape>(*b.geometry);
        s.radius = sp ? sp->radius() : 0;
        s.mass = b.mass();
        s.planeNormal =
            s.radius > 0 ? vec3(vec3::Zero()) : b.pose.vectorToWorld(vec3::UnitZ());
        s.material = b.material;
        s.dynamic = b.dynamic();
        if (isWall_[i])
        {
            sphereWalls_.push_back(int(i));
        }
        else
        {
            // (as sphereShape::worldBox)
            const vec3& c = s.state.position;
            boxes_[i] = axisAlignedBox(c.array() - s.radius, c.array() + s.radius);
            cell = std::max(cell, boxes_[i].span().maxCoeff());
            sphereOthers_.push_back(int(i));
        }
    }
    refreshNeighbours(boxes_, sphereOthers_, cell);

    // The pairs that touch (the regions' own first test, sphereOverlap),
    // in the order of candidatePairs: walls against the dynamic bodies,
    // then the neighbours, merged. A pair that does not touch adds
    // nothing, so this is the general loop's result from fewer pairs
    auto spheresApart = [this](int a, int b)
    {
        const sphereBody& A = sphereBodies_[a];
        const sphereBody& B = sphereBodies_[b];
        const double R = A.radius + B.radius;
        return (B.state.position - A.state.position).squaredNorm() >= R*R;
    };
    sphereWallPairs_.clear();
    for (const int w : sphereWalls_)
    {
        const sphereBody& W = sphereBodies_[w];
        const vec3 n = W.planeNormal;
        const vec3 p0 = W.state.position;
        for (const int i : sphereOthers_)
        {
            const sphereBody& B = sphereBodies_[i];
            const bool apart =
                W.radius == 0
              ? n.dot(B.state.position - p0) >= B.radius
              : spheresApart(w, i);
            if (B.dynamic && !apart)
            {
                sphereWallPairs_.emplace_back(w, i);
            }
        }
    }
    sphereBodyPairs_.clear();
    for (const auto& p : neighbours_)
    {
        if
        (
            (sphereBodies_[p.first].dynamic || sphereBodies_[p.second].dynamic)
         && !spheresApart(p.first, p.second)
        )
        {
            sphereBodyPairs_.push_back(p);
        }
    }
    spherePairs_.resize(sphereWallPairs_.size() + sphereBodyPairs_.size());
    std::merge
    (
        sphereWallPairs_.begin(), sphereWallPairs_.end(),
        sphereBodyPairs_.begin(), sphereBodyPairs_.end(), spherePairs_.begin()
    );
}


void demSolver::sphereSweep(contactHistoryTable& next)
{
    ++counters_.sphereSweeps;
    const auto searchStart = std::chrono::steady_clock::now();
    sphereCandidates();
    counters_.searchSeconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - searchStart).count();

    // (the law on spheres reads neither the volume law's length nor the
    // potential law's flat face)
    contactInput in;
    in.flatFaceArea = 0;
    in.dt = lastDt_;
    contactRegion r;
    load_ = pairLoad();
    for (const auto& p : spherePairs_)
    {
        if (!owns(p.first, p.second))
        {
            continue;
        }
        const sphereBody& A = sphereBodies_[p.first];
        const sphereBody& B = sphereBodies_[p.second];
        const bool plane = A.radius == 0;
        const bool touching =
            plane
          ? sphereOverlap::capRegion
            (
                A.state.position, A.planeNormal, B.state.position, B.radius, r
            )
          : sphereOverlap::lensRegion
            (
                A.state.position, A.radius, B.state.position, B.radius, r
            );
        if (!touching)
        {
            continue;
        }
        ++counters_.pairEvaluations;

        // As applyContacts: the depth from A's signed distance of B's
        // centre, the Hertz radius of the two spheres (B's on a plane)
        in.material = pairMaterialOf(A.material, B.material);
        in.effectiveMass = effectiveMass(A.mass, A.dynamic, B.mass, B.dynamic);
        in.overlapDepth =
            plane
          ? B.radius
          - bodies_[p.first].geometry->signedDistance(bodies_[p.first].pose, B.state.position)
          : sphereDepth(A.state.position, A.radius, B.state.position, B.radius);
        in.effectiveRadius =
            plane ? B.radius : A.radius*B.radius/(A.radius + B.radius);
        in.pairVolume = r.volume;

        // (the film's loads stay zero: set once above)
        load_.forceA = load_.torqueA = load_.forceB = load_.torqueB = vec3::Zero();
        load_.a = p.first;
        load_.b = p.second;
        load_.contactsFrom = contacts_.size();
        // (applyRegions of one region: no other region takes a history)
        const auto key = std::make_pair(p.first, p.second);
        const contactHistoryTable::range old = history_.find(key);
        next.beginPair(key);
        const int best = nearestHistory(old, r, nullptr);
        applyRegion
        (
            p.first, A.state, p.second, B.state, r, in,
            best >= 0 ? old.first + best : nullptr, next
        );
        load_.contactsTo = contacts_.size();
        // Alone, the pairs' loads are added to the bodies now, in the
        // order of the pairs as computeContacts adds loads_ (the film's
        // are zero); shared, after the processes' loads are gathered
        if (comm_)
        {
            loads_.push_back(load_);
        }
        else
        {
            addContactLoad(load_);
        }
    }
}

} // End namespace immersedDEM
