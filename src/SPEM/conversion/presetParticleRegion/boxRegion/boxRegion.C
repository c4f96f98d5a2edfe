#include "boxRegion.H"
#include "checkKeywords.H"
#include "vector.H"
#include "addToRunTimeSelectionTable.H"

namespace Foam
{
    defineTypeNameAndDebug(boxRegion, 0);
    addToRunTimeSelectionTable(presetParticleRegion, boxRegion, dictionary);
}


Foam::boxRegion::boxRegion
(
    const word& name,
    const dictionary& dict,
    const triMesh& mesh,
    const bodySurfaces& bodies
)
:
    presetParticleRegion(name)
{
    checkKeywords(dict, {"type", "min", "max"});

    const vector lower(dict.get<vector>("min"));
    const vector upper(dict.get<vector>("max"));
    xMin_ = lower.x();
    yMin_ = lower.y();
    xMax_ = upper.x();
    yMax_ = upper.y();

    if (!(xMax_ > xMin_ && yMax_ > yMin_))
    {
        FatalIOErrorInFunction(dict)
            << "Entry 'max " << upper << "' of " << dict.name()
            << " must exceed 'min " << lower << "' in x and y"
            << exit(FatalIOError);
    }
}


bool Foam::boxRegion::contains(const scalar x, const scalar y) const
{
    return x >= xMin_ && x <= xMax_ && y >= yMin_ && y <= yMax_;
}
