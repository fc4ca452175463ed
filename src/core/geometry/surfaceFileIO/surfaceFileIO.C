#include "surfaceFileIO.H"
#include "coreError.H"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace immersedDEM
{

namespace
{

std::string lowerExtension(const std::string& fileName)
{
    const auto dot = fileName.find_last_of('.');
    const auto slash = fileName.find_last_of('/');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
    {
        return "";
    }
    std::string ext = fileName.substr(dot + 1);
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c){ return std::tolower(c); });
    return ext;
}

void notADirectory(const std::string& fileName)
{
    std::error_code ec;
    if (std::filesystem::is_directory(fileName, ec))
    {
        throw coreError
        (
            "Surface file \"" + fileName + "\" is a directory, not a file"
        );
    }
}

std::ifstream openForReading(const std::string& fileName, std::ios::openmode mode)
{
    notADirectory(fileName);
    std::ifstream is(fileName, mode);
    if (!is.good())
    {
        throw coreError
        (
            "Surface file \"" + fileName + "\" cannot be opened: "
          + std::string(std::strerror(errno))
        );
    }
    return is;
}

[[noreturn]] void malformed(const std::string& fileName, long line, const std::string& what)
{
    std::ostringstream os;
    os << "Surface file \"" << fileName << "\", line " << line << ": " << what;
    throw coreError(os.str());
}

void requireTriangles(const std::string& fileName, const triangleSoup& soup)
{
    if (soup.faces.empty())
    {
        throw coreError("Surface file \"" + fileName + "\" contains no triangles");
    }
}

bool finite(const vec3& p)
{
    return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z());
}

triangleSoup readBinarySTL(const std::string& fileName, std::ifstream& is, std::uint32_t n)
{
    triangleSoup soup;
    soup.points.reserve(3*n);
    soup.faces.reserve(n);
    is.seekg(84);
    char rec[50];
    for (std::uint32_t i = 0; i < n; ++i)
    {
        if (!is.read(rec, 50))
        {
            throw coreError("Surface file \"" + fileName + "\": binary STL truncated");
        }
        triFace f;
        for (int k = 0; k < 3; ++k)
        {
            float xyz[3];
            std::memcpy(xyz, rec + 12 + 12*k, 12);
            const vec3 p(xyz[0], xyz[1], xyz[2]);
            if (!finite(p))
            {
                throw coreError
                (
                    "Surface file \"" + fileName + "\": triangle "
                  + std::to_string(i) + " has a non-finite coordinate"
                );
            }
            f[k] = int(soup.points.size());
            soup.points.push_back(p);
        }
        soup.faces.push_back(f);
    }
    return soup;
}

triangleSoup readAsciiSTL(const std::string& fileName, std::ifstream& is)
{
    triangleSoup soup;
    std::string line;
    long lineNo = 0;
    int nInFacet = -1;      // -1: outside a facet
    triFace f{};

    while (std::getline(is, line))
    {
        ++lineNo;
        std::istringstream ls(line);
        std::string key;
        if (!(ls >> key))
        {
            continue;
        }
        std::transform(key.begin(), key.end(), key.begin(), [](unsigned char c){ return std::tolower(c); });

        if (key == "facet")
        {
            if (nInFacet != -1)
            {
                malformed(fileName, lineNo, "'facet' inside a facet");
            }
            nInFacet = 0;
        }
        else if (key == "vertex")
        {
            if (nInFacet < 0 || nInFacet > 2)
            {
                malformed(fileName, lineNo, "'vertex' outside a facet or more than 3 in a facet");
            }
            vec3 p;
            std::string sx, sy, sz;
            if (!(ls >> sx >> sy >> sz))
            {
                malformed(fileName, lineNo, "'vertex' needs three numbers");
            }
            try
            {
                size_t used = 0;
                p.x() = std::stod(sx, &used); if (used != sx.size()) throw 0;
                p.y() = std::stod(sy, &used); if (used != sy.size()) throw 0;
                p.z() = std::stod(sz, &used); if (used != sz.size()) throw 0;
            }
            catch (...)
            {
                malformed(fileName, lineNo, "cannot read the numbers of 'vertex'");
            }
            if (!finite(p))
            {
                malformed(fileName, lineNo, "non-finite coordinate");
            }
            f[nInFacet++] = int(soup.points.size());
            soup.points.push_back(p);
        }
        else if (key == "endfacet")
        {
            if (nInFacet != 3)
            {
                malformed(fileName, lineNo, "facet does not have 3 vertices");
            }
            soup.faces.push_back(f);
            nInFacet = -1;
        }
        else if
        (
            key != "solid" && key != "endsolid" && key != "outer"
         && key != "endloop"
        )
        {
            malformed(fileName, lineNo, "unexpected '" + key + "'");
        }
    }
    if (nInFacet != -1)
    {
        malformed(fileName, lineNo, "file ends inside a facet");
    }
    return soup;
}

} // End anonymous namespace


void surfaceFileIO::mergeCoincidentPoints(triangleSoup& soup)
{
    std::map<std::array<double, 3>, int> index;
    std::vector<vec3> merged;
    std::vector<int> newIndex(soup.points.size());
    for (size_t i = 0; i < soup.points.size(); ++i)
    {
        const vec3& p = soup.points[i];
        const auto ins = index.emplace(std::array<double, 3>{p.x(), p.y(), p.z()}, int(merged.size()));
        if (ins.second)
        {
            merged.push_back(p);
        }
        newIndex[i] = ins.first->second;
    }
    for (triFace& f : soup.faces)
    {
        for (int& v : f)
        {
            v = newIndex[v];
        }
    }
    soup.points.swap(merged);
}


triangleSoup surfaceFileIO::readSTL(const std::string& fileName)
{
    std::ifstream is = openForReading(fileName, std::ios::binary);
    is.seekg(0, std::ios::end);
    const std::streamoff size = is.tellg();
    is.seekg(0);

    triangleSoup soup;
    bool binary = false;
    std::uint32_t n = 0;
    if (size >= 84)
    {
        char header[84];
        is.read(header, 84);
        std::memcpy(&n, header + 80, 4);
        binary = (std::streamoff(84) + std::streamoff(50)*n == size);
    }
    if (binary)
    {
        soup = readBinarySTL(fileName, is, n);
    }
    else
    {
        is.clear();
        is.seekg(0);
        std::string first;
        is >> first;
        std::transform(first.begin(), first.end(), first.begin(), [](unsigned char c){ return std::tolower(c); });
        if (first != "solid")
        {
            throw coreError
            (
                "Surface file \"" + fileName + "\" is neither ASCII STL (starting"
                " with 'solid') nor binary STL (size 84 + 50 x triangles)"
            );
        }
        is.clear();
        is.seekg(0);
        soup = readAsciiSTL(fileName, is);
    }
    requireTriangles(fileName, soup);
    mergeCoincidentPoints(soup);
    return soup;
}


triangleSoup surfaceFileIO::readOBJ(const std::string& fileName)
{
    std::ifstream is = openForReading(fileName, std::ios::in);
    triangleSoup soup;
    std::string line;
    long lineNo = 0;
    while (std::getline(is, line))
    {
        ++lineNo;
        std::istringstream ls(line);
        std::string key;
        if (!(ls >> key) || key[0] == '#')
        {
            continue;
        }
        if (key == "v")
        {
            vec3 p;
            if (!(ls >> p.x() >> p.y() >> p.z()) || !finite(p))
            {
                malformed(fileName, lineNo, "'v' needs three finite numbers");
            }
            soup.points.push_back(p);
        }
        else if (key == "f")
        {
            std::vector<int> poly;
            std::string tok;
            while (ls >> tok)
            {
                long idx = 0;
                try
                {
                    idx = std::stol(tok.substr(0, tok.find('/')));
                }
                catch (...)
                {
                    malformed(fileName, lineNo, "cannot read vertex index '" + tok + "'");
                }
                // OBJ is 1-based; negative indices count back from the end
                const long n = long(soup.points.size());
                const long i = idx > 0 ? idx - 1 : n + idx;
                if (idx == 0 || i < 0 || i >= n)
                {
                    malformed(fileName, lineNo, "vertex index " + tok + " out of range");
                }
                poly.push_back(int(i));
            }
            if (poly.size() < 3)
            {
                malformed(fileName, lineNo, "a face needs at least 3 vertices");
            }
            for (size_t k = 1; k + 1 < poly.size(); ++k)
            {
                soup.faces.push_back(triFace{poly[0], poly[k], poly[k + 1]});
            }
        }
        // Other records (vn, vt, g, o, s, usemtl, mtllib) carry no geometry
    }
    requireTriangles(fileName, soup);
    mergeCoincidentPoints(soup);
    return soup;
}


triangleSoup surfaceFileIO::read(const std::string& fileName)
{
    notADirectory(fileName);
    const std::string ext = lowerExtension(fileName);
    if (ext == "stl")
    {
        return readSTL(fileName);
    }
    if (ext == "obj")
    {
        return readOBJ(fileName);
    }
    throw coreError
    (
        "Surface file \"" + fileName + "\": unknown extension '" + ext
      + "'; valid extensions are .stl and .obj"
    );
}


void surfaceFileIO::write(const std::string& fileName, const triangleSoup& soup, bool ascii)
{
    const std::string ext = lowerExtension(fileName);
    // Refuse an unknown extension before creating the temporary
    if (ext != "obj" && ext != "stl")
    {
        throw coreError
        (
            "Surface file \"" + fileName + "\": unknown extension '" + ext
          + "'; valid extensions are .stl and .obj"
        );
    }
    // Write a temporary and rename: a reader never sees a half-written file
    const std::string tmp = fileName + ".tmp";
    {
        std::ofstream os(tmp, std::ios::binary);
        if (!os.good())
        {
            throw coreError("Surface file \"" + fileName + "\" cannot be written");
        }
        os.precision(17);
        if (ext == "obj")
        {
            for (const vec3& p : soup.points)
            {
                os << "v " << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
            }
            for (const triFace& f : soup.faces)
            {
                os << "f " << f[0] + 1 << ' ' << f[1] + 1 << ' ' << f[2] + 1 << '\n';
            }
        }
        else if (ext == "stl" && ascii)
        {
            os << "solid immersedDEM\n";
            for (const triFace& f : soup.faces)
            {
                const vec3& a = soup.points[f[0]];
                const vec3& b = soup.points[f[1]];
                const vec3& c = soup.points[f[2]];
                const vec3 n = (b - a).cross(c - a).normalized();
                os << "facet normal " << n.x() << ' ' << n.y() << ' ' << n.z() << "\n outer loop\n";
                for (const vec3* p : {&a, &b, &c})
                {
                    os << "  vertex " << p->x() << ' ' << p->y() << ' ' << p->z() << '\n';
                }
                os << " endloop\nendfacet\n";
            }
            os << "endsolid immersedDEM\n";
        }
        else if (ext == "stl")
        {
            char header[80] = "binary STL written by immersedDEM";
            os.write(header, 80);
            const std::uint32_t n = std::uint32_t(soup.faces.size());
            os.write(reinterpret_cast<const char*>(&n), 4);
            for (const triFace& f : soup.faces)
            {
                const vec3& a = soup.points[f[0]];
                const vec3& b = soup.points[f[1]];
                const vec3& c = soup.points[f[2]];
                const vec3 nrm = (b - a).cross(c - a).normalized();
                float buf[12];
                for (int k = 0; k < 3; ++k)
                {
                    buf[k] = float(nrm[k]);
                    buf[3 + k] = float(a[k]);
                    buf[6 + k] = float(b[k]);
                    buf[9 + k] = float(c[k]);
                }
                os.write(reinterpret_cast<const char*>(buf), 48);
                const std::uint16_t attr = 0;
                os.write(reinterpret_cast<const char*>(&attr), 2);
            }
        }
        else
        {
            throw coreError
            (
                "Surface file \"" + fileName + "\": unknown extension '" + ext
              + "'; valid extensions are .stl and .obj"
            );
        }
        if (!os.good())
        {
            throw coreError("Surface file \"" + fileName + "\": write failed");
        }
    }
    if (std::rename(tmp.c_str(), fileName.c_str()) != 0)
    {
        throw coreError("Surface file \"" + fileName + "\": cannot rename " + tmp);
    }
}

} // End namespace immersedDEM
