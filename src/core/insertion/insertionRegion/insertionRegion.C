#include "insertionRegion.H"
#include "sizeDistribution.H"
#include "coreError.H"

#include <cmath>

namespace immersedDEM
{

insertionRegion insertionRegion::box(const vec3& min, const vec3& max)
{
    if (!((max - min).minCoeff() > 0) || !min.allFinite() || !max.allFinite())
    {
        throw coreError("the box needs min < max on every axis");
    }
    insertionRegion r;
    r.kind_ = kind::box;
    r.a_ = min;
    r.b_ = max;
    return r;
}


insertionRegion insertionRegion::cylinder(const vec3& p1, const vec3& p2, double radius)
{
    const double L = (p2 - p1).norm();
    if (!(L > 0) || !std::isfinite(L))
    {
        throw coreError("the cylinder's point1 and point2 must differ");
    }
    if (!(radius > 0) || !std::isfinite(radius))
    {
        throw coreError("the cylinder's radius must be > 0");
    }
    insertionRegion r;
    r.kind_ = kind::cylinder;
    r.a_ = p1;
    r.b_ = p2;
    r.radius_ = radius;
    r.length_ = L;
    r.axis_ = (p2 - p1)/L;
    // Any unit vector normal to the axis, and the third one
    const vec3 t = std::abs(r.axis_.x()) < 0.9 ? vec3::UnitX() : vec3::UnitY();
    r.e1_ = r.axis_.cross(t).normalized();
    r.e2_ = r.axis_.cross(r.e1_);
    return r;
}


insertionRegion insertionRegion::surface(std::shared_ptr<const shape> closed)
{
    if (!closed || closed->type() != "triangleMesh")
    {
        throw coreError("a surface region needs a closed triangle surface");
    }
    insertionRegion r;
    r.kind_ = kind::surface;
    r.surfacePose_ = closed->bodyInFile();
    r.surface_ = std::move(closed);
    const axisAlignedBox b = r.surface_->worldBox(r.surfacePose_);
    r.a_ = b.min;
    r.b_ = b.max;
    return r;
}


double insertionRegion::volume() const
{
    if (kind_ == kind::surface)
    {
        return surface_->volume();
    }
    if (kind_ == kind::box)
    {
        return (b_ - a_).prod();
    }
    return M_PI*radius_*radius_*length_;
}


axisAlignedBox insertionRegion::bounds() const
{
    if (kind_ == kind::box || kind_ == kind::surface)
    {
        return axisAlignedBox(a_, b_);
    }
    // Box of the two end discs: per axis, radius sqrt(1 - a_i^2)
    const vec3 h = radius_*(vec3::Ones() - axis_.cwiseProduct(axis_)).cwiseMax(0).cwiseSqrt();
    return axisAlignedBox(a_.cwiseMin(b_) - h, a_.cwiseMax(b_) + h);
}


vec3 insertionRegion::sample(std::mt19937_64& rng) const
{
    if (kind_ == kind::box || kind_ == kind::surface)
    {
        vec3 p;
        // A surface: points of its box until one is inside (the caller
        // tests the body anyway; a region of a tiny part of its box is
        // an error rather than an endless loop)
        for (int k = 0; k < 1000000; ++k)
        {
            for (int i = 0; i < 3; ++i)
            {
                p[i] = a_[i] + (b_[i] - a_[i])*sizeDistribution::uniform01(rng);
            }
            if (kind_ == kind::box || surface_->inside(surfacePose_, p)) return p;
        }
        throw coreError("no point inside the region's surface found in 1e6 samples of its box");
    }
    // Uniform in the disc: r = R sqrt(u)
    const double t = length_*sizeDistribution::uniform01(rng);
    const double r = radius_*std::sqrt(sizeDistribution::uniform01(rng));
    const double phi = 2*M_PI*sizeDistribution::uniform01(rng);
    return a_ + t*axis_ + r*(std::cos(phi)*e1_ + std::sin(phi)*e2_);
}


bool insertionRegion::contains(const vec3& p, double margin) const
{
    if (kind_ == kind::surface)
    {
        return surface_->signedDistance(surfacePose_, p) <= -margin;
    }
    if (kind_ == kind::box)
    {
        return ((p - a_).minCoeff() >= margin) && ((b_ - p).minCoeff() >= margin);
    }
    const vec3 d = p - a_;
    const double t = d.dot(axis_);
    if (t < margin || t > length_ - margin) return false;
    const double r = (d - t*axis_).norm();
    return r <= radius_ - margin;
}


bool insertionRegion::containsAll(const std::vector<vec3>& points) const
{
    for (const vec3& p : points)
    {
        if (!contains(p)) return false;
    }
    return true;
}

} // End namespace immersedDEM
