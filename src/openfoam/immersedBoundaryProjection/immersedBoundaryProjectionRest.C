// immersedBoundaryProjection: which bodies are projected again (the
// others keep their cells: at rest, or moved less than restDistance), and
// the pose each is projected at

#include "immersedBoundaryProjection.H"
#include "coreConversion.H"
#include "pairFilter.H"

using namespace immersedDEM;


namespace
{

constexpr auto v = &Foam::coreConversion::toFoam;
constexpr auto c = &Foam::coreConversion::toCore;

} // End anonymous namespace


bool Foam::immersedBoundaryProjection::hasProjectedPose(const label bi) const
{
    return size_t(bi) < projectedGeometry_.size() && projectedGeometry_[bi];
}


void Foam::immersedBoundaryProjection::restoreProjectedPose
(
    const demSolver& dem,
    const label bi,
    const bodyPose& pose
)
{
    const size_t n = dem.bodies().size();
    projectedPose_.resize(n);
    projectedGeometry_.resize(n, nullptr);
    projectedName_.resize(n);
    projectedBox_.resize(n);
    const rigidBody& b = dem.bodies()[bi];
    projectedPose_[bi] = pose;
    projectedGeometry_[bi] = b.geometry.get();
    projectedName_[bi] = b.name;
    projectedBox_[bi] = b.geometry->worldBox(pose);
}


immersedDEM::bodyPose Foam::immersedBoundaryProjection::geometryPose
(
    const demSolver& dem,
    const size_t bi
) const
{
    const rigidBody& b = dem.bodies()[bi];
    if
    (
        projectedGeometry_.size() != dem.bodies().size()
     || projectedGeometry_[bi] != b.geometry.get()
     || projectedName_[bi] != b.name
     || !(restDistance_ > 0)
    )
    {
        return b.pose;
    }
    const bodyPose& p = projectedPose_[bi];
    const scalar moved =
        pairFilter::motionBound(p, b.pose, b.geometry->boundingRadius());
    return moved <= restDistance_ ? p : b.pose;
}


Foam::labelList Foam::immersedBoundaryProjection::bodiesToProject
(
    const demSolver& dem,
    const std::vector<bodyPose>& gp,
    bool& all,
    labelList& velocityOnly
) const
{
    const auto& bodies = dem.bodies();
    const size_t n = bodies.size();
    velocityOnly.clear();
    all =
        projectAll_ || debug || mesh_.dynamic() || mesh_.moving()
     || projectedPose_.size() != n || uibPose_.size() != n;
    if (all) return labelList();

    // Moved since their last projection: a geometry pose other than the
    // last one (the surface moved farther than restDistance); moved within
    // it, or changed their velocities: Uib only
    auto same = [](const bodyPose& a, const bodyPose& b)
    {
        return
            a.position() == b.position()
         && a.orientation().coeffs() == b.orientation().coeffs();
    };
    std::vector<bool> in(n, false);
    DynamicList<label> set;
    DynamicList<label> velocities;
    for (size_t bi = 0; bi < n; ++bi)
    {
        if (dem.isWall(int(bi))) continue;
        const rigidBody& b = bodies[bi];
        if (!same(gp[bi], projectedPose_[bi]))
        {
            in[bi] = true;
            set.append(label(bi));
        }
        else if
        (
            !same(b.pose, uibPose_[bi])
         || b.velocity != uibVelocity_[bi]
         || b.angularVelocity != uibAngularVelocity_[bi]
        )
        {
            velocities.append(label(bi));
        }
    }

    // Their cells (lambda > 0, and the sharp surface's ring) lie in their
    // world boxes grown by a cell; a body whose box, grown alike, comes
    // within a cell of theirs (before or after the move) may share cells
    // with them (the larger fraction wins, the first ring claims): it is
    // projected again too (at its geometry pose), and so on. Then the
    // bodies not projected own cells no projected body can reach, and the
    // result is that of projecting every body
    const scalar g = 2*largestCellSize_;
    std::vector<axisAlignedBox> now(n);
    for (size_t bi = 0; bi < n && set.size(); ++bi)
    {
        if (dem.isWall(int(bi))) continue;
        now[bi] = bodies[bi].geometry->worldBox(gp[bi]).inflated(g);
    }
    for (label k = 0; k < set.size(); ++k)
    {
        const label i = set[k];
        const axisAlignedBox before = projectedBox_[i].inflated(g);
        for (size_t j = 0; j < n; ++j)
        {
            if (in[j] || dem.isWall(int(j))) continue;
            if (now[j].overlaps(now[i]) || now[j].overlaps(before))
            {
                in[j] = true;
                set.append(label(j));
            }
        }
    }
    for (const label bi : velocities)
    {
        if (!in[bi]) velocityOnly.append(bi);
    }
    if (set.empty()) return labelList();
    label nBodies = 0;
    for (size_t bi = 0; bi < n; ++bi)
    {
        if (!dem.isWall(int(bi))) ++nBodies;
    }
    if (set.size() == nBodies)
    {
        all = true;
        velocityOnly.clear();
        return labelList();
    }
    Foam::sort(set);
    return labelList(std::move(set));
}


void Foam::immersedBoundaryProjection::setVelocities
(
    const demSolver& dem,
    const std::vector<bool>& velocityOnly
)
{
    // The cells a body owns (lambda, and the sharp surface's ring) take
    // its rigid velocity there now, as a projection would
    vectorField& Uib = Uib_.primitiveFieldRef();
    const vectorField& C = mesh_.cellCentres();
    for (const label celli : touched_)
    {
        const label bi = bodyOf_[celli];
        if (bi >= 0 && velocityOnly[bi])
        {
            Uib[celli] = v(dem.bodies()[bi].pointVelocity(c(C[celli] - bodyShift(celli))));
        }
    }
    for (size_t bi = 0; bi < velocityOnly.size(); ++bi)
    {
        if (!velocityOnly[bi]) continue;
        const rigidBody& b = dem.bodies()[bi];
        uibPose_[bi] = b.pose;
        uibVelocity_[bi] = b.velocity;
        uibAngularVelocity_[bi] = b.angularVelocity;
    }
}
