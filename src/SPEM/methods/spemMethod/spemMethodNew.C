#include "spemMethod.H"

// * * * * * * * * * * * * * * * * Selectors * * * * * * * * * * * * * * * * //

Foam::autoPtr<Foam::spemMethod> Foam::spemMethod::New
(
    const spemCase& c,
    PtrList<spemMaterial>& materials
)
{
    const word methodName(c.schemes.get<word>("method"));

    if (!dictionaryConstructorTablePtr_)
    {
        FatalErrorInFunction
            << "No solution methods registered: is libSPEM linked with"
            << " --no-as-needed?" << exit(FatalError);
    }
    auto cstrIter = dictionaryConstructorTablePtr_->cfind(methodName);
    if (!cstrIter.found())
    {
        const wordList valid(dictionaryConstructorTablePtr_->sortedToc());
        FatalIOErrorInFunction(c.schemes)
            << "Unknown method " << methodName << nl << nl
            << "Valid methods :" << nl << valid
            << exit(FatalIOError);
    }
    return cstrIter()(c, materials);
}


// ************************************************************************* //
