#include "pressureProbe.H"
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
    spemFunctionObject(name, runTime, dict)
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
                << ' ' << Foam::name(locations_[2*i + 1]) << ')' << nl;
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
    return true;
}


bool Foam::functionObjects::pressureProbe::write()
{
    if (!writeToFile()) return true;

    OFstream& os = file();
    os  << time_.value();
    const spemModel& m = model();
    for (size_t i = 0; i < locations_.size()/2; ++i)
    {
        const scalar px = locations_[2*i], py = locations_[2*i + 1];
        scalar p = 0;
        if (m.hasElements() && elementPressure(m.elements(), px, py, p))
        {
            os  << tab << p;
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


bool Foam::functionObjects::pressureProbe::elementPressure
(
    const elementModel& em,
    const scalar x,
    const scalar y,
    scalar& p
)
{
    scalar w[3];
    const label el = em.locate(x, y, false, w);
    if (el < 0) return false;
    p = 0;
    for (label j = 0; j < 3; ++j)
    {
        const label k = em.elementDomains()[3*el + j];
        scalar sigma[6], pk;
        em.domainCauchyStress(k, k + 1, sigma, &pk);
        p += pk/3;
    }
    return true;
}
