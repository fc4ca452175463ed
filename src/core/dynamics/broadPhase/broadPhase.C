#include "broadPhase.H"
#include "halfSpaceShape.H"

#include <algorithm>
#include <array>
#include <cmath>

namespace immersedDEM
{

broadPhase::pairList broadPhase::gridPairs
(
    const std::vector<axisAlignedBox>& box, const std::vector<int>& others
)
{
    double cell = 0;
    for (const int i : others)
    {
        cell = std::max(cell, box[i].span().maxCoeff());
    }
    std::vector<std::pair<int, int>> pairs;
    if (!(cell > 0))
    {
        return pairs;
    }
    // A uniform grid of cells as large as the largest box, so a box spans
    // at most 2 cells per axis. A pair is tested in the cell holding the
    // lower corner of the two boxes' intersection only, so it is found once.
    using key = std::array<long, 3>;
    auto index = [cell](const vec3& p)
    {
        return key
        {
            long(std::floor(p.x()/cell)), long(std::floor(p.y()/cell)),
            long(std::floor(p.z()/cell))
        };
    };
    // (cell, body) entries sorted by cell: the bodies of a cell are a run
    std::vector<std::pair<key, int>> entries;
    entries.reserve(8*others.size());
    for (const int i : others)
    {
        const key lo = index(box[i].min), hi = index(box[i].max);
        for (long x = lo[0]; x <= hi[0]; ++x)
            for (long y = lo[1]; y <= hi[1]; ++y)
                for (long z = lo[2]; z <= hi[2]; ++z)
                    entries.emplace_back(key{x, y, z}, i);
    }
    std::sort(entries.begin(), entries.end());
    for (size_t first = 0; first < entries.size();)
    {
        size_t last = first;
        while (last < entries.size() && entries[last].first == entries[first].first) ++last;
        for (size_t s = first; s < last; ++s)
        {
            for (size_t t = s + 1; t < last; ++t)
            {
                const int i = entries[s].second, j = entries[t].second;
                if (!box[i].overlaps(box[j])) continue;
                if (index(box[i].min.cwiseMax(box[j].min)) != entries[first].first) continue;
                pairs.emplace_back(std::min(i, j), std::max(i, j));
            }
        }
        first = last;
    }
    std::sort(pairs.begin(), pairs.end());
    return pairs;
}


broadPhase::pairList broadPhase::gridPairs
(
    const std::vector<axisAlignedBox>& box, const std::vector<int>& others,
    const periodicBox& periodic
)
{
    if (!periodic.active())
    {
        return gridPairs(box, others);
    }
    // Each box moved by whole periods so that its centre is in the primary
    // cell, and its images that meet the cell: two boxes that meet through
    // some images meet, moved together, at a point of the primary cell, so
    // their images there are both listed
    std::vector<axisAlignedBox> images;
    std::vector<int> of;
    for (const int i : others)
    {
        vec3 c = 0.5*(box[i].min + box[i].max);
        const vec3 c0 = c;
        periodic.wrap(c);
        const vec3 w = c - c0;
        const axisAlignedBox moved(box[i].min + w, box[i].max + w);
        for (const vec3& s : periodic.imageShifts(moved))
        {
            images.emplace_back(moved.min + s, moved.max + s);
            of.push_back(i);
        }
    }
    std::vector<int> all(images.size());
    for (size_t k = 0; k < all.size(); ++k) all[k] = int(k);
    pairList pairs;
    for (const auto& p : gridPairs(images, all))
    {
        const int i = of[p.first], j = of[p.second];
        if (i != j) pairs.emplace_back(std::min(i, j), std::max(i, j));
    }
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    return pairs;
}


bool broadPhase::imagesOverlap
(
    const axisAlignedBox& a, const axisAlignedBox& b, const periodicBox& periodic
)
{
    if (!periodic.active()) return a.overlaps(b);
    const vec3 s =
        periodic.nearestShift(0.5*(a.min + a.max), 0.5*(b.min + b.max));
    return a.overlaps(axisAlignedBox(b.min + s, b.max + s));
}


void broadPhase::refresh
(
    const std::vector<axisAlignedBox>& box, const std::vector<int>& others,
    double cell, const periodicBox& periodic, demCounters& work
)
{
    // The neighbour list: pairs of bodies whose boxes, grown by a skin,
    // overlap. Kept while every box stays inside its grown box of the last
    // build, so that any two boxes that overlap now are in it
    const size_t n = box.size();
    bool valid = listBox_.size() == n;
    for (size_t k = 0; valid && k < others.size(); ++k)
    {
        const int i = others[k];
        valid =
            (box[i].min.array() >= listBox_[i].min.array()).all()
         && (box[i].max.array() <= listBox_[i].max.array()).all();
    }
    if (!valid)
    {
        const double skin = 0.1*cell;
        listBox_.assign(n, axisAlignedBox());
        for (const int i : others)
        {
            listBox_[i] = box[i].inflated(skin);
        }
        neighbours_ = gridPairs(listBox_, others, periodic);
        ++builds_;
        ++work.broadPhaseBuilds;
    }
}


broadPhase::pairList broadPhase::candidates
(
    const std::vector<rigidBody>& bodies, const std::vector<char>& isWall,
    const periodicBox& periodic, double margin, double dropBeyond,
    const std::function<bool(const std::pair<int, int>&)>& carried,
    demCounters& work
)
{
    const int n = int(bodies.size());
    std::vector<axisAlignedBox>& box = boxes_;
    box.resize(n);
    std::vector<int> walls, others;
    double cell = 0;
    const bool lub = margin > 0;
    // Each body's centre, bounding radius and whether it moves, compact:
    // the pair loops below read these, not the bodies
    balls_.resize(n);
    for (int i = 0; i < n; ++i)
    {
        const rigidBody& b = bodies[i];
        box[i] = b.geometry->worldBox(b.pose);
        if (margin > 0) box[i] = box[i].inflated(margin);
        balls_[i].centre = b.pose.position();
        balls_[i].radius = b.geometry->boundingRadius();
        // (a prescribed one too when lubricating: its film is output)
        balls_[i].moves = b.dynamic() || (lub && b.motion != motionType::fixed);
        if (isWall[i])
        {
            walls.push_back(i);
        }
        else
        {
            others.push_back(i);
            cell = std::max(cell, box[i].span().maxCoeff());
        }
    }

    refresh(box, others, cell, periodic, work);

    std::vector<std::pair<int, int>> pairs;
    pairs.reserve(neighbours_.size() + walls.size()*others.size());

    // Walls (few, large) against every body that can move
    for (const int w : walls)
    {
        const bool plane = shapeAs<halfSpaceShape>(*bodies[w].geometry) != nullptr;
        const vec3 n = bodies[w].pose.vectorToWorld(vec3::UnitZ());
        const vec3& p0 = bodies[w].pose.position();
        for (const int i : others)
        {
            if (!balls_[i].moves || !box[w].overlaps(box[i])) continue;
            if
            (
                plane
             && n.dot(balls_[i].centre - p0) - balls_[i].radius > dropBeyond
             && !carried(std::make_pair(w, i))
            )
            {
                ++work.droppedBySpheres;
                continue;
            }
            pairs.emplace_back(w, i);
        }
    }
    // Both parts are sorted: merge them
    const size_t nWallPairs = pairs.size();
    for (const auto& p : neighbours_)
    {
        const int i = p.first, j = p.second;
        if (!balls_[i].moves && !balls_[j].moves) continue;
        if (!imagesOverlap(box[i], box[j], periodic)) continue;
        const vec3& ci = balls_[i].centre;
        const vec3& cj = balls_[j].centre;
        const double spheres =
            (cj + periodic.nearestShift(ci, cj) - ci).norm()
          - balls_[i].radius - balls_[j].radius;
        if (spheres > dropBeyond && !carried(p))
        {
            ++work.droppedBySpheres;
            continue;
        }
        pairs.push_back(p);
    }
    std::inplace_merge(pairs.begin(), pairs.begin() + nWallPairs, pairs.end());
    return pairs;
}

} // End namespace immersedDEM
