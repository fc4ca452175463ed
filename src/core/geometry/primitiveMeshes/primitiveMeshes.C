#include "primitiveMeshes.H"
#include "coreError.H"

#include <cmath>
#include <algorithm>
#include <array>
#include <map>

namespace immersedDEM
{

triangleSoup primitiveMeshes::box(const vec3& h)
{
    triangleSoup s;
    for (int i = 0; i < 8; ++i)
    {
        s.points.emplace_back
        (
            (i & 1 ? 1 : -1)*h.x(), (i & 2 ? 1 : -1)*h.y(), (i & 4 ? 1 : -1)*h.z()
        );
    }
    // Quads as corner bit patterns, listed counter-clockwise from outside
    const int quads[6][4] =
    {
        {0, 4, 6, 2}, {1, 3, 7, 5},     // -x, +x
        {0, 1, 5, 4}, {2, 6, 7, 3},     // -y, +y
        {0, 2, 3, 1}, {4, 5, 7, 6}      // -z, +z
    };
    for (const auto& q : quads)
    {
        s.faces.push_back({q[0], q[1], q[2]});
        s.faces.push_back({q[0], q[2], q[3]});
    }
    return s;
}


triangleSoup primitiveMeshes::icosphere(double radius, int levels)
{
    const double t = (1.0 + std::sqrt(5.0))/2.0;
    triangleSoup s;
    s.points =
    {
        {-1,  t,  0}, { 1,  t,  0}, {-1, -t,  0}, { 1, -t,  0},
        { 0, -1,  t}, { 0,  1,  t}, { 0, -1, -t}, { 0,  1, -t},
        { t,  0, -1}, { t,  0,  1}, {-t,  0, -1}, {-t,  0,  1}
    };
    s.faces =
    {
        {0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11},
        {1, 5, 9}, {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
        {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8}, {3, 8, 9},
        {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}
    };
    for (vec3& p : s.points) p.normalize();

    for (int l = 0; l < levels; ++l)
    {
        std::map<std::pair<int, int>, int> mid;
        auto midpoint = [&](int a, int b)
        {
            const auto k = std::make_pair(std::min(a, b), std::max(a, b));
            const auto it = mid.find(k);
            if (it != mid.end()) return it->second;
            s.points.push_back((s.points[a] + s.points[b]).normalized());
            return mid[k] = int(s.points.size()) - 1;
        };
        std::vector<triFace> faces;
        faces.reserve(4*s.faces.size());
        for (const triFace& f : s.faces)
        {
            const int ab = midpoint(f[0], f[1]);
            const int bc = midpoint(f[1], f[2]);
            const int ca = midpoint(f[2], f[0]);
            faces.push_back({f[0], ab, ca});
            faces.push_back({f[1], bc, ab});
            faces.push_back({f[2], ca, bc});
            faces.push_back({ab, bc, ca});
        }
        s.faces.swap(faces);
    }
    for (vec3& p : s.points) p *= radius;
    return s;
}


triangleSoup primitiveMeshes::torus(double R, double r, int nMajor, int nMinor)
{
    triangleSoup s;
    for (int i = 0; i < nMajor; ++i)
    {
        const double u = 2*M_PI*i/nMajor;
        for (int j = 0; j < nMinor; ++j)
        {
            const double v = 2*M_PI*j/nMinor;
            const double rho = R + r*std::cos(v);
            s.points.emplace_back(rho*std::cos(u), rho*std::sin(u), r*std::sin(v));
        }
    }
    auto id = [&](int i, int j){ return (i % nMajor)*nMinor + (j % nMinor); };
    for (int i = 0; i < nMajor; ++i)
    {
        for (int j = 0; j < nMinor; ++j)
        {
            const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
            s.faces.push_back({a, b, c});
            s.faces.push_back({a, c, d});
        }
    }
    return s;
}


namespace
{

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c)
{
    return (b - a).x()*(c - a).y() - (b - a).y()*(c - a).x();
}

// Ear clipping of a simple counter-clockwise polygon
std::vector<triFace> triangulate(const std::vector<Eigen::Vector2d>& poly)
{
    std::vector<int> idx(poly.size());
    for (size_t i = 0; i < poly.size(); ++i) idx[i] = int(i);
    std::vector<triFace> tris;
    while (idx.size() > 3)
    {
        bool clipped = false;
        const size_t n = idx.size();
        for (size_t i = 0; i < n && !clipped; ++i)
        {
            const int a = idx[(i + n - 1) % n], b = idx[i], c = idx[(i + 1) % n];
            if (cross2(poly[a], poly[b], poly[c]) <= 0) continue;    // reflex
            bool empty = true;
            for (int k : idx)
            {
                if (k == a || k == b || k == c) continue;
                if
                (
                    cross2(poly[a], poly[b], poly[k]) >= 0
                 && cross2(poly[b], poly[c], poly[k]) >= 0
                 && cross2(poly[c], poly[a], poly[k]) >= 0
                )
                {
                    empty = false;
                    break;
                }
            }
            if (empty)
            {
                tris.push_back({a, b, c});
                idx.erase(idx.begin() + long(i));
                clipped = true;
            }
        }
        if (!clipped)
        {
            throw coreError("extrudedPolygon: polygon is not simple and counter-clockwise");
        }
    }
    tris.push_back({idx[0], idx[1], idx[2]});
    return tris;
}

} // End anonymous namespace


triangleSoup primitiveMeshes::extrudedPolygon
(
    const std::vector<Eigen::Vector2d>& polygon,
    double height
)
{
    const int n = int(polygon.size());
    triangleSoup s;
    for (int z = 0; z < 2; ++z)
    {
        for (const auto& p : polygon) s.points.emplace_back(p.x(), p.y(), z*height);
    }
    for (const triFace& t : triangulate(polygon))
    {
        s.faces.push_back({t[0], t[2], t[1]});          // bottom faces -z
        s.faces.push_back({n + t[0], n + t[1], n + t[2]});  // top faces +z
    }
    for (int i = 0; i < n; ++i)
    {
        const int j = (i + 1) % n;
        s.faces.push_back({i, j, n + j});
        s.faces.push_back({i, n + j, n + i});
    }
    return s;
}


triangleSoup primitiveMeshes::hollowCylinder(double R, double r, double h, int n)
{
    if (!(R > r && r > 0 && h > 0 && n >= 3))
    {
        throw coreError("hollowCylinder: needs R > r > 0, h > 0 and n >= 3");
    }
    // Points 4i..4i+3: outer bottom, outer top, inner bottom, inner top
    triangleSoup s;
    for (int i = 0; i < n; ++i)
    {
        const double t = 2*M_PI*i/n, c = std::cos(t), z = std::sin(t);
        s.points.emplace_back(R*c, R*z, -h/2);
        s.points.emplace_back(R*c, R*z, h/2);
        s.points.emplace_back(r*c, r*z, -h/2);
        s.points.emplace_back(r*c, r*z, h/2);
    }
    for (int i = 0; i < n; ++i)
    {
        const int a = 4*i, b = 4*((i + 1) % n);
        s.faces.push_back({a, b, b + 1});               // outer side
        s.faces.push_back({a, b + 1, a + 1});
        s.faces.push_back({a + 2, a + 3, b + 3});       // inner side
        s.faces.push_back({a + 2, b + 3, b + 2});
        s.faces.push_back({a + 1, b + 1, b + 3});       // top
        s.faces.push_back({a + 1, b + 3, a + 3});
        s.faces.push_back({a, a + 2, b + 2});           // bottom
        s.faces.push_back({a, b + 2, b});
    }
    return s;
}


triangleSoup primitiveMeshes::lobed(int lobes, double c, double rl, double h, int n)
{
    if (!(lobes >= 2 && c > 0 && rl > c*std::sin(M_PI/lobes) && h > 0 && n >= 3*lobes))
    {
        throw coreError
        (
            "lobed: needs lobes >= 2, overlapping lobes (rl > c sin(pi/lobes)),"
            " h > 0 and n >= 3 lobes"
        );
    }
    // The outline: along each direction, the farthest point of the union
    // of the lobe circles (star-shaped about the axis)
    std::vector<Eigen::Vector2d> outline;
    for (int i = 0; i < n; ++i)
    {
        const double t = 2*M_PI*i/n;
        const Eigen::Vector2d u(std::cos(t), std::sin(t));
        double far = 0;
        for (int k = 0; k < lobes; ++k)
        {
            const double tk = 2*M_PI*k/lobes;
            const Eigen::Vector2d o = c*Eigen::Vector2d(std::cos(tk), std::sin(tk));
            // |s u - o| = rl, the larger root
            const double b = u.dot(o), disc = b*b - o.squaredNorm() + rl*rl;
            if (disc >= 0) far = std::max(far, b + std::sqrt(disc));
        }
        outline.push_back(far*u);
    }
    triangleSoup s = extrudedPolygon(outline, h);
    transform(s, mat3::Identity(), vec3(0, 0, -h/2));
    return s;
}


void primitiveMeshes::transform(triangleSoup& soup, const mat3& R, const vec3& t)
{
    for (vec3& p : soup.points) p = R*p + t;
}

triangleSoup primitiveMeshes::openBox(const vec3& lo, const vec3& hi, int n)
{
    n = std::max(1, n);
    triangleSoup s;
    // Points by their lattice position (i, j, k) in 0..n, shared by sides
    std::map<std::array<int, 3>, int> id;
    const vec3 e = hi - lo;
    auto point = [&](const std::array<int, 3>& ijk)
    {
        const auto it = id.find(ijk);
        if (it != id.end()) return it->second;
        const int k = int(s.points.size());
        s.points.push_back(lo + vec3(e.x()*ijk[0]/n, e.y()*ijk[1]/n, e.z()*ijk[2]/n));
        id.emplace(ijk, k);
        return k;
    };
    // A side: axis 'a' fixed at index 'at'; u, v the other axes, ordered
    // so that u x v points into the box
    auto side = [&](int a, int at, int u, int v)
    {
        for (int i = 0; i < n; ++i)
        {
            for (int j = 0; j < n; ++j)
            {
                auto p = [&](int di, int dj)
                {
                    std::array<int, 3> ijk;
                    ijk[a] = at;
                    ijk[u] = i + di;
                    ijk[v] = j + dj;
                    return point(ijk);
                };
                const int p00 = p(0, 0), p10 = p(1, 0), p11 = p(1, 1), p01 = p(0, 1);
                s.faces.push_back({p00, p10, p11});
                s.faces.push_back({p00, p11, p01});
            }
        }
    };
    side(2, 0, 0, 1);   // floor: x, y -> +z
    side(0, 0, 1, 2);   // x = lo: y, z -> +x
    side(0, n, 2, 1);   // x = hi: z, y -> -x
    side(1, 0, 2, 0);   // y = lo: z, x -> +y
    side(1, n, 0, 2);   // y = hi: x, z -> -y
    return s;
}

} // End namespace immersedDEM
