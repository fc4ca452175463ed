#include "rigidBody.H"
#include "coreError.H"

#include <cmath>
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
    return dynamic() ? a.dot(worldInertia().inverse()*a) : 0;
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

} // End namespace immersedDEM
