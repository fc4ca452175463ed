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

void openTable(std::ofstream& os, const std::string& file, const std::string& header)
{
    const bool fresh = !fs::exists(file) || fs::file_size(file) == 0;
    os.open(file, std::ios::app);
    if (!os.good())
    {
        throw coreError("Cannot open \"" + file + "\" for writing");
    }
    os.precision(10);
    if (fresh)
    {
        os << header << '\n';
        os.flush();
    }
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
        "Tx", "Ty", "Tz"
    };
    return c;
}


demOutput::demOutput(const std::string& dir)
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
    openTable(bodies_, dir_ + "/bodies.dat", header);
    openTable
    (
        contacts_, dir_ + "/contacts.dat",
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
        bodies_ << '\n';
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
            bodyOfFace.push_back(int(i));
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

    // The series lists every file present (it survives restarts)
    std::vector<std::pair<double, std::string>> files;
    for (const auto& e : fs::directory_iterator(vtkDir))
    {
        const std::string f = e.path().filename().string();
        if (f.rfind("bodies_", 0) == 0 && f.size() > 11 && f.substr(f.size() - 4) == ".vtk")
        {
            try
            {
                files.emplace_back(std::stod(f.substr(7, f.size() - 11)), f);
            }
            catch (...)
            {}
        }
    }
    std::sort(files.begin(), files.end());
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
