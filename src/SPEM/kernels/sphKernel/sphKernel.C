#include "sphKernel.H"

#include <cstdlib>

namespace Foam
{
    defineTypeNameAndDebug(sphKernel, 0);
    defineRunTimeSelectionTable(sphKernel, dictionary);
}


const Foam::word Foam::sphKernel::defaultKernel
(
    Foam::sphKernels::WendlandC2::name
);


Foam::sphKernel::sphKernel(const kernelKind kind)
:
    kind_(kind)
{}


void Foam::sphKernel::unknownKind(const kernelKind kind)
{
    FatalErrorInFunction
        << "No kernel struct for kernel kind " << int(kind)
        << ": a kernel was added without a case in sphKernel::visit"
        << exit(FatalError);

    // Not reached: FatalError either exits or throws
    std::abort();
}
