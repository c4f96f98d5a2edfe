#include "circleRegion.H"
#include "checkKeywords.H"
#include "vector.H"
#include "addToRunTimeSelectionTable.H"

namespace Foam
{
    defineTypeNameAndDebug(circleRegion, 0);
    addToRunTimeSelectionTable(presetParticleRegion, circleRegion, dictionary);
}


Foam::circleRegion::circleRegion
(
    const word& name,
    const dictionary& dict,
    const triMesh& mesh,
    const bodySurfaces& bodies
)
:
    presetParticleRegion(name)
{
    checkKeywords(dict, {"type", "centre", "radius"});

    const vector centre(dict.get<vector>("centre"));
    xCentre_ = centre.x();
    yCentre_ = centre.y();
    radius_ = readPositive(dict, "radius");
}


bool Foam::circleRegion::contains(const scalar x, const scalar y) const
{
    const scalar dx = x - xCentre_, dy = y - yCentre_;
    return dx*dx + dy*dy <= radius_*radius_;
}
