#include "demStepSize.H"
#include "broadPhase.H"
#include "sphereShape.H"
#include "coreError.H"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <sstream>

namespace immersedDEM
{

namespace
{
    // The largest speed of any body, and the smallest volume-equivalent
    // diameter of a body that is not a wall
    void speedAndSize
    (
        const std::vector<rigidBody>& bodies, const std::vector<char>& isWall,
        double& vMax, double& dMin
    )
    {
        vMax = 0;
        dMin = std::numeric_limits<double>::max();
        for (size_t i = 0; i < bodies.size(); ++i)
        {
            vMax = std::max(vMax, bodies[i].velocity.norm());
            if (!isWall[i]) dMin = std::min(dMin, 2*bodies[i].equivalentRadius());
        }
    }
}


double demStepSize::contactTime(const inputs& in, int i, int k, double f, double v)
{
    const rigidBody& b = in.bodies[i];
    const double m = b.mass();
    const double R = b.equivalentRadius();
    const pairMaterial& pm = in.materials.of(b.material, k);
    const double Reff = f*R;
    const double lc =
        in.settings.characteristicLength > 0 ? in.settings.characteristicLength : Reff;
    double tc = in.law.contactTime(pm, f*m, Reff, lc, v);

    // A mesh may touch with a flat face: a linear spring of stiffness
    // Y* A/l_c over its cross-section A ~ pi R^2, whose half period does
    // not depend on the speed
    if (!shapeAs<sphereShape>(*b.geometry))
    {
        const double kf = in.law.faceStiffness(pm, M_PI*R*R, Reff, lc);
        tc = std::min(tc, M_PI*std::sqrt(f*m/kf));
    }
    return tc;
}


double demStepSize::timeStep(const inputs& in)
{
    if (in.settings.deltaT > 0)
    {
        return in.settings.deltaT;
    }
    double vMax, dMin;
    speedAndSize(in.bodies, in.isWall, vMax, dMin);
    const double v = std::max(in.settings.referenceSpeed, 2*vMax);

    // Materials present
    std::vector<char> present(in.materials.size(), 0);
    for (const rigidBody& b : in.bodies) present[b.material] = 1;

    double tc = std::numeric_limits<double>::max();
    for (size_t i = 0; i < in.bodies.size(); ++i)
    {
        if (!in.bodies[i].dynamic()) continue;
        for (size_t k = 0; k < in.materials.size(); ++k)
        {
            if (!present[k]) continue;
            // Against a like body (m*/2, R/2), and against a wall (m, R)
            for (const double f : {0.5, 1.0})
            {
                tc = std::min(tc, contactTime(in, int(i), int(k), f, v));
            }
        }
    }
    if (tc == std::numeric_limits<double>::max())
    {
        return std::numeric_limits<double>::max();
    }
    // No body moves more than maxTravel of the smallest body's size
    // relative to another in a step, whatever the contact law says: the
    // fastest relative approach (at most 2 max|v|) cannot carry a body
    // through a wall or another body between two contact evaluations
    double dt = tc/in.settings.stepsPerContact;
    if (vMax > 0 && dMin < std::numeric_limits<double>::max())
    {
        dt = std::min(dt, maxTravel*dMin/(2*vMax));
    }
    return dt;
}


demStepSize::choice demStepSize::stepFor
(
    const inputs& in, double T, double reach, double time
)
{
    choice c;
    if (in.settings.deltaT > 0)
    {
        c.deltaT = in.settings.deltaT;
        c.userStep = true;
        return c;
    }
    const int n = int(in.bodies.size());
    double vMax, dMin;
    speedAndSize(in.bodies, in.isWall, vMax, dMin);
    const double v = std::max(in.settings.referenceSpeed, 2*vMax);

    // How far each body can go in T: its speed now and its acceleration
    // under the loads and forces now (fluid, weight, contacts, films), the
    // damper's pull to its reference course included; twice that, for
    // what a collision within the step may add
    const double g = in.settings.gravity.norm();
    std::vector<double> travel(n, 0.0);
    for (int i = 0; i < n; ++i)
    {
        const rigidBody& b = in.bodies[i];
        double a = 0;
        if (b.dynamic())
        {
            const double m = b.mass();
            const fluidLoad& fl = b.fluid;
            a = g
              + (
                    b.appliedFluidForce(time).norm()
                  + fl.damping*fl.referenceAcceleration.norm()*T
                  + b.contactForce.norm() + b.lubricationForce.norm()
                )/m;
        }
        travel[i] = 2*(b.velocity.norm()*T + 0.5*a*T*T);
    }

    double tc = std::numeric_limits<double>::max();
    auto consider = [&](int a, int b)
    {
        ++c.pairs;
        for (const int i : {a, b})
        {
            const int j = i == a ? b : a;
            if (!in.bodies[i].dynamic()) continue;
            const double f = in.bodies[j].dynamic() ? 0.5 : 1.0;
            const double t = contactTime(in, i, in.bodies[j].material, f, v);
            if (t < tc)
            {
                tc = t;
                c.a = a;
                c.b = b;
            }
        }
    };

    // Bodies: boxes grown by their travel and half the reach, then their
    // bounding spheres
    std::vector<int> others;
    std::vector<axisAlignedBox> grown(n);
    for (int i = 0; i < n; ++i)
    {
        grown[i] = in.bodies[i].geometry->worldBox(in.bodies[i].pose)
            .inflated(travel[i] + 0.5*reach);
        if (!in.isWall[i]) others.push_back(i);
    }
    const periodicBox& periodic = in.settings.periodic;
    for (const auto& p : broadPhase::gridPairs(grown, others, periodic))
    {
        const int i = p.first, j = p.second;
        if (!in.bodies[i].dynamic() && !in.bodies[j].dynamic()) continue;
        const vec3& xi = in.bodies[i].pose.position();
        const vec3& xj = in.bodies[j].pose.position();
        const double gap =
            (xj + periodic.nearestShift(xi, xj) - xi).norm()
          - in.bodies[i].geometry->boundingRadius() - in.bodies[j].geometry->boundingRadius();
        if (gap <= travel[i] + travel[j] + reach) consider(i, j);
    }
    // Walls: the distance from the body's centre to the wall's surface. A
    // turning wall (prescribed) moves near the body at most at
    // |v| + |w| |x - c|: no box test for it
    for (int w = 0; w < n; ++w)
    {
        if (!in.isWall[w]) continue;
        const rigidBody& W = in.bodies[w];
        const double spin = W.angularVelocity.norm();
        for (const int i : others)
        {
            if (!in.bodies[i].dynamic() || (spin == 0 && !grown[w].overlaps(grown[i])))
            {
                continue;
            }
            const vec3& x = in.bodies[i].pose.position();
            const double d = std::abs(W.geometry->closest(W.pose, x).distance);
            const double gap = d - in.bodies[i].geometry->boundingRadius();
            const double wallTravel =
                travel[w] + 2*spin*((x - W.pose.position()).norm() + d)*T;
            if (gap <= travel[i] + wallTravel + reach) consider(w, i);
        }
    }

    double dt = T;
    if (tc < std::numeric_limits<double>::max())
    {
        dt = tc/in.settings.stepsPerContact;
        if (vMax > 0 && dMin < std::numeric_limits<double>::max())
        {
            dt = std::min(dt, maxTravel*dMin/(2*vMax));
        }
    }
    else
    {
        // Free flight. The fluid's damper relaxes a body to its reference
        // course over (m + m_a)/c; the kicks take it implicitly (stable
        // for any step), and a tenth of that time resolves the relaxation
        // (implicit Euler's error in it under 5%). Never shorter than the
        // softest-case step, though
        for (const rigidBody& b : in.bodies)
        {
            if (!b.dynamic()) continue;
            const fluidLoad& fl = b.fluid;
            const double relax = std::min
            (
                fl.damping > 0
              ? (b.mass() + fl.addedMass)/fl.damping
              : std::numeric_limits<double>::max(),
                fl.angularDamping > 0
              ? (b.inertia().minCoeff() + fl.addedInertia)/fl.angularDamping
              : std::numeric_limits<double>::max()
            );
            if (0.1*relax < dt)
            {
                dt = 0.1*relax;
                c.nameA = b.name;
                c.relaxation = relax;
            }
        }
        if (dt < timeStep(in))
        {
            dt = timeStep(in);
            c.nameA.clear();
            c.floor = true;
        }
    }
    if (c.a >= 0)
    {
        c.nameA = in.bodies[c.a].name;
        c.nameB = in.bodies[c.b].name;
    }
    c.deltaT = std::min(dt, T);
    return c;
}


int demStepSize::plan(const inputs& in, double T, double reach, double time)
{
    last_ = stepFor(in, T, reach, time);
    const double dtMax = last_.deltaT;
    const double steps = std::ceil(T/dtMax - 1e-9);
    if (!(dtMax > 0) || !(steps <= maxStepsPerAdvance))
    {
        // The step must be representable and its count an int: a stiff or
        // light material (youngsModulus, density) makes it vanish
        std::ostringstream msg;
        msg.precision(3);
        msg << "The DEM time step " << dtMax << " s would take " << steps
            << " steps to cover " << T << " s (at most " << maxStepsPerAdvance
            << " are allowed): the contact time of the bodies is too short."
            << " Check youngsModulus of the materials (";
        for (size_t k = 0; k < in.materials.size(); ++k)
        {
            msg << (k ? ", " : "") << in.materials[k].name << ": "
                << in.materials[k].youngsModulus << " Pa";
        }
        msg << ") and density of the bodies (";
        bool first = true;
        for (size_t i = 0; i < in.bodies.size(); ++i)
        {
            if (!in.bodies[i].dynamic()) continue;
            msg << (first ? "" : ", ") << in.bodies[i].name << ": "
                << in.bodies[i].density << " kg/m3";
            first = false;
        }
        msg << "), or deltaT";
        throw coreError(msg.str());
    }
    const int n = std::max(1, int(steps));
    const double dt = T/n;
    // A step of the user's (deltaT) may let a fast body travel far
    for (size_t i = 0; i < in.bodies.size(); ++i)
    {
        const rigidBody& b = in.bodies[i];
        if (!last_.userStep || in.isWall[i] || warned_.count(i)) continue;
        const double d = 2*b.equivalentRadius();
        if (b.velocity.norm()*dt > maxTravel*d)
        {
            std::cerr
                << "\n--> immersedDEM warning: body '" << b.name << "' moves "
                << b.velocity.norm()*dt/d << " of its size (" << d << " m) in one DEM"
                << " step of " << dt << " s (more than " << maxTravel << "):"
                << " contacts may be missed or too deep. Reduce deltaT\n";
            warned_.insert(i);
        }
    }
    return n;
}


void demStepSize::renumber(const std::vector<int>& newIndex)
{
    std::set<size_t> warned;
    for (const size_t i : warned_)
    {
        if (newIndex[i] >= 0) warned.insert(size_t(newIndex[i]));
    }
    warned_.swap(warned);
}

} // End namespace immersedDEM
