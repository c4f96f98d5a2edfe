#include "cubicSpline.H"
#include "addToRunTimeSelectionTable.H"

namespace Foam
{
    defineTypeNameAndDebug(cubicSpline, 0);
    addToRunTimeSelectionTable(sphKernel, cubicSpline, dictionary);
}


Foam::cubicSpline::cubicSpline(const dictionary& schemesDict)
:
    sphKernel(kernelKind::cubicSpline)
{}
