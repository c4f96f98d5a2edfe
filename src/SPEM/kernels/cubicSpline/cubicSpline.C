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


Foam::scalar Foam::cubicSpline::W(const scalar r, const scalar h) const
{
    return sphKernels::cubicSpline::W(r, h);
}


Foam::scalar Foam::cubicSpline::F(const scalar r, const scalar h) const
{
    return sphKernels::cubicSpline::F(r, h);
}


Foam::scalar Foam::cubicSpline::support() const
{
    return sphKernels::cubicSpline::support;
}
