#include "bodyInsertion.H"
#include "bodySeparation.H"
#include "sphereShape.H"
#include "triangleMeshShape.H"
#include "coreError.H"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace immersedDEM
{

std::shared_ptr<const shape> bodyTemplate::shapeAt(double f) const
{
    if (f == 1)
    {
        return geometry;
    }
    const auto it = shapes_.find(f);
    if (it != shapes_.end())
    {
        return it->second;
    }
    std::shared_ptr<const shape> s;
    if (const auto* sp = dynamic_cast<const sphereShape*>(geometry.get()))
    {
        s = std::make_shared<sphereShape>(f*sp->radius());
    }
    else if (const auto* m = dynamic_cast<const triangleMeshShape*>(geometry.get()))
    {
        // The checked surface at factor 1, in its body frame, scaled: its
        // body frame is that of the template's shape (up to round-off),
        // its convex pieces too
        s = m->scaled(f, name);
    }
    else
    {
        triangleSoup soup = geometry->surface();
        for (vec3& p : soup.points) p *= f;
        s = std::make_shared<triangleMeshShape>(std::move(soup), name, false);
    }
    shapes_.emplace(f, s);
    return s;
}


void bodyTemplate::check() const
{
    if (!geometry)
    {
        throw coreError("template '" + name + "' has no shape");
    }
    const std::string t = geometry->type();
    if (t != "sphere" && t != "triangleMesh")
    {
        throw coreError("template '" + name + "': a body is a sphere or a triangle mesh");
    }
    if (!(density > 0) || !std::isfinite(density))
    {
        throw coreError("template '" + name + "': density must be > 0");
    }
}


quat bodyInsertion::randomRotation(std::mt19937_64& rng)
{
    const double u1 = sizeDistribution::uniform01(rng);
    const double u2 = 2*M_PI*sizeDistribution::uniform01(rng);
    const double u3 = 2*M_PI*sizeDistribution::uniform01(rng);
    const double a = std::sqrt(1 - u1), b = std::sqrt(u1);
    return quat(b*std::cos(u3), a*std::sin(u2), a*std::cos(u2), b*std::sin(u3)).normalized();
}


std::string insertionReport::summary() const
{
    std::ostringstream os;
    os.precision(4);
    os  << "insertion " << name << ": placed " << placed;
    if (requested > 0)
    {
        os  << " of " << requested << " bodies";
    }
    else
    {
        os  << " bodies (volume fraction target " << targetFraction << ")";
    }
    os  << ", volume fraction " << volumeFraction() << " of the region ("
        << regionVolume << " m3), " << attempts << " positions tried";
    if (!complete)
    {
        os  << "; COULD NOT PLACE the rest: no free position found in the"
            << " attempts allowed (region too full)";
    }
    return os.str();
}


insertionNeighbourhood::key insertionNeighbourhood::index(const vec3& p) const
{
    return key{long(std::floor(p.x()/cell_)), long(std::floor(p.y()/cell_)), long(std::floor(p.z()/cell_))};
}


const triangleSoup& insertionNeighbourhood::surfaceOf(const shape& s)
{
    auto it = surfaces_.find(&s);
    if (it == surfaces_.end())
    {
        const std::string t = s.type();
        it = surfaces_.emplace
        (
            &s, (t == "triangleMesh" || t == "wallMesh") ? s.surface() : triangleSoup()
        ).first;
    }
    return it->second;
}


void insertionNeighbourhood::add(posedBody b, const bool wall)
{
    const bool finite =
        b.type == posedBody::kind::sphere || b.type == posedBody::kind::mesh;
    if (periodic_.active() && finite && !wall)
    {
        for (const vec3& s : periodic_.imageShifts(b.box.inflated(cell_)))
        {
            if (!s.isZero()) addOne(b.translated(s));
        }
    }
    addOne(std::move(b));
}


void insertionNeighbourhood::addOne(posedBody b)
{
    const int i = int(bodies_.size());
    const bool finite =
        b.type == posedBody::kind::sphere || b.type == posedBody::kind::mesh;
    if (finite && b.box.span().maxCoeff() <= cell_)
    {
        // A box no larger than a cell: registered in the cell of its
        // centre, found from the 27 cells around a candidate's
        grid_[index(b.box.centre())].push_back(i);
    }
    else
    {
        large_.push_back(i);
    }
    bodies_.push_back(std::move(b));
}


bool insertionNeighbourhood::free(const posedBody& c, double clearance) const
{
    for (const int i : large_)
    {
        if (!bodySeparation::apart(c, bodies_[i], clearance)) return false;
    }
    // A candidate no larger than a cell (checked by the caller)
    const key k = index(c.box.centre());
    for (long x = k[0] - 1; x <= k[0] + 1; ++x)
        for (long y = k[1] - 1; y <= k[1] + 1; ++y)
            for (long z = k[2] - 1; z <= k[2] + 1; ++z)
            {
                const auto it = grid_.find(key{x, y, z});
                if (it == grid_.end()) continue;
                for (const int i : it->second)
                {
                    if (!bodySeparation::apart(c, bodies_[i], clearance)) return false;
                }
            }
    return true;
}


bool bodyInsertion::place
(
    const bodyTemplate& t,
    const std::shared_ptr<const shape>& g,
    const insertionRegion& region,
    const posedBody* regionSurface,
    insertionNeighbourhood& present,
    const double clearance,
    const int maxAttempts,
    std::mt19937_64& rng,
    bodyPose& pose,
    long& attempts
)
{
    const triangleSoup& surface = present.surfaceOf(*g);
    const bool isSphere = g->type() == "sphere";
    for (int k = 0; k < maxAttempts; ++k)
    {
        ++attempts;
        const quat q = t.randomOrientation
            ? randomRotation(rng)
            : quat(t.orientation*g->bodyInFile().orientation());
        const vec3 x = region.sample(rng);
        pose = bodyPose(x, q);
        if (isSphere)
        {
            if (!region.containsSphere(x, g->boundingRadius())) continue;
        }
        else if (!region.contains(x, 0))
        {
            continue;
        }
        const posedBody c(*g, pose, surface);
        if (regionSurface)
        {
            if (!bodySeparation::inside(c, *regionSurface)) continue;
        }
        else if (!isSphere && !region.containsAll(c.vertices))
        {
            continue;
        }
        if (present.free(c, clearance))
        {
            present.add(c);
            return true;
        }
    }
    return false;
}


insertionReport bodyInsertion::insert
(
    demSolver& dem,
    const bodyTemplate& t,
    const insertionSettings& s
)
{
    t.check();
    if ((s.number > 0) == (s.volumeFraction > 0))
    {
        throw coreError("insertion '" + s.name + "': give either a number of bodies or a volume fraction");
    }
    if (s.volumeFraction >= 1 || s.number < 0)
    {
        throw coreError("insertion '" + s.name + "': the volume fraction must be in (0, 1)");
    }
    if (!(s.clearance >= 0) || s.maxAttempts < 1)
    {
        throw coreError("insertion '" + s.name + "': clearance >= 0 and maxAttempts >= 1 are needed");
    }
    for (const rigidBody& b : dem.bodies())
    {
        if (b.name.rfind(s.name + "_", 0) == 0)
        {
            throw coreError
            (
                "insertion '" + s.name + "': the name of body '" + b.name
              + "' is taken by the names of the inserted bodies (" + s.name + "_<n>)"
            );
        }
    }

    insertionReport r;
    r.name = s.name;
    r.requested = s.number;
    r.targetFraction = s.volumeFraction;
    r.regionVolume = s.region.volume();

    // Cells twice the largest candidate's box: a candidate's neighbours are
    // in the 27 cells around its centre's
    const double largest = 2*t.maxBoundingRadius() + s.clearance;
    insertionNeighbourhood present(2*largest);
    present.setPeriodic(dem.periodic());
    for (size_t i = 0; i < dem.bodies().size(); ++i)
    {
        const rigidBody& b = dem.bodies()[i];
        present.add
        (
            posedBody(*b.geometry, b.pose, present.surfaceOf(*b.geometry)),
            dem.isWall(int(i))
        );
    }

    // A surface region, posed once
    std::unique_ptr<posedBody> regionSurface;
    if (s.region.type() == insertionRegion::kind::surface)
    {
        regionSurface.reset(new posedBody(*s.region.surfaceShape(), s.region.surfacePose()));
    }

    std::mt19937_64 rng(s.seed);
    const double target = s.volumeFraction*r.regionVolume;
    for (int n = 0; s.number == 0 || n < s.number; ++n)
    {
        const double f = t.size.sample(rng);
        const std::shared_ptr<const shape> g = t.shapeAt(f);
        const double V = g->volume();
        if (s.number == 0 && r.placedVolume + 0.5*V > target)
        {
            r.complete = true;
            break;
        }
        bodyPose pose;
        const bool placed = place
        (
            t, g, s.region, regionSurface.get(), present, s.clearance,
            s.maxAttempts, rng, pose, r.attempts
        );
        if (!placed)
        {
            break;
        }

        rigidBody b(s.name + "_" + std::to_string(n), g, t.density, t.material);
        b.pose = pose;
        vec3 v = t.velocity;
        for (int i = 0; i < 3; ++i)
        {
            v[i] += t.velocitySpread[i]*(2*sizeDistribution::uniform01(rng) - 1);
        }
        b.velocity = v;
        b.angularVelocity = t.angularVelocity;
        r.indices.push_back(dem.addBody(std::move(b)));
        ++r.placed;
        r.placedVolume += V;
        if (s.number > 0 && r.placed == s.number)
        {
            r.complete = true;
        }
    }
    dem.bodiesChanged();
    return r;
}

} // End namespace immersedDEM
