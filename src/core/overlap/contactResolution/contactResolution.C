#include "contactResolution.H"
#include "virtualMeshOverlap.H"
#include "halfSpaceShape.H"
#include "sphereShape.H"
#include "coreError.H"
#include "overlapEngine.H"

#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <vector>

namespace immersedDEM
{

namespace
{
    // The point of s (body frame) farthest along the unit vector u
    vec3 supportPoint(const shape& s, const triangleSoup& surface, const vec3& u)
    {
        if (const auto* sp = shapeAs<sphereShape>(s))
        {
            return sp->radius()*u;
        }
        vec3 best = vec3::Zero();
        double far = -std::numeric_limits<double>::max();
        for (const vec3& p : surface.points)
        {
            if (p.dot(u) > far)
            {
                far = p.dot(u);
                best = p;
            }
        }
        return best;
    }

    // The candidates: base cells d/5, levels 0 to 6 (the finest leaf d/320,
    // the former default's: d/20 at level 4)
    const double candidateCells = 5;
    const int finestLevel = 6;

    // The reference engine of a pair: exact for two meshes (CGAL) and for
    // two spheres (the lens), else the virtual mesh one level finer than
    // the finest candidate
    std::unique_ptr<overlapEngine> referenceOf(const shape& a, const shape& b, std::string& name)
    {
        const bool meshes =
            a.shapeKind() == shape::kind::triangleMesh && b.shapeKind() == shape::kind::triangleMesh;
        const bool spheres =
            a.shapeKind() == shape::kind::sphere && b.shapeKind() == shape::kind::sphere;
        name =
            meshes ? "the exact overlap"
          : spheres ? "the analytic lens"
          : "level " + std::to_string(finestLevel + 1);
        return overlapEngine::New(meshes ? "exact" : spheres ? "sphere" : "virtualMesh");
    }

    bool isWall(const shape& s)
    {
        return s.shapeKind() == shape::kind::halfSpace || s.shapeKind() == shape::kind::wallMesh;
    }

    // The volume and the queries of every pose at one resolution; a pose
    // the engine cannot measure (beyond its cell budget, or CGAL failing
    // on a degenerate pose) gets -1. The octree itself is measured, also
    // for convex pairs (convexExact off)
    void measure
    (
        const overlapEngine& e, const shape& a, const shape& B,
        const std::vector<contactResolution::posePair>& poses,
        const overlapSettings& base, double h, int level,
        std::vector<double>& V, long& queries
    )
    {
        overlapSettings s = base;
        s.h = h;
        s.level = level;
        s.convexExact = false;
        V.assign(poses.size(), 0);
        queries = 0;
        for (size_t i = 0; i < poses.size(); ++i)
        {
            try
            {
                const contactGeometry g = e.evaluate(a, poses[i].A, B, poses[i].B, s);
                V[i] = g.volume();
                queries += g.queries;
            }
            catch (const coreError&)
            {
                V[i] = -1;
            }
        }
    }

    // Over the poses the reference measured (a pose the candidate could
    // not measure: no bound)
    double largestRelative(const std::vector<double>& V, const std::vector<double>& Vref)
    {
        double error = 0;
        for (size_t i = 0; i < V.size(); ++i)
        {
            if (!(Vref[i] > 0)) continue;
            error =
                V[i] < 0
              ? std::numeric_limits<double>::max()
              : std::max(error, std::abs(V[i] - Vref[i])/Vref[i]);
        }
        return error;
    }
}


std::vector<contactResolution::posePair> contactResolution::posesOf
(
    const shape& A, const shape& B, double depth, int set
)
{
    std::vector<vec3> directions;
    std::vector<quat> turns;
    std::vector<double> depths;
    if (set == 0)
    {
        directions = {vec3(0, 0, 1), vec3(1, 1, 1).normalized(), vec3(-1, 2, 0.5).normalized()};
        turns =
        {
            quat::Identity(),
            bodyPose::axisAngle(vec3(1, 2, 3), 0.7),
            bodyPose::axisAngle(vec3(-2, 1, 1), 2.1)
        };
        depths = {depth, 0.25*depth};
    }
    else
    {
        // Directions on a golden-angle spiral, turns about them, depths
        // between the calibration's
        for (int k = 0; k < 3; ++k)
        {
            const double i = 3*set + k;
            const double z = 1 - 2*std::fmod(0.618034*i + 0.1, 1.0);
            const double phi = 2.399963*i;
            const double r = std::sqrt(std::max(0.0, 1 - z*z));
            directions.push_back(vec3(r*std::cos(phi), r*std::sin(phi), z));
            turns.push_back(bodyPose::axisAngle(vec3(std::sin(1.3*i), std::cos(0.7*i), 0.5), 0.9*i));
        }
        depths = {0.7*depth, 0.4*depth};
    }

    const bool plane = isWall(A);
    const triangleSoup surfA = plane ? triangleSoup() : A.surface();
    const triangleSoup surfB = B.surface();
    std::vector<posePair> result;
    for (size_t k = 0; k < directions.size(); ++k)
    {
        // B pressed tip first into A along u: A's farthest point along u
        // (the plane's origin), B's farthest along -u
        const vec3& u = directions[k];
        const bodyPose pB0(vec3::Zero(), turns[k]);
        const vec3 a = plane ? vec3::Zero() : supportPoint(A, surfA, u);
        const vec3 b = pB0.vectorToWorld(supportPoint(B, surfB, pB0.vectorToBody(-u)));
        for (const double delta : depths)
        {
            posePair p;
            p.A = plane ? halfSpaceShape::poseOf(vec3::Zero(), u) : bodyPose();
            p.B = bodyPose(a - delta*u - b, turns[k]);
            result.push_back(p);
        }
    }
    return result;
}


double contactResolution::largestError
(
    const shape& A, const shape& B, double d, const std::vector<posePair>& poses,
    const overlapSettings& settings, std::string* reference
)
{
    const halfSpaceShape halfSpace;
    const shape& a = isWall(A) ? static_cast<const shape&>(halfSpace) : A;
    std::string name;
    const std::unique_ptr<overlapEngine> referenceEngine = referenceOf(a, B, name);
    if (reference) *reference = name;
    std::vector<double> Vref, V;
    long queries = 0;
    measure(*referenceEngine, a, B, poses, settings, d/candidateCells, finestLevel + 1, Vref, queries);
    measure(virtualMeshOverlap(), a, B, poses, settings, settings.h, settings.level, V, queries);
    return largestRelative(V, Vref);
}


contactResolution contactResolution::calibrate
(
    const shape& A, const shape& B, double d, double depth,
    const overlapSettings& base, double tolerance
)
{
    if (!(d > 0) || !(tolerance > 0) || !(depth > 0))
    {
        throw coreError
        (
            "contactResolution: the diameter, the depth and the tolerance must be positive"
        );
    }
    const halfSpaceShape halfSpace;
    const shape& a = isWall(A) ? static_cast<const shape&>(halfSpace) : A;
    const std::vector<posePair> set = posesOf(A, B, depth, 0);

    contactResolution fallback;
    const std::unique_ptr<overlapEngine> referenceEngine = referenceOf(a, B, fallback.reference);
    const virtualMeshOverlap engine;
    fallback.cellsPerDiameter = candidateCells;
    fallback.level = finestLevel;
    fallback.met = false;
    fallback.depth = depth/d;

    std::vector<double> Vref;
    long queries = 0;
    measure(*referenceEngine, a, B, set, base, d/candidateCells, finestLevel + 1, Vref, queries);
    for (const double v : Vref)
    {
        if (v > 0) ++fallback.poses;
    }
    if (fallback.poses == 0)
    {
        // No pose overlaps (a shape the tip placement cannot press in)
        return fallback;
    }

    // The coarsest candidate within the tolerance whose next finer level
    // is within it too (the error does not fall steadily with the level
    // where the leaves are about a facet's size: a coarse level may be
    // close by chance on six poses)
    std::vector<double> errors;
    std::vector<long> levelQueries;
    for (int level = 0; level <= finestLevel; ++level)
    {
        std::vector<double> V;
        measure(engine, a, B, set, base, d/candidateCells, level, V, queries);
        const double error = largestRelative(V, Vref);
        errors.push_back(error);
        levelQueries.push_back(queries);
        fallback.defaultQueries = queries;
        const int previous = level - 1;
        const bool previousMet = previous >= 0 && errors[previous] <= tolerance;
        if ((previousMet || level == finestLevel) && error <= tolerance)
        {
            const int l = previousMet ? previous : level;
            contactResolution r = fallback;
            r.level = l;
            r.error = errors[l];
            r.queries = levelQueries[l];
            r.met = true;
            if (level < finestLevel)
            {
                std::vector<double> W;
                measure(engine, a, B, set, base, d/candidateCells, finestLevel, W, queries);
                r.defaultQueries = queries;
            }
            return r;
        }
    }
    // None: the finest, with its error
    fallback.error = errors.back();
    fallback.queries = levelQueries.back();
    return fallback;
}


std::string contactResolution::describe() const
{
    const double leaf = cellsPerDiameter*double(1L << level);
    char text[400];
    if (!met)
    {
        std::snprintf
        (
            text, sizeof(text),
            "cellSize d/%g, level %d (finest leaf d/%g, as before: no coarser level holds"
            " the tolerance); at %.2g and %.2g d deep (a collision at referenceSpeed) its"
            " volume differs by up to %.3g%% from %s over %d poses",
            cellsPerDiameter, level, leaf, depth, 0.25*depth, 100*error, reference.c_str(),
            poses
        );
        return text;
    }
    std::snprintf
    (
        text, sizeof(text),
        "cellSize d/%g, level %d (finest leaf d/%g): volume within %.2g%% of %s over %d"
        " poses %.2g and %.2g d deep; %.3g times fewer queries than the finest leaf d/320"
        " (the former default d/20, level 4)",
        cellsPerDiameter, level, leaf, 100*error, reference.c_str(), poses,
        depth, 0.25*depth,
        queries > 0 ? double(defaultQueries)/double(queries) : 1.0
    );
    return text;
}

} // End namespace immersedDEM
