#include "noDistortion.H"
#include "addToRunTimeSelectionTable.H"

namespace Foam
{
    defineTypeNameAndDebug(noDistortion, 0);
    addToRunTimeSelectionTable(distortionCriterion, noDistortion, dictionary);
}


void Foam::noDistortion::describe(Ostream& os) const
{
    os  << "none (no conversion at run time)";
}


// ************************************************************************* //
