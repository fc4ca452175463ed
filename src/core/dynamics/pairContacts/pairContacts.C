#include "pairContacts.H"
#include "pairContactsRegion.H"
#include "pairLoadExchange.H"
#include "sphereShape.H"

#include <algorithm>

namespace immersedDEM
{

bool pairContacts::apply
(
    const context& c, int ia, int ib, const contactGeometry& g
)
{
    const rigidBody& A = c.bodies[ia];
    const rigidBody& B = c.bodies[ib];
    if (g.regions.empty())
    {
        return false;
    }

    const double mA = A.mass(), mB = B.mass();
    const double Reff = demPair::effectiveRadius(A, c.isWall[ia], B);

    contactInput in;
    in.material = c.materials.of(A.material, B.material);
    in.effectiveMass = demPair::effectiveMass(mA, A.dynamic(), mB, B.dynamic());
    in.characteristicLength =
        c.characteristicLength > 0 ? c.characteristicLength : Reff;

    // Overlap depth for laws on spheres: B is a sphere (walls are A)
    in.overlapDepth = 0;
    in.effectiveRadius = Reff;
    if (c.law.needsSpheres())
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
    in.dt = c.dt;

    const bodyState a{A.pose.position(), A.velocity, A.angularVelocity};
    const bodyState b{B.pose.position(), B.velocity, B.angularVelocity};
    applyRegions(c, ia, a, ib, b, g.regions.data(), g.regions.size(), in);
    return true;
}


void pairContacts::applyRegions
(
    const context& c, int ia, const bodyState& A, int ib, const bodyState& B,
    const contactRegion* regions, size_t nRegions, contactInput& in
)
{
    // The pair's histories of the last step (pairs come in increasing
    // order: found by the table's cursor), and its entry in the next
    const auto key = std::make_pair(ia, ib);
    const contactHistoryTable::range oldHistory = history_.find(key);
    next_.beginPair(key);
    taken_.assign(oldHistory.size(), 0);
    for (size_t k = 0; k < nRegions; ++k)
    {
        const int best = nearestHistory(oldHistory, regions[k], taken_.data(), c.cellSize);
        if (best >= 0)
        {
            taken_[best] = 1;
        }
        applyRegion
        (
            c, ia, A, ib, B, regions[k], in, best >= 0 ? oldHistory.first + best : nullptr
        );
    }
}


void pairContacts::applyRegion
(
    const context& c, int ia, const bodyState& A, int ib, const bodyState& B,
    const contactRegion& r, contactInput& in, const contactHistory* old
)
{
    // Twisting friction (contactLaw::twistingCouple) for the laws on
    // overlap regions: a flat face resting on another stops spinning
    // about its normal (a point's friction has no couple about it). The
    // law on spheres keeps its point contact (as LIGGGHTS's)
    const contactLaw& law = c.law;
    applyRegionWith
    (
        c, ia, A, ib, B, r, in, old,
        [&law](const contactInput& i, contactHistory& h) { return law.evaluate(i, h); },
        !law.needsSpheres(), false
    );
}


void pairContacts::gather(demCommunicator& comm)
{
    pairLoadExchange::gather(comm, loads_, records_, next_);
}


void pairContacts::addContactLoad(std::vector<rigidBody>& bodies, const pairLoad& l)
{
    rigidBody& A = bodies[l.a];
    rigidBody& B = bodies[l.b];
    A.contactForce += l.forceA;
    A.contactTorque += l.torqueA;
    B.contactForce += l.forceB;
    B.contactTorque += l.torqueB;
}


void pairContacts::addLoads(std::vector<rigidBody>& bodies) const
{
    for (const pairLoad& l : loads_)
    {
        addContactLoad(bodies, l);
        rigidBody& A = bodies[l.a];
        rigidBody& B = bodies[l.b];
        A.lubricationForce += l.filmForceA;
        A.lubricationTorque += l.filmTorqueA;
        B.lubricationForce += l.filmForceB;
        B.lubricationTorque += l.filmTorqueB;
    }
}


void pairContacts::endPass(size_t nBodies)
{
    next_.finish();
    history_.swap(next_);
    touched_.resize(nBodies, 0);
    for (size_t k = 0; k < history_.size(); ++k)
    {
        const auto p = history_.key(k);
        touched_[p.first] = 1;
        touched_[p.second] = 1;
    }
}


std::vector<std::pair<int, int>> pairContacts::pairsInContact() const
{
    std::vector<std::pair<int, int>> pairs(history_.size());
    for (size_t k = 0; k < pairs.size(); ++k) pairs[k] = history_.key(k);
    return pairs;
}


void pairContacts::renumber(const std::vector<int>& newIndex)
{
    // Pairs keep their order (wall or lower index first): renumbering
    // keeps the order of the indices
    history_.renumber(newIndex);
    std::vector<contactRecord> contacts;
    for (contactRecord c : records_)
    {
        if (newIndex[c.a] >= 0 && newIndex[c.b] >= 0)
        {
            c.a = newIndex[c.a];
            c.b = newIndex[c.b];
            contacts.push_back(c);
        }
    }
    records_.swap(contacts);
}

} // End namespace immersedDEM
