#include "surgeFront.H"
#include "Time.H"
#include "addToRunTimeSelectionTable.H"

namespace Foam
{
namespace functionObjects
{
    defineTypeNameAndDebug(surgeFront, 0);
    addToRunTimeSelectionTable(functionObject, surgeFront, dictionary);
}
}


Foam::functionObjects::surgeFront::surgeFront
(
    const word& name,
    const Time& runTime,
    const dictionary& dict
)
:
    spemFunctionObject(name, runTime, dict, needs::particles)
{
    read(dict);
    writeColumns({"front", "height"});
}


bool Foam::functionObjects::surgeFront::read(const dictionary& dict)
{
    writeFile::read(dict);
    readPoint(dict, "origin", ox_, oy_);
    const vector d = dict.getOrDefault<vector>("direction", vector(1, 0, 0));
    const scalar len = std::hypot(d.x(), d.y());
    if (!(len > 0))
    {
        FatalIOErrorInFunction(dict)
            << "direction " << d << " has no component in the x-y plane"
            << exit(FatalIOError);
    }
    dx_ = d.x()/len;
    dy_ = d.y()/len;
    minDivR_ = dict.getOrDefault<scalar>("minDivR", 0.5);
    return true;
}


bool Foam::functionObjects::surgeFront::write()
{
    const spemModel& m = model();
    if (!m.hasElements()) particles();
    if (!writeToFile()) return true;

    // Upward: against gravity
    const scalar* g = m.gravity();
    const scalar gMag = std::hypot(g[0], g[1]);
    const scalar ux = gMag > 0 ? -g[0]/gMag : 0;
    const scalar uy = gMag > 0 ? -g[1]/gMag : 1;

    scalar front = -GREAT, height = -GREAT;
    const auto add = [&](const scalar x, const scalar y, const scalar h)
    {
        const scalar rx = x - ox_, ry = y - oy_;
        const scalar along = rx*dx_ + ry*dy_;
        front = max(front, along);
        if (along < h) height = max(height, rx*ux + ry*uy);
    };

    if (m.hasParticles())
    {
        const sphFluid& sph = m.particles();
        const particleSet& ps = sph.particles();
        for (label i = 0; i < ps.size(); ++i)
        {
            if (ps.kinds()[i] != particleSet::kind::fluid) continue;
            if (sph.divR()[i] < minDivR_) continue;
            add
            (
                ps.positions()[2*i], ps.positions()[2*i + 1],
                ps.smoothingLength()[i]
            );
        }
    }
    if (m.hasElements())
    {
        const elementModel& em = m.elements();
        const std::vector<scalar>& x = em.positions();
        for (label r = 0; r < em.regions().size(); ++r)
        {
            if (!em.hasMaterial(r) || !em.material(r).isFluid()) continue;
            for
            (
                label el = em.regions()[r].elemBegin;
                el < em.regions()[r].elemEnd;
                ++el
            )
            {
                const scalar h = std::sqrt(std::abs(em.elementArea()[el]));
                for (label a = 0; a < 3; ++a)
                {
                    const label n = em.elementNodes()[3*el + a];
                    add(x[2*n], x[2*n + 1], h);
                }
            }
        }
    }

    OFstream& os = file();
    os  << time_.value() << tab;
    if (front > -GREAT) os << front; else os << "NaN";
    os  << tab;
    if (height > -GREAT) os << height; else os << "NaN";
    os  << endl;
    return true;
}


// ************************************************************************* //
