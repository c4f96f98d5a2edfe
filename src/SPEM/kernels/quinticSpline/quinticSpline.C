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


Foam::scalar Foam::quinticSpline::W(const scalar r, const scalar h) const
{
    return sphKernels::quinticSpline::W(r, h);
}


Foam::scalar Foam::quinticSpline::F(const scalar r, const scalar h) const
{
    return sphKernels::quinticSpline::F(r, h);
}


Foam::scalar Foam::quinticSpline::support() const
{
    return sphKernels::quinticSpline::support;
}
