#include "demOutput.H"
#include "coreError.H"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <sstream>

namespace immersedDEM
{

namespace fs = std::filesystem;

namespace
{

// Opens dir/name.dat, or dir/name_<startTime>.dat when the first exists
// (an earlier run's: OpenFOAM's writeFile convention), truncated, with the
// header line
std::string openTable
(
    std::ofstream& os,
    const std::string& dir,
    const std::string& name,
    const std::string& startTimeName,
    const std::string& header
)
{
    std::string file = dir + "/" + name + ".dat";
    if (fs::exists(file))
    {
        file = dir + "/" + name + "_" + startTimeName + ".dat";
    }
    os.open(file, std::ios::trunc);
    if (!os.good())
    {
        throw coreError("Cannot open \"" + file + "\" for writing");
    }
    os.precision(10);
    os << header << '\n';
    os.flush();
    return file;
}


void writeAtomically(const std::string& file, const std::string& text)
{
    const std::string tmp = file + ".tmp";
    {
        std::ofstream os(tmp);
        os << text;
        if (!os.good())
        {
            throw coreError("Cannot write \"" + file + "\"");
        }
    }
    fs::rename(tmp, file);
}

std::string timeName(double t)
{
    std::ostringstream os;
    os.precision(8);
    os << t;
    return os.str();
}

} // End anonymous namespace


const std::vector<std::string>& demOutput::bodyColumns()
{
    static const std::vector<std::string> c
    {
        "time", "body", "x", "y", "z", "qw", "qx", "qy", "qz",
        "vx", "vy", "vz", "wx", "wy", "wz",
        "Fx", "Fy", "Fz", "Fcx", "Fcy", "Fcz", "Ffx", "Ffy", "Ffz",
        "Tx", "Ty", "Tz", "Flx", "Fly", "Flz", "xu", "yu", "zu", "m", "V"
    };
    return c;
}


demOutput::demOutput(const std::string& dir, const std::string& startTimeName)
:
    dir_(dir)
{
    std::error_code ec;
    fs::create_directories(dir_, ec);
    if (ec)
    {
        throw coreError("Cannot create the output folder \"" + dir_ + "\": " + ec.message());
    }
    std::string header = "#";
    for (const std::string& c : bodyColumns()) header += " " + c;
    bodiesFile_ = openTable(bodies_, dir_, "bodies", startTimeName, header);
    contactsFile_ = openTable
    (
        contacts_, dir_, "contacts", startTimeName,
        "# time bodyA bodyB volume Fn nx ny nz px py pz Ftx Fty Ftz"
    );
}


void demOutput::writeBodies(double time, const demSolver& dem)
{
    const auto& bodies = dem.bodies();
    for (size_t i = 0; i < bodies.size(); ++i)
    {
        if (dem.isWall(int(i))) continue;
        const rigidBody& b = bodies[i];
        const vec3& x = b.pose.position();
        const quat& q = b.pose.orientation();
        const vec3 F = b.totalForce();
        const vec3 T = b.totalTorque();
        auto v3 = [&](const vec3& v){ bodies_ << ' ' << v.x() << ' ' << v.y() << ' ' << v.z(); };
        bodies_ << time << ' ' << b.name;
        v3(x);
        bodies_ << ' ' << q.w() << ' ' << q.x() << ' ' << q.y() << ' ' << q.z();
        v3(b.velocity);
        v3(b.angularVelocity);
        v3(F);
        v3(b.contactForce);
        v3(b.appliedFluidForce(dem.time()));
        v3(T);
        v3(b.lubricationForce);
        v3(x + b.periodicOffset);
        bodies_ << ' ' << b.mass() << ' ' << b.geometry->volume() << '\n';
    }
    bodies_.flush();
}


void demOutput::writeContacts(double time, const demSolver& dem)
{
    const auto& bodies = dem.bodies();
    for (const contactRecord& c : dem.contacts())
    {
        const vec3& n = c.region.normal;
        const vec3& p = c.region.point;
        const vec3& ft = c.force.tangentialForce;
        contacts_ << time << ' ' << bodies[c.a].name << ' ' << bodies[c.b].name << ' '
            << c.region.volume << ' ' << c.force.normalForce << ' '
            << n.x() << ' ' << n.y() << ' ' << n.z() << ' '
            << p.x() << ' ' << p.y() << ' ' << p.z() << ' '
            << ft.x() << ' ' << ft.y() << ' ' << ft.z() << '\n';
    }
    contacts_.flush();
}


void demOutput::writeVTK(double time, const demSolver& dem)
{
    const std::string vtkDir = dir_ + "/VTK";
    fs::create_directories(vtkDir);

    std::vector<vec3> points;
    std::vector<std::array<int, 3>> faces;
    std::vector<int> bodyOfFace;
    const auto& bodies = dem.bodies();
    for (size_t i = 0; i < bodies.size(); ++i)
    {
        if (dem.isWall(int(i))) continue;
        const triangleSoup s = bodies[i].geometry->surface();
        const int offset = int(points.size());
        for (const vec3& p : s.points) points.push_back(bodies[i].pose.toWorld(p));
        for (const triFace& f : s.faces)
        {
            faces.push_back({f[0] + offset, f[1] + offset, f[2] + offset});
            bodyOfFace.push_back(int(dem.identity(int(i))));
        }
    }

    std::ostringstream os;
    os.precision(9);
    os << "# vtk DataFile Version 3.0\nimmersedDEM bodies at time " << time
       << "\nASCII\nDATASET POLYDATA\nPOINTS " << points.size() << " double\n";
    for (const vec3& p : points) os << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
    os << "POLYGONS " << faces.size() << ' ' << 4*faces.size() << '\n';
    for (const auto& f : faces) os << "3 " << f[0] << ' ' << f[1] << ' ' << f[2] << '\n';
    os << "CELL_DATA " << faces.size() << "\nSCALARS body int 1\nLOOKUP_TABLE default\n";
    for (int b : bodyOfFace) os << b << '\n';
    const std::string name = "bodies_" + timeName(time) + ".vtk";
    writeAtomically(vtkDir + "/" + name, os.str());

    // The series lists the files this run wrote (a rerun over an older
    // run's folder does not mix the two)
    const auto it = std::find_if
    (
        vtkFiles_.begin(), vtkFiles_.end(),
        [&](const std::pair<double, std::string>& f){ return f.second == name; }
    );
    if (it == vtkFiles_.end())
    {
        vtkFiles_.emplace_back(time, name);
        std::sort(vtkFiles_.begin(), vtkFiles_.end());
    }
    const auto& files = vtkFiles_;
    std::ostringstream ss;
    ss.precision(12);
    ss << "{\n  \"file-series-version\" : \"1.0\",\n  \"files\" : [\n";
    for (size_t i = 0; i < files.size(); ++i)
    {
        ss << "    { \"name\" : \"" << files[i].second << "\", \"time\" : " << files[i].first
           << " }" << (i + 1 < files.size() ? "," : "") << '\n';
    }
    ss << "  ]\n}\n";
    writeAtomically(vtkDir + "/bodies.vtk.series", ss.str());
}

} // End namespace immersedDEM
