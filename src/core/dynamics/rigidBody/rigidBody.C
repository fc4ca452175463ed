#include "rigidBody.H"
#include "coreError.H"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace immersedDEM
{

motionType motionTypeFromName(const std::string& name)
{
    if (name == "free") return motionType::free;
    if (name == "fixed") return motionType::fixed;
    if (name == "prescribed") return motionType::prescribed;

    throw coreError
    (
        "Unknown motion type '" + name
      + "'; valid types are (fixed free prescribed)"
    );
}


std::string motionTypeName(motionType m)
{
    switch (m)
    {
        case motionType::free: return "free";
        case motionType::fixed: return "fixed";
        case motionType::prescribed: return "prescribed";
    }
    // Only reachable through a cast of an invalid integer
    throw coreError("Invalid motion type value " + std::to_string(int(m)));
}


rigidBody::rigidBody
(
    const std::string& name,
    std::shared_ptr<const shape> geometry,
    double density,
    int material
)
:
    name(name),
    geometry(std::move(geometry)),
    density(density),
    material(material)
{
    if (!this->geometry)
    {
        throw coreError("Body '" + name + "' has no shape");
    }
    if (!(std::isfinite(density) && density > 0))
    {
        std::ostringstream os;
        os  << "Body '" << name << "': density must be positive and finite, not "
            << density;
        throw coreError(os.str());
    }
}


mat3 rigidBody::worldInertia() const
{
    const mat3& R = pose.rotation();
    return R*inertia().asDiagonal()*R.transpose();
}


double rigidBody::inverseInertiaAlong(const vec3& a) const
{
    if (!dynamic())
    {
        return 0;
    }
    // I^-1 = R diag(1/I_k) R^T: the components of a in the principal axes
    const vec3 b = pose.rotation().transpose()*a;
    const vec3& I = inertia();
    return b.x()*b.x()/I.x() + b.y()*b.y()/I.y() + b.z()*b.z()/I.z();
}


double rigidBody::sphereRadiusOfVolume() const
{
    return std::cbrt(3*geometry->volume()/(4*M_PI));
}


double rigidBody::kineticEnergy() const
{
    // Rotational part in the body frame: no world tensor to build
    const vec3 wBody = pose.vectorToBody(angularVelocity);
    return
        0.5*mass()*velocity.squaredNorm()
      + 0.5*wBody.dot(inertia().cwiseProduct(wBody));
}


vec3 rigidBody::angularMomentum() const
{
    const vec3 wBody = pose.vectorToBody(angularVelocity);
    return pose.vectorToWorld(inertia().cwiseProduct(wBody));
}

fluidImpedance::bodySize rigidBody::fluidSize() const
{
    const triangleSoup surface = geometry->surface();
    double area = 0;
    for (const auto& f : surface.faces)
    {
        const vec3& p0 = surface.points[f[0]];
        area += 0.5*(surface.points[f[1]] - p0).cross(surface.points[f[2]] - p0).norm();
    }
    fluidImpedance::bodySize s;
    s.volume = geometry->volume();
    s.area = area;
    s.circumscribedRadius = geometry->boundingRadius();
    s.depth = 0;

    // A 2D body: its locked axis is fixed in the body's frame (it turns
    // only about it)
    int locked = -1;
    if (lockTranslation.sum() == 1)
    {
        for (int k = 0; k < 3; ++k)
        {
            if
            (
                lockTranslation[k]
             && lockRotation[(k + 1) % 3] && lockRotation[(k + 2) % 3]
            )
            {
                locked = k;
            }
        }
    }
    if (locked >= 0 && !surface.points.empty())
    {
        const vec3 e = pose.vectorToBody(vec3::Unit(locked));
        double lo = std::numeric_limits<double>::max();
        double hi = -lo;
        double R2 = 0;
        for (const vec3& p : surface.points)
        {
            const double z = p.dot(e);
            lo = std::min(lo, z);
            hi = std::max(hi, z);
            R2 = std::max(R2, (p - z*e).squaredNorm());
        }
        if (hi > lo)
        {
            s.depth = hi - lo;
            const double section = s.volume/s.depth;
            s.volume = section;
            s.area = std::max(area - 2*section, 0.0)/s.depth;
            s.circumscribedRadius = std::sqrt(R2);
        }
    }
    return s;
}

} // End namespace immersedDEM
