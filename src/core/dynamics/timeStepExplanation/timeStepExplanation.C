#include "timeStepExplanation.H"
#include "sphereShape.H"

#include <cmath>
#include <limits>
#include <sstream>

namespace immersedDEM
{

timeStepExplanation timeStepExplanation::of(const demSolver& dem)
{
    timeStepExplanation e;
    const demSettings& s = dem.settings();
    if (s.deltaT > 0)
    {
        e.userStep = true;
        e.deltaT = s.deltaT;
        return e;
    }
    const auto& bodies = dem.bodies();
    const auto& materials = dem.materials();
    double vMax = 0;
    for (const rigidBody& b : bodies) vMax = std::max(vMax, b.velocity.norm());
    e.speed = std::max(s.referenceSpeed, 2*vMax);
    e.speedFromBodies = 2*vMax > s.referenceSpeed;

    std::vector<char> present(materials.size(), 0);
    for (const rigidBody& b : bodies) present[b.material] = 1;

    const std::unique_ptr<contactLaw> law = contactLaw::New(s.contactLaw);
    double tc = std::numeric_limits<double>::max();
    auto consider = [&](double t, int i, int k, bool wall, bool flat)
    {
        if (t < tc)
        {
            tc = t;
            e.body = i;
            e.material = k;
            e.againstWall = wall;
            e.flatFace = flat;
        }
    };
    for (size_t i = 0; i < bodies.size(); ++i)
    {
        const rigidBody& b = bodies[i];
        if (!b.dynamic()) continue;
        const double m = b.mass();
        const double R = b.equivalentRadius();
        for (size_t k = 0; k < materials.size(); ++k)
        {
            if (!present[k]) continue;
            const pairMaterial pm = pairMaterial::of(materials[b.material], materials[k]);
            for (const double f : {0.5, 1.0})
            {
                const double Reff = f*R;
                const double lc = s.characteristicLength > 0 ? s.characteristicLength : Reff;
                consider(law->contactTime(pm, f*m, Reff, lc, e.speed), int(i), int(k), f == 1.0, false);
                if (!dynamic_cast<const sphereShape*>(b.geometry.get()))
                {
                    const double kf = law->faceStiffness(pm, M_PI*R*R, Reff, lc);
                    consider(M_PI*std::sqrt(f*m/kf), int(i), int(k), f == 1.0, true);
                }
            }
        }
    }
    if (e.body < 0)
    {
        e.deltaT = std::numeric_limits<double>::max();
        return e;
    }
    e.contactTime = tc;
    e.deltaT = tc/s.stepsPerContact;
    return e;
}


std::string timeStepExplanation::text(const demSolver& dem) const
{
    std::ostringstream os;
    os.precision(4);
    if (userStep)
    {
        os  << "DEM step " << deltaT << " s: the fixed deltaT of 'time'";
        return os.str();
    }
    if (body < 0)
    {
        os  << "DEM step: none needed (no free body)";
        return os.str();
    }
    const rigidBody& b = dem.bodies()[body];
    os  << "DEM step " << deltaT << " s = contact time " << contactTime << " s / "
        << dem.settings().stepsPerContact << " stepsPerContact; set by body " << b.name
        << " (" << b.geometry->type() << ", equivalent radius " << b.equivalentRadius()
        << " m, material " << dem.materials()[b.material].name << ") against "
        << (againstWall ? "a wall" : "a body like it") << " of material "
        << dem.materials()[material].name << ", "
        << (flatFace ? "flat face (linear spring over its cross-section)"
                     : "law " + dem.settings().contactLaw)
        << ", at " << speed << " m/s ("
        << (speedFromBodies ? "twice the fastest body's speed" : "time referenceSpeed")
        << ")";
    return os.str();
}

std::string timeStepExplanation::lastStep(const demSolver& dem)
{
    return choice(dem.lastStep());
}

std::string timeStepExplanation::choice(const demSolver::stepChoice& c)
{
    std::ostringstream os;
    os.precision(4);
    os  << c.deltaT << " s (";
    if (c.userStep)
    {
        os  << "deltaT)";
    }
    else if (c.a < 0)
    {
        os  << "free flight: no pair can meet";
        if (c.floor)
        {
            os  << "; the DEM's own step, its floor";
        }
        else if (!c.nameA.empty())
        {
            os  << "; a tenth of the relaxation time of body " << c.nameA
                << " under the fluid's damping, (m + m_a)/c = " << c.relaxation << " s";
        }
        os  << ")";
    }
    else
    {
        os  << c.nameA << " against " << c.nameB
            << ", " << c.pairs << (c.pairs == 1 ? " pair" : " pairs") << " can meet)";
    }
    return os.str();
}

} // End namespace immersedDEM
