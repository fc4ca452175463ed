#include "immersedFluidCoupling.H"
#include "immersedBoundaryProjection.H"
#include "coreConversion.H"
#include "bodyFluidSums.H"
#include "immersedForcing.H"
#include "clockTime.H"

#include <cmath>

using namespace immersedDEM;

namespace Foam
{
    defineTypeNameAndDebug(immersedFluidCoupling, 0);
}


namespace
{

constexpr auto v = &Foam::coreConversion::toFoam;
constexpr auto c = &Foam::coreConversion::toCore;

} // End anonymous namespace


Foam::immersedFluidCoupling::immersedFluidCoupling(const demSolver& dem)
{
    const label n = dem.bodies().size();
    memory_.setSize(n);
    sizes_.setSize(n);
    sized_.setSize(n, false);
    takenUnknown_.setSize(n, false);
    for (label i = 0; i < n; ++i)
    {
        memory_[i] = couplingMemory
        (
            dem.bodies()[i].velocity, dem.bodies()[i].angularVelocity
        );
    }
}


void Foam::immersedFluidCoupling::setInnerMomentum
(
    const immersedBoundaryProjection& projection,
    const demSolver& dem,
    const volVectorField& U
)
{
    if (innerMomentumSet_)
    {
        return;
    }
    // The fluid inside the bodies as it is before the first step: if it
    // is at rest while a body starts moving, the first step's forcing sets
    // it in motion, and the inner term must cancel that part of the
    // forcing's reaction (it is the body's own volume, not the fluid
    // around it, being accelerated)
    const bodyFluidSums sums(projection, dem, U, 0, pName_);
    forAll(memory_, i)
    {
        memory_[i].innerMomentum = c(sums.momentum[i]);
        memory_[i].innerAngularMomentum = c(sums.angularMomentum[i]);
    }
    innerMomentumSet_ = true;
}


const immersedDEM::fluidImpedance::bodySize&
Foam::immersedFluidCoupling::sizeOf(const demSolver& dem, const label i)
{
    if (!sized_[i])
    {
        sizes_[i] = dem.bodies()[i].fluidSize();
        sized_[i] = true;
    }
    return sizes_[i];
}


void Foam::immersedFluidCoupling::fluidLoads
(
    const immersedBoundaryProjection& projection,
    demSolver& dem,
    const volVectorField& U,
    scalar deltaT,
    const settings& s
)
{
    const scalar rho = s.rho;
    const clockTime timer;
    setInnerMomentum(projection, dem, U);
    const bodyFluidSums sums(projection, dem, U, deltaT, pName_);
    const List<vector>& P = sums.penalty;
    const List<vector>& PM = sums.penaltyMoment;
    const List<vector>& M = sums.momentum;
    const List<vector>& L = sums.angularMomentum;
    auto& bodies = dem.bodies();
    // Bodies in contact at the end of the last DEM step (pairs with a
    // contact history)
    List<bool> inContact(bodies.size(), false);
    for (const auto& p : dem.pairsInContact())
    {
        if (p.first < inContact.size()) inContact[p.first] = true;
        if (p.second < inContact.size()) inContact[p.second] = true;
    }
    // The bodies' volume-equivalent radii (in 2D of their sections), and
    // the others within reach of a body's shell, for its solid fraction
    const label n = bodies.size();
    List<scalar> equivalentRadius(n, scalar(0));
    forAll(equivalentRadius, j)
    {
        if (dem.isWall(j)) continue;
        const fluidImpedance::bodySize& sj = sizeOf(dem, j);
        equivalentRadius[j] = sj.depth > 0
            ? std::sqrt(sj.volume/constant::mathematical::pi)
            : std::cbrt(3*sj.volume/(4*constant::mathematical::pi));
    }
    std::vector<std::pair<double, double>> near;
    auto neighbours = [&](const label i) -> const std::vector<std::pair<double, double>>&
    {
        near.clear();
        const vec3& xi = bodies[i].pose.position();
        for (label j = 0; j < n; ++j)
        {
            if (j == i || dem.isWall(j)) continue;
            const vec3& xj = bodies[j].pose.position();
            const double d = (xj + dem.periodic().nearestShift(xi, xj) - xi).norm();
            if (d < 2*equivalentRadius[i] + equivalentRadius[j])
            {
                near.emplace_back(d, equivalentRadius[j]);
            }
        }
        return near;
    };
    forAll(M, i)
    {
        if (dem.isWall(i)) continue;
        rigidBody& b = bodies[i];
        couplingMemory& mem = memory_[i];
        const scalar Vb = b.geometry->volume();
        // The fluid's time scheme: second order from the second step of a
        // body's history on (OpenFOAM's backward is Euler in a run's first
        // step; a body inserted later takes its first step as Euler too,
        // while the fluid is already second order)
        const bool second = s.backward && mem.history >= 1 && previousDeltaT_ > 0;
        const immersedForcing::timeDerivative ddt = second
            ? immersedForcing::timeDerivative::backward(deltaT, previousDeltaT_)
            : immersedForcing::timeDerivative::euler(deltaT);
        // (with what of it left the mesh: a body crossing an outlet)
        const vec3 innerRate =
            ddt.of(c(M[i]), mem.innerMomentum, mem.innerMomentum0)
          + c(sums.outflow[i]);
        const vec3 innerAngularRate =
            ddt.of(c(L[i]), mem.innerAngularMomentum, mem.innerAngularMomentum0)
          + c(sums.angularOutflow[i]);
        // The force and torque from the fluid's momentum balance, in its
        // time scheme, and as the body takes them: first-order rates over
        // the step (timeDerivative::firstOrder). With backward, a change
        // of the fluid's velocity in one step is answered in the next by a
        // force against it on fluid that goes on unchanged, which a body
        // moving to first order would take as real (a flow started at
        // t = 0 sent neutrally buoyant bodies upstream: case.impulsiveStart)
        const vec3 Fscheme = immersedForcing::fluidForce
        (
            rho, c(P[i]), innerRate, Vb, dem.settings().gravity
        );
        const vec3 Tscheme = immersedForcing::fluidTorque(rho, c(PM[i]), innerAngularRate);
        if (takenUnknown_[i])
        {
            mem.takenForce = Fscheme;
            mem.takenTorque = Tscheme;
            takenUnknown_[i] = false;
        }
        const vec3 F = ddt.firstOrder(Fscheme, mem.takenForce);
        const vec3 T = ddt.firstOrder(Tscheme, mem.takenTorque);
        mem.takenForce = F;
        mem.takenTorque = T;
        if (debug)
        {
            Info<< "immersedFluidCoupling loads " << word(b.name)
                << " t " << U.time().value()
                << " penalty " << rho*P[i]
                << " innerRate " << v(rho*innerRate)
                << " v " << v(b.velocity) << endl;
        }
        // The fluid's answer to a change of motion over the next step
        // (fluidImpedance.H), with the added mass the other bodies around
        // confine
        fluidImpedance::bodySize size = sizeOf(dem, i);
        size.cellSize = b.fluidCellSize;
        size.solidFraction = fluidImpedance::surroundingFraction
        (
            equivalentRadius[i], neighbours(i), size.depth > 0
        );
        fluidImpedance::coefficients z =
            fluidImpedance::estimate(size, rho, s.nu, deltaT);
        // The added mass the fluid solver shows (the change of force
        // against the change of acceleration; measuredAddedMass), for the
        // contact rule below. The smallest change of acceleration worth
        // measuring: 1e-2 m/s2, over the body's size for rotation
        const scalar unitMass = rho*Vb;
        const scalar unitInertia = rho/b.density*b.inertia().sum()/3;
        const scalar aFloor = 1e-2;
        mem.addedMass.record
        (
            F, (b.velocity - mem.previousVelocity)/deltaT, sqr(aFloor)
        );
        mem.addedInertia.record
        (
            T, (b.angularVelocity - mem.previousAngularVelocity)/deltaT,
            sqr(aFloor)/pow(Vb, 2.0/3.0)
        );
        // The body goes on from its course of the last step (reference
        // accelerations from it, first order as the force taken is: the
        // fluid's answer to the scheme's view of the change, taken to
        // first order, is its answer to this one)
        const immersedForcing::timeDerivative dv =
            immersedForcing::timeDerivative::euler(deltaT);
        vec3 a =
            dv.of(b.velocity, mem.previousVelocity, mem.previousVelocity0);
        vec3 alpha = dv.of
        (
            b.angularVelocity,
            mem.previousAngularVelocity,
            mem.previousAngularVelocity0
        );
        // Which rule: a body in a bed (in contact now, or with contacts in
        // more than one of the last CFD steps, or in two apart) takes the
        // contact rule; a free body the implicit coupling, unless the
        // fluid solver's significant answer exceeds its stable range
        // (M > m + 2 m_hat: fluidImpedance.H)
        const scalar cap = 100;
        bool held = mem.inBed(inContact[i]);
        if
        (
            !held
         && mem.addedMass.value(true) > b.mass() + 2*z.addedMass
         && z.addedMass < cap*unitMass
        )
        {
            held = true;
        }
        if (held)
        {
            // The contact rule. The body moves within the step by its
            // contacts, far faster than the fluid can answer, and its
            // velocity at the step's end is a sample of that motion: no
            // added mass carries it on. The damper m_a/deltaT (I_a/deltaT)
            // on its departure from the course extrapolated from the last
            // steps takes the fluid's answer to it within the step, m_a the
            // larger of rho V and the measured answer (the answer among
            // touching bodies exceeds any per-body estimate), and lets a
            // body at rest on a wall or in a bed stay at rest. A body that
            // landed within the step (in contact now, free at the step
            // before) changed its velocity by an impact, which does not go
            // on: its course is not extrapolated from it
            const scalar ma =
                mem.addedMass.stabilisation(b.mass(), unitMass, cap*unitMass);
            const scalar Ia = mem.addedInertia.stabilisation
            (
                b.inertia().sum()/3, unitInertia, cap*unitInertia
            );
            if (inContact[i] && !mem.wasInContact)
            {
                a = vec3::Zero();
                alpha = vec3::Zero();
            }
            b.fluid = fluidLoad::held
            (
                F, T, ma, Ia, std::min(z.nominalAddedMass, ma), deltaT,
                dem.time(), b.velocity, a, b.angularVelocity, alpha
            );
        }
        else
        {
            // The implicit coupling: the added mass carries the course on
            // and meets the fluid's answer to it, -m_a a; a bounce within
            // the step keeps its rebound
            b.fluid = fluidLoad::coupled
            (
                F, T, z, dem.time(), b.velocity, a, b.angularVelocity, alpha
            );
        }
        // Free of contacts at the step's start: an impact within the step
        // restarts the dampers' course (the contact moves the body with
        // its own added mass, far faster than the fluid; the damper would
        // take its rebound back towards the course before it)
        b.fluid.impactRestartsCourse = inContact[i] ? 0 : 1;
        if (debug)
        {
            Info<< "IFC " << word(b.name) << " t " << U.time().value()
                << " dt " << deltaT
                << " F " << v(F) << " T " << v(T)
                << " F(scheme) " << v(Fscheme) << " T(scheme) " << v(Tscheme)
                << " v " << v(b.velocity) << " w " << v(b.angularVelocity)
                << " a " << v(a)
                << " m " << b.mass() << " mhat " << z.addedMass
                << " c " << z.damping << " phi " << size.solidFraction
                << " con " << inContact[i] << mem.wasInContact
                << " held " << held << " M " << mem.addedMass.value() << endl;
        }
        mem.remember(b.velocity, b.angularVelocity, c(M[i]), c(L[i]), inContact[i]);
    }
    previousDeltaT_ = deltaT;
    seconds_ += timer.elapsedTime();
}


Foam::scalar Foam::immersedFluidCoupling::takeSeconds()
{
    const scalar s = seconds_;
    seconds_ = 0;
    return s;
}


void Foam::immersedFluidCoupling::bodiesChanged
(
    const demSolver& dem,
    const std::vector<int>& kept,
    const label firstNew
)
{
    const label n = dem.bodies().size();
    // Kept bodies' entries to their new places; new bodies' set to fill
    auto remap = [&](auto& l, const auto& fill)
    {
        typename std::decay<decltype(l)>::type m(n, fill);
        for (label i = 0; i < firstNew; ++i)
        {
            m[i] = l[kept.empty() ? i : kept[i]];
        }
        l.transfer(m);
    };
    remap(memory_, couplingMemory());
    remap(sizes_, fluidImpedance::bodySize());
    remap(sized_, false);
    remap(takenUnknown_, false);
    for (label i = firstNew; i < n; ++i)
    {
        memory_[i] = couplingMemory
        (
            dem.bodies()[i].velocity, dem.bodies()[i].angularVelocity
        );
    }
}


void Foam::immersedFluidCoupling::setNewInnerMomentum
(
    const immersedBoundaryProjection& projection,
    const demSolver& dem,
    const volVectorField& U,
    const label first
)
{
    if (first >= label(dem.bodies().size()))
    {
        return;
    }
    const bodyFluidSums sums(projection, dem, U, 0, pName_);
    for (label i = first; i < memory_.size(); ++i)
    {
        memory_[i].innerMomentum = c(sums.momentum[i]);
        memory_[i].innerAngularMomentum = c(sums.angularMomentum[i]);
    }
}


void Foam::immersedFluidCoupling::noteContacts(demSolver& dem)
{
    const std::vector<char>& touched = dem.touched();
    forAll(memory_, i)
    {
        memory_[i].noteStep(size_t(i) < touched.size() && touched[i]);
    }
    dem.clearTouched();
}
