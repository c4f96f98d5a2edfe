#include "spemMethod.H"

// * * * * * * * * * * * * * * * * Selectors * * * * * * * * * * * * * * * * //

Foam::autoPtr<Foam::spemMethod> Foam::spemMethod::New
(
    const spemCase& c,
    PtrList<spemMaterial>& materials
)
{
    const word methodName(c.schemes.get<word>("method"));

    // The paper's multi-resolution method derives from SPEM (next version)
    const word notYet("multiResolutionSPEM");
    if (methodName == notYet)
    {
        FatalIOErrorInFunction(c.schemes)
            << "method " << methodName
            << " is not available in this version; use SPEM or SPH"
            << exit(FatalIOError);
    }

    if (!dictionaryConstructorTablePtr_)
    {
        FatalErrorInFunction
            << "No solution methods registered: is libSPEM linked with"
            << " --no-as-needed?" << exit(FatalError);
    }
    auto cstrIter = dictionaryConstructorTablePtr_->cfind(methodName);
    if (!cstrIter.found())
    {
        wordList valid(dictionaryConstructorTablePtr_->sortedToc());
        valid.append(notYet);
        FatalIOErrorInFunction(c.schemes)
            << "Unknown method " << methodName << nl << nl
            << "Valid methods :" << nl << valid
            << exit(FatalIOError);
    }
    return cstrIter()(c, materials);
}


// ************************************************************************* //
