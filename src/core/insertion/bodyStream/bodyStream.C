#include "bodyStream.H"
#include "coreError.H"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace immersedDEM
{

std::string streamStepReport::summary() const
{
    std::ostringstream os;
    os.precision(6);
    os  << "insertion " << name << ": t " << time << ", inserted " << placed;
    if (placed > 0)
    {
        os  << " (" << name << "_" << firstName;
        if (placed > 1) os << " to " << name << "_" << firstName + placed - 1;
        os  << ")";
    }
    os  << ", " << due - waiting << " of " << due << " due placed in all, "
        << attempts << " positions tried";
    if (waiting > 0)
    {
        os  << "; " << waiting << " WAITING: no free position for "
            << name << "_" << due - waiting << " in the attempts allowed"
            << " (tried again at the next step)";
    }
    if (finishedNow)
    {
        os  << "; volume fraction reached, the insertion ends";
    }
    return os.str();
}


bodyStream::bodyStream(const bodyTemplate& t, const streamSettings& s)
:
    template_(t),
    settings_(s)
{
    template_.check();
    if (!(s.rate > 0) || !std::isfinite(s.rate))
    {
        throw coreError("insertion '" + s.name + "': the rate must be > 0 bodies per second");
    }
    if (!(s.end > s.start))
    {
        throw coreError("insertion '" + s.name + "': the end time must be after the start time");
    }
    if (s.number < 0 || s.volumeFraction < 0 || s.volumeFraction >= 1)
    {
        throw coreError("insertion '" + s.name + "': number >= 0 and a volume fraction in [0, 1) are needed");
    }
    if (!(s.clearance >= 0) || s.maxAttempts < 1)
    {
        throw coreError("insertion '" + s.name + "': clearance >= 0 and maxAttempts >= 1 are needed");
    }
    if (s.region.type() == insertionRegion::kind::surface)
    {
        regionSurface_.reset(new posedBody(*s.region.surfaceShape(), s.region.surfacePose()));
    }
}


std::mt19937_64 bodyStream::generator(long n, long r) const
{
    std::seed_seq seq
    {
        std::uint32_t(settings_.seed), std::uint32_t(settings_.seed >> 32),
        std::uint32_t(n), std::uint32_t(std::uint64_t(n) >> 32), std::uint32_t(r)
    };
    return std::mt19937_64(seq);
}


long bodyStream::due(double t) const
{
    const double last = std::min(t, settings_.end);
    if (last < settings_.start)
    {
        return 0;
    }
    // Body k is due at start + k/rate; a millionth of a body absorbs the
    // round-off of the time (t = 0.3 may be 0.29999999999999999)
    const double k = std::floor(settings_.rate*(last - settings_.start) + 1e-6);
    double n = k + 1;
    if (settings_.number > 0)
    {
        n = std::min(n, double(settings_.number));
    }
    return long(std::min(n, 1e15));
}


rigidBody bodyStream::body(long n) const
{
    std::mt19937_64 rng = generator(n, 0);
    const double f = template_.size.sample(rng);
    rigidBody b(bodyName(n), template_.shapeAt(f), template_.density, template_.material);
    vec3 v = template_.velocity;
    for (int i = 0; i < 3; ++i)
    {
        v[i] += template_.velocitySpread[i]*(2*sizeDistribution::uniform01(rng) - 1);
    }
    b.velocity = v;
    b.angularVelocity = template_.angularVelocity;
    return b;
}


double bodyStream::smallestDiameter() const
{
    const double V = template_.geometry->volume();
    return 2*std::cbrt(3*V/(4*M_PI))*template_.size.minimum();
}


streamStepReport bodyStream::insert(demSolver& dem, double t)
{
    streamStepReport r;
    r.name = settings_.name;
    r.time = t;
    r.firstName = state_.placed;
    const long nDue = state_.finished ? state_.placed : due(t);
    r.due = nDue;
    if (state_.placed >= nDue)
    {
        return r;
    }

    // What is present now, near the region
    const double largest = 2*template_.maxBoundingRadius() + settings_.clearance;
    insertionNeighbourhood present(2*largest);
    present.setPeriodic(dem.periodic());
    const axisAlignedBox near = settings_.region.bounds().inflated(largest);
    for (size_t i = 0; i < dem.bodies().size(); ++i)
    {
        const rigidBody& b = dem.bodies()[i];
        // (in a periodic domain an image of a body far away may be near)
        if (!dem.periodic().active() && !b.geometry->worldBox(b.pose).overlaps(near)) continue;
        present.add
        (
            posedBody(*b.geometry, b.pose, present.surfaceOf(*b.geometry)),
            dem.isWall(int(i))
        );
    }

    const double target = settings_.volumeFraction*settings_.region.volume();
    while (state_.placed < nDue)
    {
        const long n = state_.placed;
        rigidBody b = body(n);
        const double V = b.geometry->volume();
        if (settings_.volumeFraction > 0 && state_.placedVolume + 0.5*V > target)
        {
            state_.finished = true;
            r.finishedNow = true;
            r.due = state_.placed;
            break;
        }
        std::mt19937_64 rng = generator(n, state_.round + 1);
        bodyPose pose;
        long attempts = 0;
        const bool placed = bodyInsertion::place
        (
            template_, b.geometry, settings_.region, regionSurface_.get(), present,
            settings_.clearance, settings_.maxAttempts, rng, pose, attempts
        );
        r.attempts += attempts;
        state_.attempts += attempts;
        if (!placed)
        {
            // It waits, and the bodies after it: tried again next time
            ++state_.round;
            break;
        }
        b.pose = pose;
        r.indices.push_back(dem.addBody(std::move(b)));
        ++r.placed;
        ++state_.placed;
        state_.round = 0;
        state_.placedVolume += V;
    }
    r.waiting = r.due - state_.placed;
    if (r.placed > 0)
    {
        dem.bodiesChanged();
    }
    return r;
}

} // End namespace immersedDEM
