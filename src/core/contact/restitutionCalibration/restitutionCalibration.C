#include "restitutionCalibration.H"
#include "coreError.H"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <mutex>

namespace immersedDEM
{

namespace
{

constexpr int nQ = 9;       // q = 1, 1.25, ..., 3

double qOf(int i) { return 1 + 0.25*i; }

} // End anonymous namespace


double restitutionCalibration::restitution(double c, double q)
{
    // x(0) = 0, x'(0) = 1; RK4 until x returns to 0, the last step cut at
    // the crossing. The collision lasts O(1): 1e-3 steps resolve e to
    // better than 1e-6.
    double x = 0, v = 1;
    const double dt = 1e-3;
    auto accel = [&](double x, double v)
    {
        if (x <= 0) return 0.0;
        const double f = std::pow(x, q) + c*std::sqrt(q*std::pow(x, q - 1))*v;
        return -std::max(0.0, f);
    };
    for (int n = 0; n < 100000000; ++n)
    {
        const double k1x = v, k1v = accel(x, v);
        const double k2x = v + 0.5*dt*k1v, k2v = accel(x + 0.5*dt*k1x, v + 0.5*dt*k1v);
        const double k3x = v + 0.5*dt*k2v, k3v = accel(x + 0.5*dt*k2x, v + 0.5*dt*k2v);
        const double k4x = v + dt*k3v, k4v = accel(x + dt*k3x, v + dt*k3v);
        const double xNew = x + dt/6*(k1x + 2*k2x + 2*k3x + k4x);
        const double vNew = v + dt/6*(k1v + 2*k2v + 2*k3v + k4v);
        if (n > 0 && xNew <= 0)
        {
            // Linear in the last step: the speed at the crossing
            const double t = x/(x - xNew);
            return -(v + t*(vNew - v));
        }
        if (vNew >= 0 && n > 0 && xNew <= x && vNew == v)
        {
            break;      // stuck: no rebound
        }
        x = xNew;
        v = vNew;
    }
    return 0;
}


double restitutionCalibration::damping(double e, double q)
{
    if (!(e > 0 && e <= 1))
    {
        throw coreError("restitution must be in (0, 1], not " + std::to_string(e));
    }
    if (e == 1)
    {
        return 0;
    }

    // The last (e, q) asked on this thread and its answer: a law asks the
    // same for every contact of a material pair (no lock and no map
    // search per contact)
    thread_local double lastE = -1, lastQ = 0, lastC = 0;
    if (e == lastE && q == lastQ)
    {
        return lastC;
    }

    // Each (e, q node) bisected when first asked: a law asks one q (Hertz
    // 1.5, a flat face 1, a sphere 2), so the two nodes about it, not all
    // nine (all nine were bisected at the first contact of a pour)
    const double qc = std::min(3.0, std::max(1.0, q));
    const int node = std::min(nQ - 2, int((qc - 1)/0.25));
    static std::mutex mutex;
    static std::map<double, std::array<double, nQ>> table;
    std::array<double, nQ> cs;
    {
        std::lock_guard<std::mutex> lock(mutex);
        auto it = table.find(e);
        if (it == table.end())
        {
            std::array<double, nQ> row;
            row.fill(-1);
            it = table.emplace(e, row).first;
        }
        for (int i = node; i <= node + 1; ++i)
        {
            if (it->second[i] >= 0) continue;
            // e falls monotonically with c: bisect
            double lo = 0, hi = 1;
            while (restitution(hi, qOf(i)) > e) hi *= 2;
            for (int k = 0; k < 32; ++k)
            {
                const double mid = 0.5*(lo + hi);
                (restitution(mid, qOf(i)) > e ? lo : hi) = mid;
            }
            it->second[i] = 0.5*(lo + hi);
        }
        cs = it->second;
    }
    const int i = node;
    const double t = (qc - qOf(i))/0.25;
    lastE = e;
    lastQ = q;
    lastC = (1 - t)*cs[i] + t*cs[i + 1];
    return lastC;
}

} // End namespace immersedDEM
