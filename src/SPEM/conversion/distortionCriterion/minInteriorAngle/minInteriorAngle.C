#include "minInteriorAngle.H"
#include "addToRunTimeSelectionTable.H"
#include "unitConversion.H"

#include <cmath>

namespace Foam
{
    defineTypeNameAndDebug(minInteriorAngle, 0);
    addToRunTimeSelectionTable
    (
        distortionCriterion,
        minInteriorAngle,
        dictionary
    );
}


Foam::scalar Foam::minInteriorAngle::readLimit
(
    const dictionary& conversionDict
)
{
    const scalar limit =
        conversionDict.getOrDefault<scalar>("minInteriorAngle", defaultLimit);

    // Written to reject NaN as well
    if (!(limit > 0 && limit < 60))
    {
        FatalIOErrorInFunction(conversionDict)
            << "Entry 'minInteriorAngle " << limit << "' of "
            << conversionDict.name() << " must lie in (0, 60) degrees"
            << " (60: every triangle, even equilateral, would be distorted);"
            << " the paper uses " << defaultLimit << exit(FatalIOError);
    }
    return limit;
}


Foam::minInteriorAngle::minInteriorAngle(const dictionary& conversionDict)
:
    distortionCriterionModel(),
    limit_(readLimit(conversionDict)),
    cotLimit_(1/std::tan(degToRad(limit_)))
{}


void Foam::minInteriorAngle::describe(Ostream& os) const
{
    os  << "minInteriorAngle < " << limit_ << " deg";
}
