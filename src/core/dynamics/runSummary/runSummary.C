#include "runSummary.H"

#include <algorithm>
#include <cstdio>
#include <sstream>

namespace immersedDEM
{

void runSummary::track(const demSolver& dem)
{
    for (const auto& c : dem.contacts())
    {
        if (c.region.volume > maxVolume_)
        {
            const auto& A = dem.bodies()[c.a];
            const auto& B = dem.bodies()[c.b];
            maxVolume_ = c.region.volume;
            maxVolumeTime_ = dem.time();
            maxVolumePair_ = A.name + "-" + B.name;
            const double V = dem.smallerVolume(c);
            maxVolumeFraction_ = V > 0 ? maxVolume_/V : 0;
        }
    }
    for (size_t i = 0; i < dem.bodies().size(); ++i)
    {
        if (dem.isWall(int(i))) continue;
        const double v = dem.bodies()[i].velocity.norm();
        if (v > maxSpeed_)
        {
            maxSpeed_ = v;
            maxSpeedTime_ = dem.time();
            maxSpeedBody_ = dem.bodies()[i].name;
        }
    }
}


void runSummary::demParts(const demSolver& dem, double demSeconds, seconds& s)
{
    const auto& w = dem.work();
    s.detection = w.searchSeconds;
    s.lubrication = w.lubricationSeconds;
    s.geometry = std::max(0.0, w.contactSeconds - w.searchSeconds - w.lubricationSeconds);
    s.integration = std::max(0.0, demSeconds - w.contactSeconds);
}


std::string runSummary::text
(
    const seconds& s,
    double simulated,
    long steps,
    bool coupled
) const
{
    std::ostringstream os;
    char buf[256];
    auto line = [&](const char* what, double t)
    {
        std::snprintf
        (
            buf, sizeof(buf), "    %-36s %10.3f  %5.1f%%\n",
            what, t, s.total > 0 ? 100*t/s.total : 0.0
        );
        os << buf;
    };
    os << "Summary (wall-clock seconds, share of the run)\n";
    line("reading, mesh and insertion", s.setup);
    if (coupled) line("projection", s.projection);
    line("contact detection", s.detection);
    line("contact geometry and laws", s.geometry);
    line("lubrication", s.lubrication);
    line("integration, insertion, removal", s.integration);
    if (coupled) line("forcing and fluid loads", s.forcing);
    line("output", s.output);
    const double plugin = s.setup + s.projection + s.detection + s.geometry
        + s.lubrication + s.integration + s.forcing + s.output;
    if (coupled)
    {
        line("immersedDEM (all of the above)", plugin);
        line("fluid solver and the rest", std::max(0.0, s.total - plugin));
    }
    line("total", s.total);
    std::snprintf
    (
        buf, sizeof(buf),
        "    simulated %g s in %ld DEM steps: %.4g DEM steps/s, %.4g wall s"
        " per simulated s\n",
        simulated, steps, s.total > 0 ? steps/s.total : 0.0,
        simulated > 0 ? s.total/simulated : 0.0
    );
    os << buf;
    std::snprintf
    (
        buf, sizeof(buf),
        "    largest overlap %g m3 (%.3g%% of the smaller body), %s at t = %g\n",
        maxVolume_, 100*maxVolumeFraction_, maxVolumePair_.c_str(), maxVolumeTime_
    );
    os << buf;
    std::snprintf
    (
        buf, sizeof(buf), "    largest speed %g m/s, %s at t = %g",
        maxSpeed_, maxSpeedBody_.c_str(), maxSpeedTime_
    );
    os << buf;
    return os.str();
}

} // End namespace immersedDEM
