// What the fluid coupling keeps of a body from one CFD step to the next
// (src/core/coupling/couplingMemory): the choice of rule from the recent
// contacts, the shift of the history, and the restart list (fields()).
// And the body's size as the coupling's estimates see it
// (rigidBody::fluidSize), 3D and 2D.

#include "couplingMemory.H"
#include "rigidBody.H"
#include "sphereShape.H"
#include "triangleMeshShape.H"
#include "primitiveMeshes.H"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

using namespace immersedDEM;

// A free body that hits something once (one step, or two in a row across
// a step's end) stays free; a body with contacts in two runs, or in three
// steps, is in a bed; in contact now is always in a bed
TEST(couplingMemory, isolatedImpactsKeepTheImplicitRule)
{
    EXPECT_TRUE(couplingMemory::isolatedImpact(0));
    EXPECT_TRUE(couplingMemory::isolatedImpact(0b1));
    EXPECT_TRUE(couplingMemory::isolatedImpact(0b10000000));
    EXPECT_TRUE(couplingMemory::isolatedImpact(0b110));
    EXPECT_FALSE(couplingMemory::isolatedImpact(0b101));
    EXPECT_FALSE(couplingMemory::isolatedImpact(0b111));
    EXPECT_FALSE(couplingMemory::isolatedImpact(0b10000001));

    couplingMemory m;
    // A new body is in a bed until its contacts are one run of two steps:
    // until it has been free for recentSteps - 2 steps
    EXPECT_TRUE(m.inBed(false));
    for (int k = 0; k < couplingMemory::recentSteps - 3; ++k)
    {
        m.noteStep(false);
        EXPECT_TRUE(m.inBed(false)) << "after " << k + 1 << " free steps";
    }
    m.noteStep(false);
    EXPECT_FALSE(m.inBed(false));
    m.noteStep(false);
    m.noteStep(false);
    EXPECT_TRUE(m.inBed(true));
    // One bounce: free; a second one within recentSteps: in a bed
    m.noteStep(true);
    EXPECT_FALSE(m.inBed(false));
    m.noteStep(false);
    m.noteStep(true);
    EXPECT_TRUE(m.inBed(false));
    // Forgotten after recentSteps free steps, and the mask holds only them
    for (int k = 0; k < couplingMemory::recentSteps; ++k) m.noteStep(false);
    EXPECT_EQ(m.recentContacts, 0);
    EXPECT_FALSE(m.inBed(false));
}

// After the loads: the last becomes the one before, the history grows
TEST(couplingMemory, rememberShiftsTheHistory)
{
    couplingMemory m(vec3(1, 0, 0), vec3(0, 2, 0));
    EXPECT_EQ(m.history, 0);
    EXPECT_EQ(m.previousVelocity, vec3(1, 0, 0));
    m.remember(vec3(3, 0, 0), vec3(0, 4, 0), vec3(5, 0, 0), vec3(0, 6, 0), true);
    m.remember(vec3(7, 0, 0), vec3(0, 8, 0), vec3(9, 0, 0), vec3(0, 10, 0), false);
    EXPECT_EQ(m.history, 2);
    EXPECT_EQ(m.previousVelocity, vec3(7, 0, 0));
    EXPECT_EQ(m.previousVelocity0, vec3(3, 0, 0));
    EXPECT_EQ(m.previousAngularVelocity, vec3(0, 8, 0));
    EXPECT_EQ(m.previousAngularVelocity0, vec3(0, 4, 0));
    EXPECT_EQ(m.innerMomentum, vec3(9, 0, 0));
    EXPECT_EQ(m.innerMomentum0, vec3(5, 0, 0));
    EXPECT_EQ(m.innerAngularMomentum, vec3(0, 10, 0));
    EXPECT_EQ(m.innerAngularMomentum0, vec3(0, 6, 0));
    EXPECT_FALSE(m.wasInContact);
}

namespace
{

// Sets every member it visits to a value of its own and keeps the names
struct filler
{
    std::set<std::string>& names;
    int count = 0;
    void operator()(const char* n, vec3& x) { names.insert(n); x.setConstant(++count); }
    void operator()(const char* n, double& x) { names.insert(n); x = ++count; }
    void operator()(const char* n, int& x) { names.insert(n); x = ++count; }
    void operator()(const char* n, bool& x) { names.insert(n); ++count; x = !x; }
};

} // End anonymous namespace

// The restart writes what fields() lists: every member, each name once,
// the measured added masses under their prefixes; a memory filled through
// fields() and copied through fields() into a fresh one is the same
TEST(couplingMemory, fieldsListEveryMemberOnce)
{
    std::set<std::string> names;
    couplingMemory m;
    filler f{names};
    couplingMemory::fields(m, f);

    // 8 vectors, history, inContact, recentContacts, the force and torque
    // taken, and the two measurements' 13 members each
    EXPECT_EQ(f.count, 13 + 2*13);
    EXPECT_EQ(names.size(), size_t(f.count));
    EXPECT_TRUE(names.count("previousVelocity0"));
    EXPECT_TRUE(names.count("recentContacts"));
    EXPECT_TRUE(names.count("addedMassSumFa"));
    EXPECT_TRUE(names.count("addedInertiaSkip"));
    EXPECT_TRUE(names.count("takenTorque"));
    // Every member was reached: none is at its default
    const couplingMemory fresh;
    EXPECT_NE(m.innerMomentum, fresh.innerMomentum);
    EXPECT_NE(m.previousAngularVelocity0, fresh.previousAngularVelocity0);
    EXPECT_NE(m.history, fresh.history);
    EXPECT_NE(m.wasInContact, fresh.wasInContact);
    EXPECT_NE(m.recentContacts, fresh.recentContacts);
    EXPECT_NE(m.takenForce, fresh.takenForce);
    EXPECT_NE(m.addedMass.value(), fresh.addedMass.value());
    EXPECT_NE(m.addedInertia.value(true), fresh.addedInertia.value(true));
    // Nothing the list misses: the struct is the members listed (a twin
    // with them in the same order has its size)
    struct twin
    {
        vec3 v[8];
        int history;
        bool inContact;
        int recentContacts;
        vec3 taken[2];
        measuredAddedMass m[2];
    };
    EXPECT_EQ(sizeof(couplingMemory), sizeof(twin));

    // Through the list into a fresh memory: equal member for member
    std::vector<double> values;
    struct collect
    {
        std::vector<double>& v;
        void operator()(const char*, const vec3& x) { v.insert(v.end(), x.data(), x.data() + 3); }
        void operator()(const char*, double x) { v.push_back(x); }
        void operator()(const char*, int x) { v.push_back(x); }
        void operator()(const char*, bool x) { v.push_back(x); }
    };
    couplingMemory::fields(static_cast<const couplingMemory&>(m), collect{values});
    couplingMemory copy;
    size_t k = 0;
    struct restore
    {
        const std::vector<double>& v; size_t& k;
        void operator()(const char*, vec3& x) { x = vec3(v[k], v[k + 1], v[k + 2]); k += 3; }
        void operator()(const char*, double& x) { x = v[k++]; }
        void operator()(const char*, int& x) { x = int(v[k++]); }
        void operator()(const char*, bool& x) { x = v[k++] != 0; }
    };
    couplingMemory::fields(copy, restore{values, k});
    EXPECT_EQ(k, values.size());
    std::vector<double> again;
    couplingMemory::fields(static_cast<const couplingMemory&>(copy), collect{again});
    EXPECT_EQ(values, again);
}

// The body's size for the estimates: a sphere's volume, area and radius;
// a cylinder whose axis is locked (2D) per unit depth: its section, its
// perimeter and its radius, its length as the depth
TEST(rigidBody, fluidSizeIn3DAnd2D)
{
    const double a = 1e-3;
    rigidBody ball("ball", std::make_shared<sphereShape>(a), 2000);
    const fluidImpedance::bodySize s = ball.fluidSize();
    EXPECT_NEAR(s.volume, 4.0/3.0*M_PI*a*a*a, 1e-12*a*a*a);
    EXPECT_EQ(s.depth, 0);
    EXPECT_NEAR(s.circumscribedRadius, a, 1e-12);
    // The sphere's surface is triangulated: its area within the
    // triangulation's error (a few per cent at its resolution)
    EXPECT_NEAR(s.area, 4*M_PI*a*a, 0.05*4*M_PI*a*a);

    const double L = 4e-3;
    const int segments = 64;
    const auto polygon = [](double R, int n)
    {
        std::vector<Eigen::Vector2d> p;
        for (int k = 0; k < n; ++k)
        {
            p.emplace_back(R*std::cos(2*M_PI*k/n), R*std::sin(2*M_PI*k/n));
        }
        return p;
    };
    rigidBody rod
    (
        "rod",
        std::make_shared<triangleMeshShape>
        (
            primitiveMeshes::extrudedPolygon(polygon(a, segments), L), "rod"
        ),
        2000
    );
    // Placed as in its file (the body frame is its principal frame)
    rod.pose = rod.geometry->bodyInFile();
    // Translation along z and rotations about x and y locked: a 2D body
    rod.lockTranslation = Eigen::Vector3i(0, 0, 1);
    rod.lockRotation = Eigen::Vector3i(1, 1, 0);
    const fluidImpedance::bodySize r = rod.fluidSize();
    // The polygon's section, perimeter and circumradius, exactly
    const double section = 0.5*segments*a*a*std::sin(2*M_PI/segments);
    const double perimeter = 2*segments*a*std::sin(M_PI/segments);
    EXPECT_NEAR(r.depth, L, 1e-12);
    EXPECT_NEAR(r.volume, section, 1e-9*section);
    EXPECT_NEAR(r.area, perimeter, 1e-9*perimeter);
    EXPECT_NEAR(r.circumscribedRadius, a, 1e-12);
    // Unlocked: the 3D cylinder
    rod.lockTranslation.setZero();
    rod.lockRotation.setZero();
    const fluidImpedance::bodySize t = rod.fluidSize();
    EXPECT_EQ(t.depth, 0);
    EXPECT_NEAR(t.area, perimeter*L + 2*section, 1e-9*t.area);
}
