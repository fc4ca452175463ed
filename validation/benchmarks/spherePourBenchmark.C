/*---------------------------------------------------------------------------*\
Application
    spherePourBenchmark

Description
    The core's twin of validation/benchmarks/liggghts/pour1000.in, the
    LIGGGHTS reference that compareLiggghts.sh runs beside it: change both
    together.

    1000 equal spheres (r = 1 mm, density 2500; Y = 1e7 Pa, nu = 0.3,
    e = 0.5, mu = 0.5, walls of the same material) poured into a box of 5
    plane walls (floor z = 0, sides x = 0, x = W, y = 0, y = W, W = 26 mm,
    open top) under gravity, with the Hertz-Mindlin law ("hertzMindlin")
    on the analytic sphere overlap ("sphere"), at a fixed time step of
    8e-6 s (about 1/30 of the sphere-sphere Hertz contact time at
    0.5 m/s) for 25000 steps (0.2 s): the spheres land and come to rest
    in a pile.

    Start at rest on a 10 x 10 x 10 simple cubic lattice of spacing 2.5 mm,
    x fastest, then y, then z (LIGGGHTS's create_atoms order): centres
    x_i = 1.75 mm + 2.5 mm i (y likewise), z_k = 2 mm + 2.5 mm k, each
    nudged sideways by
        dx = 0.2 mm sin(7919 y0 + 3001 z0),  dy = 0.2 mm sin(6007 x0 + 4001 z0)
    (x0, y0, z0 the lattice point in metres).

    The damping has the same form on both sides: the normal force
        f_n = max(0, 4/3 E* sqrt(R*) delta^(3/2) + c sqrt(m* S_n) v_n)
    and the tangential damping c sqrt(m* S_t), with c = c(0.5, 3/2) of
    restitutionCalibration (a head-on rebound of exactly 0.5). LIGGGHTS's
    hertz model is that form with c = 2 sqrt(5/6) |beta|,
    beta = ln e_L/sqrt(ln^2 e_L + pi^2), and limitForce on (no
    attraction): compareLiggghts.sh gives it the e_L whose c is this one,
    from the damping printed here.

    Prints the setup, a history every 2500 steps as LIGGGHTS's thermo
    (step, translational and rotational kinetic energy, mean and maximum
    height of the centres) and a summary; its last line, for scripts:
        RESULT steps=N wall=s stepsPerSecond=x keTrans=J keRot=J
               meanHeight=m maxHeight=m lost=n nan=0|1 damping=c
    (one line). wall is the clock around the stepping loop only, as
    LIGGGHTS's "Loop time"; lost the spheres whose centre was outside the
    box at any history line (every --every steps) or at the end.

Usage
    spherePourBenchmark [nSteps] [--dt=s] [--every=n]

    nSteps  steps to run (default 25000)
    --dt    the time step (default 8e-6 s)
    --every steps between history lines (default 2500; 0: none)
\*---------------------------------------------------------------------------*/

#include "demSolver.H"
#include "halfSpaceShape.H"
#include "sphereShape.H"
#include "hertzMindlinContactLaw.H"
#include "restitutionCalibration.H"
#include "coreError.H"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

using namespace immersedDEM;

namespace
{

struct options
{
    long nSteps = 25000;
    double dt = 8e-6;
    long every = 2500;
};


options parse(int argc, char* argv[])
{
    options o;
    int positional = 0;
    for (int i = 1; i < argc; ++i)
    {
        const std::string a = argv[i];
        auto value = [&](const char* key) -> const char*
        {
            const size_t n = std::strlen(key);
            return a.compare(0, n, key) == 0 ? a.c_str() + n : nullptr;
        };
        if (const char* v = value("--dt=")) o.dt = std::atof(v);
        else if (const char* v = value("--every=")) o.every = std::atol(v);
        else if (!a.empty() && a[0] != '-' && positional == 0)
        {
            o.nSteps = std::atol(a.c_str());
            ++positional;
        }
        else
        {
            throw coreError("Unknown argument '" + a + "'");
        }
    }
    if (o.nSteps < 0 || !(o.dt > 0) || o.every < 0)
    {
        throw coreError("nSteps must be >= 0, dt > 0 and every >= 0");
    }
    return o;
}


// The case, as in liggghts/pour1000.in
constexpr double radius = 1e-3;
constexpr double density = 2500;
constexpr double W = 0.026;             // box width
constexpr double spacing = 2.5e-3;      // lattice
constexpr double x0First = 1.75e-3;     // first lattice point, x and y
constexpr double z0First = 2e-3;        // first layer
constexpr int nSide = 10;               // nSide^3 spheres
constexpr double nudge = 0.2e-3;


struct state
{
    double keTrans = 0, keRot = 0, meanHeight = 0, maxHeight = 0;
    int lost = 0;
    bool nan = false;
};


//- Marks the spheres whose centre is outside the box now
void markOutside(const demSolver& dem, int firstSphere, std::vector<bool>& outside)
{
    outside.resize(dem.bodies().size(), false);
    for (size_t i = firstSphere; i < dem.bodies().size(); ++i)
    {
        const vec3& x = dem.bodies()[i].pose.position();
        if (!(x.x() > 0 && x.x() < W && x.y() > 0 && x.y() < W && x.z() > 0))
        {
            outside[i] = true;
        }
    }
}


state measure(const demSolver& dem, int firstSphere)
{
    state s;
    s.maxHeight = -std::numeric_limits<double>::max();
    int n = 0;
    for (size_t i = firstSphere; i < dem.bodies().size(); ++i)
    {
        const rigidBody& b = dem.bodies()[i];
        const vec3& x = b.pose.position();
        if (!x.allFinite() || !b.velocity.allFinite() || !b.angularVelocity.allFinite())
        {
            s.nan = true;
            continue;
        }
        const double m = b.mass();
        s.keTrans += 0.5*m*b.velocity.squaredNorm();
        s.keRot += 0.5*0.4*m*radius*radius*b.angularVelocity.squaredNorm();
        s.meanHeight += x.z();
        s.maxHeight = std::max(s.maxHeight, x.z());
        ++n;
        if (!(x.x() > 0 && x.x() < W && x.y() > 0 && x.y() < W && x.z() > 0))
        {
            ++s.lost;
        }
    }
    s.meanHeight /= std::max(1, n);
    return s;
}


int run(const options& o)
{
    contactMaterial m;
    m.name = "glass";
    m.youngsModulus = 1e7;
    m.poissonsRatio = 0.3;
    m.restitution = 0.5;
    m.friction = 0.5;

    demSettings s;
    s.overlapMethod = "sphere";
    s.contactLaw = "hertzMindlin";
    s.deltaT = o.dt;
    s.gravity = vec3(0, 0, -9.81);
    demSolver dem({m}, s);

    auto addWall = [&](const std::string& name, const vec3& p, const vec3& n)
    {
        rigidBody w(name, std::make_shared<halfSpaceShape>(), 1.0, 0);
        w.pose = halfSpaceShape::poseOf(p, n);
        w.motion = motionType::fixed;
        dem.addBody(std::move(w), true);
    };
    addWall("floor", vec3::Zero(), vec3::UnitZ());
    addWall("xMin", vec3::Zero(), vec3::UnitX());
    addWall("xMax", vec3(W, 0, 0), -vec3::UnitX());
    addWall("yMin", vec3::Zero(), vec3::UnitY());
    addWall("yMax", vec3(0, W, 0), -vec3::UnitY());
    const int nWalls = int(dem.bodies().size());

    const auto ball = std::make_shared<sphereShape>(radius);
    for (int k = 0; k < nSide; ++k)
    {
        for (int j = 0; j < nSide; ++j)
        {
            for (int i = 0; i < nSide; ++i)
            {
                const double x0 = x0First + i*spacing;
                const double y0 = x0First + j*spacing;
                const double z0 = z0First + k*spacing;
                rigidBody b("sphere" + std::to_string(dem.bodies().size() - nWalls), ball, density, 0);
                b.pose.setPosition
                (
                    vec3
                    (
                        x0 + nudge*std::sin(7919.0*y0 + 3001.0*z0),
                        y0 + nudge*std::sin(6007.0*x0 + 4001.0*z0),
                        z0
                    )
                );
                dem.addBody(std::move(b));
            }
        }
    }
    const int nSpheres = int(dem.bodies().size()) - nWalls;

    // The Hertz contact times at 0.5 m/s, against the step
    const hertzMindlinContactLaw law;
    const pairMaterial pm = pairMaterial::of(m, m);
    const double mass = dem.bodies()[nWalls].mass();
    const double tcSphere = law.contactTime(pm, mass/2, radius/2, radius/2, 0.5);
    const double tcWall = law.contactTime(pm, mass, radius, radius, 0.5);

    std::printf("spherePourBenchmark: %d spheres (r = %g mm, density %g), lattice %d^3 spacing %g mm\n",
        nSpheres, radius*1e3, density, nSide, spacing*1e3);
    std::printf("  box %g x %g mm, 5 plane walls; Y = %g Pa, nu = %g, e = %g, mu = %g\n",
        W*1e3, W*1e3, m.youngsModulus, m.poissonsRatio, m.restitution, m.friction);
    const double damping = restitutionCalibration::damping(m.restitution, 1.5);
    std::printf("  damping c(e, 3/2) = %.12g: f_n = max(0, 4/3 E* sqrt(R*) delta^1.5 + c sqrt(m* S_n) v_n)\n",
        damping);
    std::printf("  law %s, overlap %s; dt = %g s = t_c/%.1f (sphere-sphere t_c %.3g s at 0.5 m/s;"
        " sphere-wall %.3g s); %ld steps = %g s\n\n",
        s.contactLaw.c_str(), s.overlapMethod.c_str(), o.dt, tcSphere/o.dt, tcSphere, tcWall,
        o.nSteps, o.nSteps*o.dt);

    // Every sphere whose centre left the box at a history line or the end
    std::vector<bool> everOutside;
    auto history = [&](long n)
    {
        markOutside(dem, nWalls, everOutside);
        const state st = measure(dem, nWalls);
        std::printf("%8ld %13.6e %13.6e %13.6e %13.6e\n",
            n, st.keTrans, st.keRot, st.meanHeight, st.maxHeight);
        std::fflush(stdout);
    };
    if (o.every > 0)
    {
        std::printf("%8s %13s %13s %13s %13s\n", "step", "keTrans [J]", "keRot [J]", "zMean [m]", "zMax [m]");
        history(0);
    }

    const auto t0 = std::chrono::steady_clock::now();
    for (long n = 1; n <= o.nSteps; ++n)
    {
        dem.step(o.dt);
        if (o.every > 0 && n % o.every == 0)
        {
            history(n);
        }
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    state st = measure(dem, nWalls);
    markOutside(dem, nWalls, everOutside);
    st.lost = int(std::count(everOutside.begin(), everOutside.end(), true));
    const demSolver::counters& w = dem.work();
    std::printf("\nSummary\n");
    std::printf("  spheres                 %d (+ %d walls)\n", nSpheres, nWalls);
    std::printf("  steps                   %ld (%g s simulated)\n", w.steps, dem.time());
    std::printf("  wall-clock (loop)       %.3f s\n", seconds);
    std::printf("  steps per second        %.1f\n", w.steps/std::max(seconds, 1e-12));
    std::printf("  contact evaluation      %.3f s (%.0f %% of the loop)\n",
        w.contactSeconds, 100*w.contactSeconds/std::max(seconds, 1e-12));
    std::printf("  pair evaluations        %ld (%.1f per step, %.3f us each incl. broad phase)\n",
        w.pairEvaluations, double(w.pairEvaluations)/std::max(1L, w.steps),
        1e6*w.contactSeconds/std::max(1L, w.pairEvaluations));
    std::printf("  contacts at the end     %zu\n", dem.contacts().size());
    std::printf("  neighbour lists built   %ld (every %.1f steps)\n",
        w.broadPhaseBuilds, double(w.steps)/std::max(1L, w.broadPhaseBuilds));
    std::printf("  kinetic energy          translational %.6e J, rotational %.6e J\n",
        st.keTrans, st.keRot);
    std::printf("  height of the centres   mean %.6e m, max %.6e m\n", st.meanHeight, st.maxHeight);
    std::printf("  outside the box         %d (at any history line or the end)\n", st.lost);
    std::printf("  NaN                     %s\n", st.nan ? "yes" : "no");
    std::printf("RESULT steps=%ld wall=%.6f stepsPerSecond=%.3f keTrans=%.6e keRot=%.6e"
        " meanHeight=%.6e maxHeight=%.6e lost=%d nan=%d damping=%.12g\n",
        w.steps, seconds, w.steps/std::max(seconds, 1e-12), st.keTrans, st.keRot,
        st.meanHeight, st.maxHeight, st.lost, st.nan ? 1 : 0, damping);
    return st.nan ? 1 : 0;
}

} // End anonymous namespace


int main(int argc, char* argv[])
{
    try
    {
        return run(parse(argc, argv));
    }
    catch (const std::exception& e)
    {
        std::fprintf(stderr, "spherePourBenchmark: %s\n", e.what());
        return 2;
    }
}


// ************************************************************************* //
