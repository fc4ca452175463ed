#include "bodyRemoval.H"

namespace immersedDEM
{

std::vector<int> bodyRemoval::bodiesIn
(
    const demSolver& dem, const std::vector<insertionRegion>& regions
)
{
    std::vector<int> found;
    const auto& bodies = dem.bodies();
    for (size_t i = 0; i < bodies.size(); ++i)
    {
        if (dem.isWall(int(i))) continue;
        const vec3& x = bodies[i].pose.position();
        for (const insertionRegion& r : regions)
        {
            if (r.contains(x, 0))
            {
                found.push_back(int(i));
                break;
            }
        }
    }
    return found;
}

}
