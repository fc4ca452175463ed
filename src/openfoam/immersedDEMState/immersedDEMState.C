#include "immersedDEMState.H"
#include "dictionaryChecks.H"
#include "sphereShape.H"
#include "triangleMeshShape.H"
#include "coreError.H"
#include "unitConversion.H"

namespace Foam
{
    defineTypeNameAndDebug(immersedDEMState, 0);
}


namespace
{

immersedDEM::vec3 toCore(const Foam::vector& v)
{
    return immersedDEM::vec3(v.x(), v.y(), v.z());
}

} // End anonymous namespace


void Foam::immersedDEMState::readMaterials()
{
    const dictionary& all = properties_.subDict("materials");
    for (const entry& e : all)
    {
        const dictionary& d = immersedDEMChecks::subDictEntry(all, e, "material properties");
        immersedDEMChecks::allowOnly(d, {"youngsModulus", "poissonsRatio"});
        materials_.push_back
        ({
            e.keyword(),
            immersedDEMChecks::positive(d, "youngsModulus"),
            immersedDEMChecks::inRange(d, "poissonsRatio", 0, 0.5)
        });
    }
    if (materials_.empty())
    {
        FatalIOErrorInFunction(all)
            << "No material in " << all.name() << exit(FatalIOError);
    }
}


void Foam::immersedDEMState::readBodies()
{
    const dictionary& all = properties_.subDict("bodies");
    const fileName surfaceDir = mesh_.time().constant()/"triSurface";

    for (const entry& e : all)
    {
        const dictionary& d = immersedDEMChecks::subDictEntry(all, e, "a body's description");
        body b;
        b.name = e.keyword();

        const word shapeType = immersedDEMChecks::oneOf(d, "shape", {"sphere", "triangleMesh"});
        wordList allowed
        {
            "shape", "density", "material", "position", "rotationAxis",
            "rotationAngle", "velocity", "angularVelocity", "motion"
        };
        if (shapeType == "sphere")
        {
            allowed.append("radius");
            immersedDEMChecks::allowOnly(d, allowed);
            b.geometry.reset
            (
                new immersedDEM::sphereShape(immersedDEMChecks::positive(d, "radius"))
            );
        }
        else
        {
            allowed.append(wordList{"file", "scale", "checkSelfIntersection"});
            immersedDEMChecks::allowOnly(d, allowed);
            const fileName file = surfaceDir/d.get<fileName>("file");
            const scalar scale = immersedDEMChecks::positiveOrDefault(d, "scale", 1);
            try
            {
                auto s = immersedDEM::triangleMeshShape::fromFile
                (
                    file, scale, d.getOrDefault<bool>("checkSelfIntersection", true)
                );
                for (const std::string& w : s->warnings())
                {
                    WarningInFunction << "Body " << b.name << ": " << w.c_str() << endl;
                }
                b.geometry = std::move(s);
            }
            catch (const immersedDEM::coreError& err)
            {
                FatalIOErrorInFunction(d)
                    << "Body '" << b.name << "', keyword 'file' in " << d.name()
                    << ":" << nl << "    " << err.what() << nl
                    << exit(FatalIOError);
            }
        }

        b.density = immersedDEMChecks::positive(d, "density");

        const word mat = d.get<word>("material");
        b.material = -1;
        wordList names;
        for (size_t i = 0; i < materials_.size(); ++i)
        {
            names.append(materials_[i].name);
            if (materials_[i].name == mat) b.material = label(i);
        }
        if (b.material < 0)
        {
            FatalIOErrorInFunction(d)
                << "Unknown material '" << mat << "' for body '" << b.name
                << "' in " << d.name() << nl
                << "Valid materials: " << names << nl
                << exit(FatalIOError);
        }

        const vector axis = d.getOrDefault<vector>("rotationAxis", vector(0, 0, 1));
        if (mag(axis) == 0)
        {
            FatalIOErrorInFunction(d)
                << "Keyword 'rotationAxis' in " << d.name() << " is a zero vector"
                << exit(FatalIOError);
        }
        const scalar angle = degToRad(d.getOrDefault<scalar>("rotationAngle", 0));
        // The rotation turns the shape as given in its file about its centroid
        const immersedDEM::quat R = immersedDEM::bodyPose::axisAngle(toCore(axis), angle);
        b.pose = immersedDEM::bodyPose
        (
            toCore(d.get<vector>("position")),
            R*b.geometry->bodyInFile().orientation()
        );
        b.velocity = d.getOrDefault<vector>("velocity", Zero);
        b.angularVelocity = d.getOrDefault<vector>("angularVelocity", Zero);
        b.motion = immersedDEMChecks::oneOfOrDefault
        (
            d, "motion", {"free", "fixed", "prescribed"}, "free"
        );

        const scalar V = b.geometry->volume();
        const immersedDEM::vec3 J = b.density*b.geometry->principalMoments();
        Info<< "    body " << b.name << ": " << shapeType
            << ", volume " << V << " m3, mass " << b.density*V
            << " kg, principal moments (" << J.x() << ' ' << J.y() << ' ' << J.z()
            << ") kg m2" << endl;

        bodies_.push_back(std::move(b));
    }
}


Foam::immersedDEMState::immersedDEMState(const fvMesh& mesh)
:
    regIOobject
    (
        IOobject
        (
            typeName,
            mesh.time().constant(),
            mesh,
            IOobject::NO_READ,
            IOobject::NO_WRITE
        )
    ),
    mesh_(mesh),
    properties_
    (
        IOobject
        (
            "immersedDEMProperties",
            mesh.time().constant(),
            mesh,
            IOobject::MUST_READ,
            IOobject::NO_WRITE
        )
    ),
    lambda_
    (
        IOobject("lambda", mesh.time().timeName(), mesh, IOobject::NO_READ, IOobject::AUTO_WRITE),
        mesh,
        dimensionedScalar(dimless, Zero)
    ),
    Uib_
    (
        IOobject("Uib", mesh.time().timeName(), mesh, IOobject::NO_READ, IOobject::AUTO_WRITE),
        mesh,
        dimensionedVector(dimVelocity, Zero)
    )
{
    immersedDEMChecks::allowOnly(properties_, {"materials", "bodies"});
    Info<< "immersedDEM: reading " << properties_.objectPath() << endl;
    readMaterials();
    readBodies();
    Info<< "immersedDEM: " << bodies_.size() << " bodies, "
        << materials_.size() << " materials" << nl << endl;
}


Foam::immersedDEMState& Foam::immersedDEMState::New(const fvMesh& mesh)
{
    if (!mesh.foundObject<immersedDEMState>(typeName))
    {
        immersedDEMState* s = new immersedDEMState(mesh);
        s->store();
    }
    return mesh.lookupObjectRef<immersedDEMState>(typeName);
}
