#include "quinticSpline.H"
#include "addToRunTimeSelectionTable.H"

namespace Foam
{
    defineTypeNameAndDebug(quinticSpline, 0);
    addToRunTimeSelectionTable(sphKernel, quinticSpline, dictionary);
}


Foam::quinticSpline::quinticSpline(const dictionary& schemesDict)
:
    sphKernel(kernelKind::quinticSpline)
{}
