#include "contactReuse.H"
#include "convexOverlap.H"

#include <algorithm>
#include <cmath>
#include <limits>

namespace immersedDEM
{

contactReuse::contactReuse
(
    const demSettings& s, const std::string& engineType, const contactLaw& law
)
:
    enabled_(s.reuseContacts && !law.needsSpheres() && engineType != "sphere"),
    convexEngine_(engineType == "convex"),
    convexShortcut_(engineType == "virtualMesh" && s.overlap.convexExact),
    fraction_(s.reuseFraction),
    fractionMin_(s.reuseFractionMin),
    fractionMax_(s.reuseFractionMax),
    tolerance_(law.type() == "potential" ? s.reuseTolerancePotential : s.reuseTolerance),
    maxSteps_(s.reuseMaxSteps)
{}


bool contactReuse::reusable(const shape& A, const shape& B) const
{
    // The potential law reused: F = w'(V0 - S.u - M.dtheta) S, the gradient
    // of w of the first-order volume, is conservative between two full
    // evaluations (the error is that of the volume, within reuseTolerance)
    if (!enabled_)
    {
        return false;
    }
    // Pairs measured exactly by the convex path (convexOverlap): a few
    // microseconds per sub-step, exact; carried, they would cost about 2
    // to 3 times less but take the first-order error of S, M and the
    // normal (contactScaleBenchmark --reuse-only)
    if (convexEngine_ || (convexShortcut_ && convexOverlap::handles(A, B)))
    {
        return false;
    }
    // Spheres and planes among themselves: analytic and cheap already
    return !demPair::analytic(A, B);
}


bool contactReuse::carry
(
    const entry& rec, const rigidBody& A, bool wallA, const rigidBody& B,
    contactGeometry& g, bool anyMotion, double& moved, vec3* u0
) const
{
    if (!anyMotion && rec.count >= maxSteps_)
    {
        return false;
    }
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
    const double w = wallA ? 1.0 : A.equivalentRadius()/(A.equivalentRadius() + RB);
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


bool contactReuse::carry
(
    const std::pair<int, int>& p, const std::vector<rigidBody>& bodies,
    const std::vector<char>& isWall, contactGeometry& g, demCounters& work
)
{
    const auto it = records_.find(p);
    double moved = 0;
    if
    (
        it == records_.end()
     || !carry(it->second, bodies[p.first], isWall[p.first], bodies[p.second], g, false, moved)
    )
    {
        return false;
    }
    ++it->second.count;
    it->second.lastPass = pass_;
    ++work.reusedEvaluations;
    return true;
}


void contactReuse::record
(
    const std::pair<int, int>& p, const std::vector<rigidBody>& bodies,
    const std::vector<char>& isWall, const contactGeometry& g, bool full
)
{
    const rigidBody& A = bodies[p.first];
    const rigidBody& B = bodies[p.second];
    // The bound: a fraction of the shallowest region's equivalent
    // depth V/area
    double depth = std::numeric_limits<double>::max();
    for (const contactRegion& r : g.regions)
    {
        depth = std::min(depth, r.area > 0 ? r.volume/r.area : 0.0);
    }
    const auto it = records_.find(p);
    const double reuseTol = tolerance_;
    double fraction = fraction_;
    vec3 slope = vec3::Zero();
    // (a full evaluation forced at the end of an advance starts
    // the pair afresh, as a restart from there does)
    if (it != records_.end() && !full)
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
         && carry(it->second, A, isWall[p.first], B, carried, true, moved, &u)
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
            fractionMin_, std::min(fractionMax_, fraction)
        );
    }
    entry& rec = it != records_.end() ? it->second : records_[p];
    rec.poseA = A.pose;
    rec.poseB = B.pose;
    rec.regions = g.regions;
    rec.depth = depth;
    rec.fraction = fraction;
    rec.slope = slope;
    rec.count = 0;
    rec.lastPass = pass_;
}


void contactReuse::endPass()
{
    // Records of pairs not in contact (or not reusable) now are dropped
    for (auto it = records_.begin(); it != records_.end();)
    {
        it = it->second.lastPass == pass_ ? std::next(it) : records_.erase(it);
    }
}

} // End namespace immersedDEM
