#include "pressureProbe.H"
#include "spemModel.H"
#include "Time.H"
#include "addToRunTimeSelectionTable.H"

#include <limits>

namespace Foam
{
namespace functionObjects
{
    defineTypeNameAndDebug(pressureProbe, 0);
    addToRunTimeSelectionTable(functionObject, pressureProbe, dictionary);
}
}


Foam::functionObjects::pressureProbe::pressureProbe
(
    const word& name,
    const Time& runTime,
    const dictionary& dict
)
:
    spemFunctionObject(name, runTime, dict),
    normalOffset_(0),
    body_(-1),
    checked_(false)
{
    read(dict);
    wordList columns(locations_.size()/2);
    forAll(columns, i) columns[i] = "p" + Foam::name(i);
    if (writeToFile())
    {
        OFstream& os = file();
        for (label i = 0; i < columns.size(); ++i)
        {
            os  << "# Probe " << i << " (" << Foam::name(locations_[2*i])
                << ' ' << Foam::name(locations_[2*i + 1]) << ')';
            if (!bodyName_.empty())
            {
                os  << " at t = 0, moving with body " << bodyName_
                    << ", offset " << normalOffset_
                    << " m along its outward normal";
            }
            os  << nl;
        }
    }
    writeColumns(columns);
}


bool Foam::functionObjects::pressureProbe::read(const dictionary& dict)
{
    writeFile::read(dict);
    const List<vector> points = dict.get<List<vector>>("probeLocations");
    if (points.empty())
    {
        FatalIOErrorInFunction(dict)
            << "probeLocations is empty" << exit(FatalIOError);
    }
    locations_.resize(2*points.size());
    forAll(points, i)
    {
        locations_[2*i] = points[i].x();
        locations_[2*i + 1] = points[i].y();
    }
    bodyName_ = dict.getOrDefault<word>("body", word::null);
    normalOffset_ = dict.getOrDefault<scalar>("normalOffset", 0);
    if (bodyName_.empty() && dict.found("normalOffset"))
    {
        FatalIOErrorInFunction(dict)
            << "normalOffset is the distance from the surface of a rigid"
            << " body: it needs the keyword body" << exit(FatalIOError);
    }
    body_ = -1;
    return true;
}


void Foam::functionObjects::pressureProbe::findBody()
{
    if (bodyName_.empty() || body_ >= 0) return;

    const rigidBodies& bodies = model().bodies();
    const label b = bodies.findBody(bodyName_);
    if (b < 0)
    {
        wordList names(bodies.size());
        forAll(bodies, i) names[i] = bodies[i].name();
        FatalErrorInFunction
            << "Function object " << name() << ": no rigid body "
            << bodyName_ << " in constant/rigidBodyProperties; bodies: "
            << names << exit(FatalError);
    }

    // The offset along the outward normal at the closest surface point, in
    // the reference configuration: the offset point is body-fixed too
    const rigidBodyShape& shape = bodies[b].shape();
    referenceLocations_ = locations_;
    for (size_t i = 0; i < locations_.size()/2; ++i)
    {
        vector2D closest, normal;
        shape.signedDistance
        (
            locations_[2*i], locations_[2*i + 1], closest, normal
        );
        referenceLocations_[2*i] += normalOffset_*normal.x();
        referenceLocations_[2*i + 1] += normalOffset_*normal.y();
    }
    body_ = b;
}


const std::vector<Foam::scalar>&
Foam::functionObjects::pressureProbe::currentLocations()
{
    if (bodyName_.empty()) return locations_;
    findBody();
    model().bodies()[body_].toCurrent(referenceLocations_, current_);
    return current_;
}


void Foam::functionObjects::pressureProbe::checkInsideMesh()
{
    if (checked_) return;
    checked_ = true;
    const triMesh& mesh = model().mesh();
    const std::vector<scalar>& X = mesh.points();
    const std::vector<label>& tri = mesh.triangles();
    const std::vector<scalar>& probes =
        bodyName_.empty() ? locations_ : referenceLocations_;
    for (size_t i = 0; i < probes.size()/2; ++i)
    {
        const scalar px = probes[2*i], py = probes[2*i + 1];
        bool inside = false;
        for (label t = 0; t < mesh.nTriangles() && !inside; ++t)
        {
            // Barycentric coordinates, with a round-off margin for a probe
            // on a wall
            const label* n = &tri[3*t];
            const scalar x0 = X[2*n[0]], y0 = X[2*n[0] + 1];
            const scalar ax = X[2*n[1]] - x0, ay = X[2*n[1] + 1] - y0;
            const scalar bx = X[2*n[2]] - x0, by = X[2*n[2] + 1] - y0;
            const scalar det = ax*by - ay*bx;
            const scalar s = ((px - x0)*by - (py - y0)*bx)/det;
            const scalar r = (ax*(py - y0) - ay*(px - x0))/det;
            const scalar tol = 1e-9;
            inside = s >= -tol && r >= -tol && s + r <= 1 + tol;
        }
        if (!inside)
        {
            FatalErrorInFunction
                << "Function object " << name() << ": probe " << label(i)
                << " of probeLocations, (" << px << ' ' << py << ")"
                << (bodyName_.empty() ? "" : " (with its normalOffset)")
                << ", is outside the mesh: it would read nothing (NaN)"
                << " at every write" << exit(FatalError);
        }
    }
}


bool Foam::functionObjects::pressureProbe::execute()
{
    findBody();
    checkInsideMesh();
    return spemFunctionObject::execute();
}


bool Foam::functionObjects::pressureProbe::write()
{
    if (!writeToFile()) return true;

    OFstream& os = file();
    os  << time_.value();
    const spemModel& m = model();
    const std::vector<scalar>& locations = currentLocations();
    // The elements holding the probes, in one look-up (one check of the
    // locator's grid for all of them)
    std::vector<label> holders(locations.size()/2, -1);
    std::vector<scalar> bary;
    if (m.hasElements()) m.elements().locate(locations, holders, bary);
    for (size_t i = 0; i < locations.size()/2; ++i)
    {
        const scalar px = locations[2*i], py = locations[2*i + 1];
        scalar p = 0;
        if (holders[i] >= 0)
        {
            os  << tab << elementPressure(m.elements(), holders[i]);
        }
        // Kernel (Shepard) interpolation from the particles, wall particles
        // included so that a probe on a wall reads the wall pressure
        else if
        (
            m.hasParticles() && m.particles().interpolatePressure(px, py, p)
        )
        {
            os  << tab << p;
        }
        else
        {
            os  << tab << "NaN";
        }
    }
    os  << endl;
    return true;
}


Foam::scalar Foam::functionObjects::pressureProbe::elementPressure
(
    const elementModel& em,
    const label el
)
{
    scalar p = 0;
    for (label j = 0; j < 3; ++j)
    {
        const label k = em.elementDomains()[3*el + j];
        scalar sigma[6], pk;
        em.domainCauchyStress(k, k + 1, sigma, &pk);
        p += pk/3;
    }
    return p;
}
