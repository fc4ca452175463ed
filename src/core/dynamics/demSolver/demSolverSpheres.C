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


void demSolver::sphereSweep
(
    const std::vector<std::pair<int, int>>& candidates, contactHistoryTable& next
)
{
    ++counters_.sphereSweeps;
    const size_t n = bodies_.size();
    sphereBodies_.resize(n);
    for (size_t i = 0; i < n; ++i)
    {
        const rigidBody& b = bodies_[i];
        sphereBody& s = sphereBodies_[i];
        s.state = bodyState{b.pose.position(), b.velocity, b.angularVelocity};
        if (const auto* sp = shapeAs<sphereShape>(*b.geometry))
        {
            s.radius = sp->radius();
            s.planeNormal = vec3::Zero();
        }
        else
        {
            s.radius = 0;
            s.planeNormal = b.pose.vectorToWorld(vec3::UnitZ());
        }
        s.mass = b.mass();
        s.material = b.material;
        s.dynamic = b.dynamic();
    }

    // (the law on spheres reads neither the volume law's length nor the
    // potential law's flat face)
    contactInput in;
    in.flatFaceArea = 0;
    in.dt = lastDt_;
    contactRegion r;
    load_ = pairLoad();
    for (const auto& p : candidates)
    {
        if (!owns(p.first, p.second))
        {
            continue;
        }
        const sphereBody& A = sphereBodies_[p.first];
        const sphereBody& B = sphereBodies_[p.second];
        if (!(A.dynamic || B.dynamic))
        {
            continue;
        }
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
        applyRegions(p.first, A.state, p.second, B.state, &r, 1, in, next);
        load_.contactsTo = contacts_.size();
        // Alone, the pairs' loads are added to the bodies now, in the
        // order of the pairs as computeContacts adds loads_; shared, after
        // the processes' loads are gathered
        if (comm_)
        {
            loads_.push_back(load_);
        }
        else
        {
            addPairLoad(load_);
        }
    }
}

} // End namespace immersedDEM
