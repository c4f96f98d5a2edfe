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
