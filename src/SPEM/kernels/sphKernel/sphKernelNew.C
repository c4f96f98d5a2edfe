#include "sphKernel.H"

Foam::autoPtr<Foam::sphKernel> Foam::sphKernel::New
(
    const dictionary& schemesDict
)
{
    const word kernelType
    (
        schemesDict.getOrDefault<word>("kernel", defaultKernel)
    );

    if (!dictionaryConstructorTablePtr_)
    {
        FatalErrorInFunction
            << "The SPH kernel selection table is empty: libSPEM was not"
            << " loaded (linked with --as-needed?)" << exit(FatalError);
    }

    auto cstrIter = dictionaryConstructorTablePtr_->cfind(kernelType);

    if (!cstrIter.found())
    {
        FatalIOErrorInLookup
        (
            schemesDict,
            "kernel",
            kernelType,
            *dictionaryConstructorTablePtr_
        ) << exit(FatalIOError);
    }

    return cstrIter()(schemesDict);
}
