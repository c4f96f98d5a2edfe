#include "rigidBodyShape.H"

Foam::autoPtr<Foam::rigidBodyShape> Foam::rigidBodyShape::New
(
    const dictionary& dict
)
{
    const word shapeType(dict.get<word>("shape"));

    if (!dictionaryConstructorTablePtr_)
    {
        FatalErrorInFunction
            << "The rigid body shape selection table is empty: libSPEM"
            << " was not loaded (linked with --as-needed?)"
            << exit(FatalError);
    }

    auto cstrIter = dictionaryConstructorTablePtr_->cfind(shapeType);

    if (!cstrIter.found())
    {
        FatalIOErrorInLookup
        (
            dict,
            "shape",
            shapeType,
            *dictionaryConstructorTablePtr_
        ) << exit(FatalIOError);
    }

    return cstrIter()(dict);
}
