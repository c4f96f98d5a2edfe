#include "WendlandC2.H"
#include "addToRunTimeSelectionTable.H"

namespace Foam
{
    defineTypeNameAndDebug(WendlandC2, 0);
    addToRunTimeSelectionTable(sphKernel, WendlandC2, dictionary);
}


Foam::WendlandC2::WendlandC2(const dictionary& schemesDict)
:
    sphKernel(kernelKind::WendlandC2)
{}


Foam::scalar Foam::WendlandC2::W(const scalar r, const scalar h) const
{
    return sphKernels::WendlandC2::W(r, h);
}


Foam::scalar Foam::WendlandC2::F(const scalar r, const scalar h) const
{
    return sphKernels::WendlandC2::F(r, h);
}


Foam::scalar Foam::WendlandC2::support() const
{
    return sphKernels::WendlandC2::support;
}
