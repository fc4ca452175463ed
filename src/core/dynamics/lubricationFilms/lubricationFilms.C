#include "lubricationFilms.H"
#include "wallMeshShape.H"

#include <algorithm>
#include <cmath>
#include <limits>

namespace immersedDEM
{

lubricationFilms::lubricationFilms(const demSettings& s)
:
    settings_(s.lubrication),
    carryFilms_(s.reuseContacts),
    maxSteps_(s.reuseMaxSteps)
{}


double lubricationFilms::reach
(
    const std::vector<rigidBody>& bodies, const std::vector<char>& isWall
) const
{
    if (!active())
    {
        return 0;
    }
    double h = 0;
    for (size_t i = 0; i < bodies.size(); ++i)
    {
        if (!isWall[i]) h = std::max(h, bodies[i].fluidCellSize);
    }
    return std::max(settings_.activation, settings_.pairActivation)*h;
}


void lubricationFilms::beginPass
(
    const std::vector<std::pair<int, int>>& candidates, size_t nBodies
)
{
    filter_.beginSweep();
    // Each body's pairs that may carry a film this step (an upper bound
    // on its films: every process counts all pairs alike)
    neighbours_.assign(nBodies, 0);
    for (const auto& p : candidates)
    {
        ++neighbours_[p.first];
        ++neighbours_[p.second];
    }
}


bool lubricationFilms::movedLess
(
    const bodyPose& a0, const rigidBody& A,
    const bodyPose& b0, const rigidBody& B, double bound
)
{
    return
        pairFilter::motionBound(a0, A.pose, A.geometry->boundingRadius())
      + pairFilter::motionBound(b0, B.pose, B.geometry->boundingRadius())
      < bound;
}


double lubricationFilms::inverseMassAlong
(
    const rigidBody& b, const vec3& x, const vec3& n, double addedMass
)
{
    if (!b.dynamic())
    {
        return 0;
    }
    const vec3 rn = (x - b.pose.position()).cross(n);
    return 1/(b.mass() + addedMass) + b.inverseInertiaAlong(rn);
}


double lubricationFilms::filmFactorAt(const rigidBody& b, const vec3& x)
{
    if (!b.faceFilm)
    {
        return b.filmFactor;
    }
    // (only a wall mesh has faces; a mixed wall's films cost one query)
    const auto* w = dynamic_cast<const wallMeshShape*>(b.geometry.get());
    if (!w)
    {
        return b.filmFactor;
    }
    const int face = w->distanceField().tree().closest(b.pose.toBody(x)).face;
    return face >= 0 && size_t(face) < b.faceFilm->size()
        ? (*b.faceFilm)[size_t(face)] : b.filmFactor;
}


void lubricationFilms::lubricate
(
    int ia, int ib, const std::vector<rigidBody>& bodies,
    const std::vector<char>& isWall,
    const std::vector<contactRecord>& contacts, size_t contactsFrom,
    double dt, pairLoad& load, demCounters& work
)
{
    const rigidBody& A = bodies[ia];
    const rigidBody& B = bodies[ib];
    // The activation distance (a wall's, or a pair of bodies'): in the
    // finer fluid cells of the two
    double cell = 0;
    for (const rigidBody* b : {&A, &B})
    {
        if (b->fluidCellSize > 0 && !isWall[b == &A ? ia : ib])
        {
            cell = cell > 0 ? std::min(cell, b->fluidCellSize) : b->fluidCellSize;
        }
    }
    const lubricationSettings& ls = settings_;
    const double hAct =
        (isWall[ia] || isWall[ib] ? ls.activation : ls.pairActivation)*cell;
    if (!(hAct > 0))
    {
        return;
    }
    // A film measured earlier in this advance, carried while the bodies
    // have moved, relative to each other, by less than a small fraction
    // of its gap: the gap and the normal follow the material points that
    // were closest (first order in the motion)
    const std::uint64_t key = pairFilter::key(ia, ib);
    const auto carried = films_.find(key);
    if
    (
        carried != films_.end()
     && carried->second.count < maxSteps_
     && movedLess
        (
            carried->second.poseA, A, carried->second.poseB, B,
            filmCarryFraction*carried->second.gap
        )
    )
    {
        filmRecord& f = carried->second;
        ++f.count;
        // The filter's record lives on as near: when the film is measured
        // again, no new proof (a body near a wall mesh: milliseconds)
        filter_.stillTouching(ia, ib);
        const vec3 pa = A.pose.toWorld(f.pointA);
        const vec3 pb = B.pose.toWorld(f.pointB);
        const vec3 n = A.pose.vectorToWorld(f.normal);
        const double gap = (pb - pa).dot(n);
        ++work.reusedFilms;
        if (gap < hAct)
        {
            const mat3& RA = A.pose.rotation();
            applyFilm
            (
                bodies, A, B, 0.5*(pa + pb), n, gap, f.radius, hAct,
                ls.roughness*demPair::effectiveRadius(A, isWall[ia], B), dt, load, work,
                f.footprintArea,
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
    for (size_t k = contactsFrom; k < contacts.size(); ++k)
    {
        if (!best || contacts[k].region.volume > best->region.volume)
        {
            best = &contacts[k];
        }
    }
    if (best)
    {
        const double Rcap = demPair::effectiveRadius(A, isWall[ia], B);
        const vec3& x = best->region.point;
        const vec3& n = best->region.normal;
        // The surfaces' curvatures near the contact point: carried while
        // the bodies have moved, and the point has moved on A, less than
        // a small fraction of the activation distance (a pair of several
        // regions may change its largest), measured otherwise
        const mat3& RA = A.pose.rotation();
        const mat3& RB = B.pose.rotation();
        const double carryBound = filmCarryFraction*hAct;
        const vec3 xA = A.pose.toBody(x);
        mat3 KA, KB;
        const auto cf = contactFilms_.find(key);
        if
        (
            cf != contactFilms_.end()
         && cf->second.count < maxSteps_
         && (xA - cf->second.point).norm() < carryBound
         && movedLess(cf->second.poseA, A, cf->second.poseB, B, carryBound)
        )
        {
            ++cf->second.count;
            ++work.reusedFilms;
            KA = RA*cf->second.curvatureA*RA.transpose();
            KB = RB*cf->second.curvatureB*RB.transpose();
        }
        else
        {
            KA = lubrication::curvatureNear(*A.geometry, A.pose, x);
            KB = lubrication::curvatureNear(*B.geometry, B.pose, x);
            if (carryFilms_ && !demPair::analytic(*A.geometry, *B.geometry))
            {
                contactFilmRecord& f = contactFilms_[key];
                f.poseA = A.pose;
                f.poseB = B.pose;
                f.curvatureA = RA.transpose()*KA*RA;
                f.curvatureB = RB.transpose()*KB*RB;
                f.point = xA;
                f.count = 0;
            }
        }
        const double R = lubrication::gapRadius(KA, KB, n, Rcap);
        applyFilm(bodies, A, B, x, n, 0, R, hAct, ls.roughness*Rcap, dt, load, work);
        return;
    }
    filter_.setReach(hAct);
    if (filter_.separated(ia, ib, *A.geometry, A.pose, *B.geometry, B.pose))
    {
        return;
    }
    const closestApproach c =
        lubrication::approach(*A.geometry, A.pose, *B.geometry, B.pose, hAct);
    filter_.engineResult(ia, ib, c.found);
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
    const double Rcap = demPair::effectiveRadius(A, isWall[ia], B);
    const double R = lubrication::gapRadius
    (
        lubrication::curvatureNear(*A.geometry, A.pose, x),
        lubrication::curvatureNear(*B.geometry, B.pose, x),
        n, Rcap
    );
    // (spheres and planes are measured exactly and cheaply every time)
    if (carryFilms_ && !demPair::analytic(*A.geometry, *B.geometry))
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
        bodies, A, B, x, n, c.gap, R, hAct, ls.roughness*Rcap, dt, load, work,
        c.footprintArea,
        c.footprintSpread, c.footprintHeight, c.footprintCentre
    );
}


double lubricationFilms::filmShare
(
    const std::vector<rigidBody>& bodies, const rigidBody& A, const rigidBody& B
) const
{
    int n = 1;
    for (const rigidBody* b : {&A, &B})
    {
        const size_t i = size_t(b - bodies.data());
        if (b->dynamic() && i < neighbours_.size())
        {
            n = std::max(n, neighbours_[i]);
        }
    }
    return 1.0/n;
}


void lubricationFilms::applyFilm
(
    const std::vector<rigidBody>& bodies,
    const rigidBody& A, const rigidBody& B, const vec3& x, const vec3& n,
    double gap, double R, double hAct, double hRough, double dt,
    pairLoad& load, demCounters& work,
    double footprintArea, const mat3& footprintSpread,
    double footprintHeight, const vec3& footprintCentre
) const
{
    // A wall the fluid slips along takes a quarter of the film, one it
    // passes through none
    const double factor = filmFactorAt(A, x)*filmFactorAt(B, x);
    if (!(factor > 0))
    {
        return;
    }
    double coeff = factor*lubrication::coefficient
    (
        settings_.viscosity, R, gap, hAct, hRough
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
            settings_.viscosity, footprintArea, axes.s[0],
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
        flat.normal *= factor*w.normal;
        flat.tilt1 *= factor;
        flat.tilt2 *= factor;
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
    const double share = filmShare(bodies, A, B);
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
    load.filmForceB += F;
    load.filmTorqueB += (at - B.pose.position()).cross(F);
    load.filmForceA -= F;
    load.filmTorqueA -= (at - A.pose.position()).cross(F);
    // The tilting film's torque on B (its opposite on A)
    const vec3 w = B.angularVelocity - A.angularVelocity;
    vec3 T = vec3::Zero();
    for (int k = 0; k < 2; ++k)
    {
        T -= tilt[k]*w.dot(axes.e[k])*axes.e[k];
    }
    load.filmTorqueB += T;
    load.filmTorqueA -= T;
    load.film = true;
    ++work.lubricatedPairs;
}

} // End namespace immersedDEM
