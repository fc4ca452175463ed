#include "sphereSweep.H"
#include "pairContactsRegion.H"
#include "hertzMindlinContactLaw.H"
#include "restitutionCalibration.H"
#include "sphereOverlap.H"
#include "sphereShape.H"
#include "halfSpaceShape.H"

#include <algorithm>
#include <chrono>

namespace immersedDEM
{

bool sphereSweep::applies
(
    const demSettings& s, const std::string& engineType,
    const contactLaw& law, bool films,
    const std::vector<rigidBody>& bodies, const std::vector<char>& isWall
)
{
    if
    (
        !s.sphereSweep
     || engineType != "sphere"
     || !law.needsSpheres()
     || films
    )
    {
        return false;
    }
    for (size_t i = 0; i < bodies.size(); ++i)
    {
        const shape& s = *bodies[i].geometry;
        const bool sphere = shapeAs<sphereShape>(s) != nullptr;
        const bool plane = shapeAs<halfSpaceShape>(s) != nullptr;
        // Bodies are spheres; walls are spheres or planes (the engine's
        // own range; a plane is always the pair's first body, A)
        if (!(sphere || (isWall[i] && plane)))
        {
            return false;
        }
    }
    return true;
}


void sphereSweep::candidates
(
    const std::vector<rigidBody>& bodies, const std::vector<char>& isWall,
    broadPhase& broad, demCounters& work
)
{
    const size_t n = bodies.size();
    sphereBodies_.resize(n);
    sphereBoxes_.resize(n);
    sphereWalls_.clear();
    sphereOthers_.clear();
    double cell = 0;
    for (size_t i = 0; i < n; ++i)
    {
        const rigidBody& b = bodies[i];
        sphereBody& s = sphereBodies_[i];
        s.state = pairContacts::bodyState{b.pose.position(), b.velocity, b.angularVelocity};
        const auto* sp = shapeAs<sphereShape>(*b.geometry);
        s.radius = sp ? sp->radius() : 0;
        s.mass = b.mass();
        s.planeNormal =
            s.radius > 0 ? vec3(vec3::Zero()) : b.pose.vectorToWorld(vec3::UnitZ());
        s.material = b.material;
        s.dynamic = b.dynamic();
        if (isWall[i])
        {
            sphereWalls_.push_back(int(i));
        }
        else
        {
            // (as sphereShape::worldBox)
            const vec3& c = s.state.position;
            sphereBoxes_[i] = axisAlignedBox(c.array() - s.radius, c.array() + s.radius);
            cell = std::max(cell, sphereBoxes_[i].span().maxCoeff());
            sphereOthers_.push_back(int(i));
        }
    }
    broad.refresh(sphereBoxes_, sphereOthers_, cell, periodicBox(), work);

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
    // The walls' candidates: made again with the neighbour list, or when a
    // wall has moved. While the list stands every body's box is inside
    // its grown box; a ball touching a plane has a point behind it, inside
    // that box, so a body whose grown box lies wholly in front of a plane
    // cannot touch it (not every wall against every body at every step:
    // 5,000 tests for a pour of 1,000 spheres on five planes)
    bool wallsMoved = sphereWallNearPose_.size() != 2*sphereWalls_.size();
    for (size_t k = 0; !wallsMoved && k < sphereWalls_.size(); ++k)
    {
        const sphereBody& W = sphereBodies_[sphereWalls_[k]];
        wallsMoved =
            W.state.position != sphereWallNearPose_[2*k]
         || W.planeNormal != sphereWallNearPose_[2*k + 1];
    }
    if (wallsMoved || sphereWallNearBuild_ != broad.builds())
    {
        sphereWallNear_.clear();
        sphereWallNearPose_.clear();
        for (const int w : sphereWalls_)
        {
            const sphereBody& W = sphereBodies_[w];
            const vec3& n = W.planeNormal;
            const vec3& p0 = W.state.position;
            sphereWallNearPose_.push_back(p0);
            sphereWallNearPose_.push_back(n);
            for (const int i : sphereOthers_)
            {
                // (the lowest point of the grown box along n, with a
                // margin for the round-off of the step's own test)
                const axisAlignedBox& g = broad.grownBoxes()[i];
                const bool behind =
                    n.dot(g.centre() - p0) - n.cwiseAbs().dot(0.5*g.span())
                  < 1e-9*g.span().maxCoeff();
                if (W.radius > 0 || behind)
                {
                    sphereWallNear_.emplace_back(w, i);
                }
            }
        }
        sphereWallNearBuild_ = broad.builds();
    }
    // (each pair written, kept by advancing the count: whether a listed
    // pair touches is a coin toss the branch predictor lost, the largest
    // cost of this function)
    sphereWallPairs_.resize(sphereWallNear_.size());
    size_t nWall = 0;
    for (const auto& p : sphereWallNear_)
    {
        const int w = p.first, i = p.second;
        const sphereBody& W = sphereBodies_[w];
        const sphereBody& B = sphereBodies_[i];
        const bool apart =
            W.radius == 0
          ? W.planeNormal.dot(B.state.position - W.state.position) >= B.radius
          : spheresApart(w, i);
        sphereWallPairs_[nWall] = p;
        nWall += B.dynamic & !apart;
    }
    sphereWallPairs_.resize(nWall);
    // The neighbours that can touch while the list stands. It stands while
    // every ball's box is inside its grown box, so while each centre is
    // inside its grown box shrunk by the radius, G; two balls whose boxes
    // G are R_a + R_b or farther apart cannot touch meanwhile. The grown
    // boxes hold about twice the pairs of this criterion (their tests were
    // the largest cost of this function)
    if (sphereNeighboursBuild_ != broad.builds())
    {
        sphereNeighbours_.clear();
        for (const auto& p : broad.neighbours())
        {
            const double RA = sphereBodies_[p.first].radius;
            const double RB = sphereBodies_[p.second].radius;
            const axisAlignedBox& gA = broad.grownBoxes()[p.first];
            const axisAlignedBox& gB = broad.grownBoxes()[p.second];
            const vec3 gap =
                ((gB.min.array() + RB) - (gA.max.array() - RA))
               .max((gA.min.array() + RA) - (gB.max.array() - RB))
               .max(0.0);
            // (with a margin for round-off)
            const double reach = (RA + RB)*(1 + 1e-9);
            if (gap.squaredNorm() < reach*reach)
            {
                sphereNeighbours_.push_back(p);
            }
        }
        sphereNeighboursBuild_ = broad.builds();
    }
    sphereBodyPairs_.resize(sphereNeighbours_.size());
    size_t nBody = 0;
    for (const auto& p : sphereNeighbours_)
    {
        const bool moves = sphereBodies_[p.first].dynamic | sphereBodies_[p.second].dynamic;
        sphereBodyPairs_[nBody] = p;
        nBody += moves & !spheresApart(p.first, p.second);
    }
    sphereBodyPairs_.resize(nBody);
    spherePairs_.resize(sphereWallPairs_.size() + sphereBodyPairs_.size());
    std::merge
    (
        sphereWallPairs_.begin(), sphereWallPairs_.end(),
        sphereBodyPairs_.begin(), sphereBodyPairs_.end(), spherePairs_.begin()
    );
}


void sphereSweep::sweep
(
    const pairContacts::context& c, pairContacts& contacts,
    broadPhase& broad, const demCommunicator* comm,
    const std::vector<std::uint64_t>& identity, demCounters& work
)
{
    ++work.sphereSweeps;
    const auto searchStart = std::chrono::steady_clock::now();
    candidates(c.bodies, c.isWall, broad, work);
    work.searchSeconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - searchStart).count();

    // (the law on spheres reads neither the volume law's length nor the
    // potential law's flat face)
    contactInput in;
    in.flatFaceArea = 0;
    in.dt = c.dt;
    // (the region measured in place, in the law's input)
    contactRegion& r = in.region;
    pairLoad& load = contacts.load();
    load = pairLoad();
    // Hertz-Mindlin (the law on spheres) compiled into the loop, its
    // damping coefficient looked up once per pair of materials (not per
    // contact); any other law on spheres through
    // its interface
    const bool hertz = dynamic_cast<const hertzMindlinContactLaw*>(&c.law) != nullptr;
    // Alone, Hertz-Mindlin's loads go straight onto the bodies (not summed
    // per pair first: a pair has one region, so the sums are the same)
    const bool direct = hertz && !comm;
    const size_t nMaterials = c.materials.size();
    sphereDamping_.assign(nMaterials*nMaterials, -1);
    for (const auto& p : spherePairs_)
    {
        if (!demCommunicator::owns(comm, identity[p.first], identity[p.second]))
        {
            continue;
        }
        const sphereBody& A = sphereBodies_[p.first];
        const sphereBody& B = sphereBodies_[p.second];
        const bool plane = A.radius == 0;
        double distance = 0;
        const bool touching =
            plane
          ? sphereOverlap::capRegion
            (
                A.state.position, A.planeNormal, B.state.position, B.radius, r
            )
          : sphereOverlap::lensRegion
            (
                A.state.position, A.radius, B.state.position, B.radius, r, &distance
            );
        if (!touching)
        {
            continue;
        }
        ++work.pairEvaluations;

        // As applyContacts: the depth from A's signed distance of B's
        // centre (two spheres: pairContacts::sphereDepth, with the lens's distance of
        // the centres), the Hertz radius of the two spheres (B's on a
        // plane)
        in.material = c.materials.of(A.material, B.material);
        in.effectiveMass = demPair::effectiveMass(A.mass, A.dynamic, B.mass, B.dynamic);
        in.overlapDepth =
            plane
          ? B.radius
          - c.bodies[p.first].geometry->signedDistance(c.bodies[p.first].pose, B.state.position)
          : A.radius + B.radius - distance;
        in.effectiveRadius =
            plane ? B.radius : A.radius*B.radius/(A.radius + B.radius);
        in.pairVolume = r.volume;

        // (the film's loads stay zero: set once above)
        if (!direct)
        {
            load.forceA = load.torqueA = load.forceB = load.torqueB = vec3::Zero();
            load.a = p.first;
            load.b = p.second;
            load.contactsFrom = contacts.records().size();
        }
        // (applyRegions of one region: no other region takes a history)
        const auto key = std::make_pair(p.first, p.second);
        const contactHistoryTable::range old = contacts.history().find(key);
        contacts.next().beginPair(key);
        const int best = pairContacts::nearestHistory(old, r, nullptr, c.cellSize);
        const contactHistory* oldBest = best >= 0 ? old.first + best : nullptr;
        if (hertz)
        {
            double& d = sphereDamping_[size_t(A.material)*nMaterials + size_t(B.material)];
            if (d < 0)
            {
                d = restitutionCalibration::damping(in.material.restitution, 1.5);
            }
            const double damping = d;
            contacts.applyRegionWith
            (
                c, p.first, A.state, p.second, B.state, r, in, oldBest,
                [damping](const contactInput& i, contactHistory& h)
                {
                    return hertzMindlinContactLaw::force(i, h, damping);
                },
                false, direct
            );
        }
        else
        {
            contacts.applyRegion(c, p.first, A.state, p.second, B.state, r, in, oldBest);
        }
        // Alone, the pairs' loads are added to the bodies now, in the
        // order of the pairs as pairContacts::addLoads adds them (the film's
        // are zero); shared, after the processes' loads are gathered
        if (direct)
        {
            continue;
        }
        load.contactsTo = contacts.records().size();
        if (comm)
        {
            contacts.keepLoad();
        }
        else
        {
            pairContacts::addContactLoad(c.bodies, load);
        }
    }
}

} // End namespace immersedDEM
