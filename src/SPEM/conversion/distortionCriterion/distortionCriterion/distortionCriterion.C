#include "distortionCriterion.H"

namespace Foam
{
    defineTypeNameAndDebug(distortionCriterion, 0);
    defineRunTimeSelectionTable(distortionCriterion, dictionary);
}


const Foam::word Foam::distortionCriterion::defaultCriterion
(
    "minInteriorAngle"
);
